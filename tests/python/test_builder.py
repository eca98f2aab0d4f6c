"""vtdyn.Builder (python/vtdyn/builder.c) against closed forms: models built by hand, solved by
Model.inverse and Model.contacts, and every error path.

* The paper's double link (two uniform links, 2 m and 100 kg, revolute about z, y up) built
  here: Model.inverse at 200 random states against the double pendulum's Lagrange equations
  tau = M(q) q'' + C(q, q') q' + G(q), written out below, to 1e-12 of the largest effort.
* A body of mass 1 with a payload of mass 2 at its centre of mass gives the efforts of one
  body of mass 3 and the summed inertia (1e-12); a free box built with its four bottom corners
  as frames stands on them with m g / 4 each (closed form, 1e-12).
* Errors: an unknown joint, drive or function kind and malformed arrays raise ValueError naming
  the argument; what the builder refuses raises vtdyn.Error with its status and message.
"""
import math

import numpy as np
import pytest

import vtdyn

G, L, M = 9.81, 2.0, 100.0
J = M * L * L / 12  # a uniform rod about its centre


def double_link(drives=()):
    """the paper's double link: link 1 pinned to the ground at the origin, link 2 to its tip;
    x along the links at q = 0, gravity -y (the builder's default)"""
    b = vtdyn.Builder()
    assert b.add_body(mass=M, inertia=(0, J, J), joint_child=(-L / 2, 0, 0), name="link1", joint_name="j1") == 1
    assert b.add_body(parent=1, joint="revolute", mass=M, inertia=[[0, 0, 0], [0, J, 0], [0, 0, J]],
                      joint_parent=(L / 2, 0, 0), joint_child=(-L / 2, 0, 0), name="link2", joint_name="j2") == 2
    for k, d in enumerate(drives):
        assert b.add_drive(**d) == k
    return b.build()


def lagrange(q, v, a):
    """the double pendulum of two uniform rods (length L, mass M, centre at L/2, inertia J about
    it), q1 the absolute angle of link 1 from x, q2 link 2's relative angle, gravity -y"""
    lc = L / 2
    c2, s2 = np.cos(q[..., 1]), np.sin(q[..., 1])
    m11 = 2 * J + M * lc * lc + M * (L * L + lc * lc + 2 * L * lc * c2)
    m12 = J + M * (lc * lc + L * lc * c2)
    m22 = J + M * lc * lc
    h = -M * L * lc * s2
    g1 = (M * lc + M * L) * G * np.cos(q[..., 0]) + M * lc * G * np.cos(q[..., 0] + q[..., 1])
    g2 = M * lc * G * np.cos(q[..., 0] + q[..., 1])
    t1 = m11 * a[..., 0] + m12 * a[..., 1] + h * (2 * v[..., 0] * v[..., 1] + v[..., 1] ** 2) + g1
    t2 = m12 * a[..., 0] + m22 * a[..., 1] - h * v[..., 0] ** 2 + g2
    return np.stack([t1, t2], axis=-1)


def test_double_link_inverse_against_lagrange():
    m = double_link()
    assert (m.nq, m.nv, m.nbody) == (2, 2, 2) and m.body_names == ("link1", "link2") and m.joint_names == ("j1", "j2")
    assert list(m.gravity) == [0.0, -G, 0.0] and list(m.masses) == [M, M] and not m.floating
    rng = np.random.default_rng(7)
    q, v, a = (rng.uniform(-3, 3, (200, 2)) for _ in range(3))
    r = m.inverse(q, v, a)
    ref = lagrange(q, v, a)
    assert np.abs(r.effort - ref).max() <= 1e-12 * np.abs(ref).max()


def test_payload_and_free_box():
    I1, I2 = np.diag([0.1, 0.2, 0.3]), np.array([[0.05, 0.01, 0.0], [0.01, 0.04, 0.0], [0.0, 0.0, 0.06]])
    one = vtdyn.Builder(gravity=(0, 0, -G))
    one.add_body(mass=3.0, inertia=I1 + I2, joint="universal", axis1=(0, 0, 1), axis2=(1, 0, 0), joint_child=(0.1, 0.2, 0.3))
    two = vtdyn.Builder(gravity=(0, 0, -G))
    two.add_body(mass=1.0, inertia=I1, joint="universal", axis1=(0, 0, 1), axis2=(1, 0, 0), joint_child=(0.1, 0.2, 0.3))
    assert two.add_payload(body=1, mass=2.0, inertia=I2) == 1
    rng = np.random.default_rng(8)
    q, v, a = (rng.uniform(-2, 2, (50, 2)) for _ in range(3))
    r1, r2 = one.build().inverse(q, v, a), two.build().inverse(q, v, a)
    assert np.abs(r1.effort - r2.effort).max() <= 1e-12 * np.abs(r1.effort).max()
    # a free box (12 kg, 0.4 x 0.2 x 0.1 m) with its bottom corners as frames, standing on them
    b = vtdyn.Builder(gravity=(0, 0, -G))
    assert b.add_body(joint="free", mass=12.0, inertia=(0.05, 0.17, 0.2), name="box") == 1
    corners = [(x, y, -0.05) for x in (0.2, -0.2) for y in (0.1, -0.1)]
    for k, p in enumerate(corners):
        assert b.add_frame("corner%d" % k, body=1, point=p) == k
    assert b.find_body("box") == 1 and b.find_frame("corner2") == 2
    box = b.build()
    assert box.floating and box.frame_names == ("corner0", "corner1", "corner2", "corner3")
    cs = box.contacts([vtdyn.Contact(frame="corner%d" % k) for k in range(4)])
    r = box.inverse(box.q0, np.zeros(6), np.zeros(6), contacts=cs)
    assert np.abs(r.contact_force - [0, 0, 12.0 * G / 4]).max() <= 1e-12 * 12.0 * G


def test_builder_errors():
    b = vtdyn.Builder()
    with pytest.raises(ValueError, match="^joint: unknown kind 'hinge'"):
        b.add_body(joint="hinge")
    with pytest.raises(ValueError, match="^inertia: "):
        b.add_body(inertia=(1, 2))
    with pytest.raises(ValueError, match="^axis1: "):
        b.add_body(axis1=(0, 1))
    with pytest.raises(ValueError, match="^name: "):
        b.add_body(name=5)
    with pytest.raises(ValueError, match="^layout: "):
        vtdyn.Builder(layout="sparse")
    with pytest.raises(vtdyn.Error) as e:
        vtdyn.Builder(rcond_min=2.0)
    assert e.value.status == "VT_ERR_BAD_OPTION"
    with pytest.raises(vtdyn.Error) as e:
        b.build()
    assert e.value.status == "VT_ERR_EMPTY_MODEL"
    with pytest.raises(vtdyn.Error) as e:
        b.add_body(parent=3)
    assert e.value.status == "VT_ERR_PARENT" and e.value.row is None and str(e.value)
    with pytest.raises(vtdyn.Error) as e:
        b.add_body(mass=-1.0)
    assert e.value.status == "VT_ERR_MASS"
    with pytest.raises(vtdyn.Error) as e:
        b.add_body(joint="universal", axis1=(0, 0, 1), axis2=(0, 1, 1))
    assert e.value.status == "VT_ERR_AXES_NOT_PERPENDICULAR"
    assert b.add_body(mass=1.0) == 1  # the refusals left the builder as it was
    assert b.add_body(parent=1, joint="prismatic", joint_parent=(1, 0, 0), axis1=(1, 0, 0)) == 2
    b.add_frame("tip", body=2)
    with pytest.raises(vtdyn.Error) as e:
        b.add_frame("tip", body=1)
    assert e.value.status == "VT_ERR_BAD_NAME"
    with pytest.raises(vtdyn.Error) as e:
        b.find_joint("nope")
    assert e.value.status == "VT_ERR_NOT_FOUND" and "nope" in str(e.value)
    with pytest.raises(ValueError, match="^kind: unknown kind 'speed'"):
        b.add_drive(kind="speed")
    with pytest.raises(ValueError, match=r"^f \(cosine\): unknown kind"):
        b.add_drive(f=("cosine", (1, 2)))
    with pytest.raises(ValueError, match="^f: "):
        b.add_drive(f="fast")
    with pytest.raises(ValueError, match=r"^f \(polynomial\): "):
        b.add_drive(f=vtdyn.Function.polynomial(*range(9)))
    with pytest.raises(ValueError, match=r"^f \(spline\): "):
        b.add_drive(f=vtdyn.Function.spline([0, 1, 2], [0, 1]))
    with pytest.raises(vtdyn.Error) as e:
        b.add_drive(f=vtdyn.Function.spline([0, 2, 1], [0, 1, 2]))
    assert e.value.status == "VT_ERR_BAD_DRIVE"
    with pytest.raises(vtdyn.Error) as e:
        b.add_drive(body=9)
    assert e.value.status == "VT_ERR_BAD_INDEX"
    with pytest.raises(vtdyn.Error) as e:
        b.add_cut_joint(body_a=0, body_b=2, joint="spherical", planar=True)
    assert e.value.status == "VT_ERR_BAD_CUT_JOINT"
    with pytest.raises(ValueError, match="^joint: "):
        b.add_cut_joint(joint="weld")
    with pytest.raises(vtdyn.Error) as e:
        b.add_payload(body=1, mass=-2.0)
    assert e.value.status == "VT_ERR_MASS"
    with pytest.raises(TypeError):
        b.add_body(1)  # keyword-only


def test_frame_poses_of_a_loop():
    """a loop's frames: placed on the full layout (a link's end at its closed-form place), refused
    on the recursive one, naming the layout"""
    for layout in ("full", "recursive"):
        b = vtdyn.Builder(layout=layout)
        l1 = b.add_body(mass=1.0, joint_child=(-0.5, 0.0, 0.0))
        l2 = b.add_body(parent=l1, mass=1.0, joint_parent=(0.5, 0.0, 0.0), joint_child=(-0.5, 0.0, 0.0))
        b.add_cut_joint(body_a=0, body_b=l2, point_a=(1.0, 1.0, 0.0), point_b=(0.5, 0.0, 0.0), planar=True)
        b.add_frame("tip", body=l2, point=(0.5, 0.0, 0.0))
        m = b.build()
        if layout == "recursive":
            with pytest.raises(ValueError, match="needs the full layout"):
                m.frame_poses(m.q0)
            continue
        q = np.array([math.pi / 2, -math.pi / 2])  # up along y, then along x: the tip at (1, 1, 0)
        pos, rot = m.frame_poses(q, "tip")
        assert np.allclose(pos[0], (1.0, 1.0, 0.0), atol=1e-15)
        assert np.allclose(rot[0], np.eye(3), atol=1e-15)
