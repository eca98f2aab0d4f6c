"""Model.contacts and Model.inverse(..., contacts=...) (python/vtdyn/contacts.c, model.c) against
Pinocchio, closed forms and themselves.

* Solo-12 floating (example-robot-data) standing on its four feet FL_FOOT ... HR_FOOT (front mu
  0.8, hind 0.6) at 200 states near the stand (made in Pinocchio's terms, turned into vtdyn's
  as tests/peers/check_contacts.py does): the twelve joint efforts equal
  pin.rnea(q, v, a) - sum_c J_c^T f_c (J_c the foot frame's linear Jacobian, LOCAL_WORLD_ALIGNED,
  f_c vtdyn's contact_force) to 1e-9 of the larger of the row's largest effort and the weight;
  the root's six of that sum and vtdyn's own root efforts zero to the same; every force pushes
  (n.f >= 0) and lies in its 4-face pyramid, |f_x|, |f_y| <= mu cos(pi/4) f_z. Pushed on its base
  and pulled at a foot (loads=): pin.rnea(q, v, a, fext) - sum_c J_c^T f_c the same way.
* A box (a URDF written here: 12 kg, its corners links fixed to it) floating on its four bottom
  corners, no motor: at rest each corner carries m g / 4 straight up (closed form); accelerated
  and turning, the forces are the minimum-norm solution of the box's six Newton-Euler equations
  (numpy's lstsq: what the rule gives when no motor is left to weigh), to 1e-12 of the weight.
  Only its centre point active: m g there, exactly 0 at the inactive corners. The corners given
  as points on the bottom centre's frame (Contact(frame=, point=): in its axes from its origin)
  give the same closed form.
* A row the contacts cannot carry (falling faster than gravity: a pull; thrown sideways beyond
  friction: a slip) raises vtdyn.Error VT_ERR_CONTACT with that row; one state equals its row
  of a batch bitwise; threads 1 and 2 give bitwise the same arrays; every argument error raises
  ValueError naming the argument, and a contact the library refuses raises vtdyn.Error.
"""
import math

import numpy as np
import pinocchio as pin
import pytest

import vtdyn
from test_vtdyn import urdf

FEET = ("FL_FOOT", "FR_FOOT", "HL_FOOT", "HR_FOOT")
MU = {"FL_FOOT": 0.8, "FR_FOOT": 0.8, "HL_FOOT": 0.6, "HR_FOOT": 0.6}
STAND = {"HAA": 0.0, "F_HFE": 0.8, "F_KFE": -1.6, "H_HFE": -0.8, "H_KFE": 1.6}
G = 9.81


@pytest.fixture(scope="module")
def solo():
    m = vtdyn.load_urdf(urdf("Solo-12"), floating=True)
    pm = pin.buildModelFromUrdf(urdf("Solo-12"), pin.JointModelFreeFlyer())
    cs = m.contacts([vtdyn.Contact(frame=f, mu=MU[f]) for f in FEET])
    return m, pm, cs


def solo_states(m, pm, n, seed):
    """n states near the stand: Pinocchio's (q, v, a) and vtdyn's (q, v, a) rows"""
    rng = np.random.default_rng(seed)
    names = [pm.names[j] for j in range(2, pm.njoints)]
    P, V = [], []
    for _ in range(n):
        q = pin.neutral(pm)
        for nm in names:
            leg, kind = nm.split("_")
            q[pm.joints[pm.getJointId(nm)].idx_q] = (STAND["HAA"] if kind == "HAA" else STAND[leg[0] + "_" + kind]) + \
                rng.uniform(-0.1, 0.1)
        q[:3] = rng.uniform(-0.05, 0.05, 3) + (0, 0, 0.25)
        e = np.r_[rng.uniform(-0.05, 0.05, 3), 1.0]
        q[3:7] = e / np.linalg.norm(e)  # Pinocchio: (x, y, z, w)
        v = rng.uniform(-0.3, 0.3, pm.nv)
        a = rng.uniform(-0.3, 0.3, pm.nv)
        v[:6] *= 0.2
        a[:6] *= 0.2
        P.append((q, v, a))
    qv, vv, av = np.empty((n, m.nq)), np.empty((n, m.nv)), np.empty((n, m.nv))
    for s, (q, v, a) in enumerate(P):
        R = pin.Quaternion(q[3:7]).toRotationMatrix()
        vl, w, al, dw = v[:3], v[3:6], a[:3], a[3:6]
        for b, (qa, nq, va, nv) in enumerate(m.body_index):
            if nq == 7:
                qv[s, qa:qa + 7] = np.r_[q[:3], q[6], q[3:6]]
                vv[s, va:va + 6] = np.r_[R @ vl, R @ w]
                av[s, va:va + 6] = np.r_[R @ (al + np.cross(w, vl)), R @ dw]
            else:
                j = pm.joints[pm.getJointId(m.body_joint_names[b])]
                qv[s, qa], vv[s, va], av[s, va] = q[j.idx_q], v[j.idx_v], a[j.idx_v]
    return P, (qv, vv, av)


def feet_difference(m, pm, pd, feet, weight, qp, vp, ap, effort, force, fext=None):
    """one state's largest difference, relative to the larger of the weight and the largest joint
    effort, between vtdyn's joint efforts and pin.rnea (with fext) - sum_c J_c^T f_c (J_c the foot
    frame's linear Jacobian, LOCAL_WORLD_ALIGNED), and of that sum's six root terms from zero"""
    tau = (pin.rnea(pm, pd, qp, vp, ap) if fext is None else pin.rnea(pm, pd, qp, vp, ap, fext)) + \
        pm.damping * vp + pm.friction * np.sign(vp)
    pin.computeJointJacobians(pm, pd, qp)
    pin.updateFramePlacements(pm, pd)
    for c, fid in enumerate(feet):
        J = pin.getFrameJacobian(pm, pd, fid, pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)[:3]
        tau = tau - J.T @ force[c]
    mine = np.empty(pm.nv - 6)
    for b, (qa, nq, va, nv) in enumerate(m.body_index):
        if nq != 7:
            mine[pm.joints[pm.getJointId(m.body_joint_names[b])].idx_v - 6] = effort[va]
    scale = max(weight, np.abs(tau[6:]).max())
    return max(np.abs(mine - tau[6:]).max() / scale, np.abs(tau[:6]).max() / scale)


def test_solo_against_pinocchio(solo):
    m, pm, cs = solo
    pd = pm.createData()
    weight = sum(pm.inertias[i].mass for i in range(pm.njoints)) * G
    feet = [pm.getFrameId(f) for f in FEET]
    P, (q, v, a) = solo_states(m, pm, 200, seed=1)
    r = m.inverse(q, v, a, contacts=cs)
    assert r.contact_force.shape == (200, 4, 3) and r.effort.shape == (200, 18)
    worst = 0.0
    for s, (qp, vp, ap) in enumerate(P):
        worst = max(worst, feet_difference(m, pm, pd, feet, weight, qp, vp, ap, r.effort[s], r.contact_force[s]),
                    np.abs(r.effort[s, :6]).max() / weight)
        for c, f in enumerate(FEET):
            fx, fy, fz = r.contact_force[s, c]
            lim = MU[f] * math.cos(math.pi / 4) * fz
            assert fz >= 0 and abs(fx) <= lim + 1e-9 * weight and abs(fy) <= lim + 1e-9 * weight, (s, f)
    assert worst <= 1e-9, worst
    print("Solo-12 on four feet, 200 states: largest relative difference from Pinocchio %.2g" % worst)


def test_solo_pushed_against_pinocchio(solo):
    """loads with contacts: a push on the base (base_link) and a pull on a foot's frame, world axes,
    at 100 states on four feet: the twelve joint efforts equal pin.rnea(q, v, a, fext) - sum_c
    J_c^T f_c (each load moved to the world origin, then into its frame's joint by oMi.actInv),
    the root's six of that sum zero, to 1e-9 of the weight: the ground's forces balance the
    loads too"""
    m, pm, cs = solo
    pd = pm.createData()
    weight = sum(pm.inertias[i].mass for i in range(pm.njoints)) * G
    feet = [pm.getFrameId(f) for f in FEET]
    frames = ["base_link", "FL_FOOT"]
    P, (q, v, a) = solo_states(m, pm, 100, seed=3)
    rng = np.random.default_rng(4)
    w = np.empty((100, 2, 6))
    w[:, 0] = np.c_[rng.uniform(-3, 3, (100, 2)), rng.uniform(-6, 0, 100), rng.uniform(-0.3, 0.3, (100, 3))]
    w[:, 1] = np.c_[rng.uniform(-1, 1, (100, 2)), rng.uniform(-2, 0, 100), np.zeros((100, 3))]
    r = m.inverse(q, v, a, contacts=cs, loads=w, load_frames=frames)
    pos, _ = m.frame_poses(q, frames)
    fids = [pm.getFrameId(f) for f in frames]
    worst = 0.0
    for s, (qp, vp, ap) in enumerate(P):
        pin.forwardKinematics(pm, pd, qp)
        fext = [pin.Force.Zero() for _ in range(pm.njoints)]
        for k, f in enumerate(fids):
            j = pm.frames[f].parentJoint
            fext[j] += pd.oMi[j].actInv(pin.Force(w[s, k, :3], w[s, k, 3:] + np.cross(pos[s, k], w[s, k, :3])))
        worst = max(worst, feet_difference(m, pm, pd, feet, weight, qp, vp, ap, r.effort[s], r.contact_force[s], fext))
    assert worst <= 1e-9, worst
    free = m.inverse(q, v, a, contacts=cs)
    assert np.abs(free.contact_force - r.contact_force).max() > 0.1  # the loads move the feet's forces
    print("Solo-12 pushed on four feet, 100 states: largest relative difference from Pinocchio %.2g" % worst)


def test_solo_rows_and_threads(solo):
    m, pm, cs = solo
    _, (q, v, a) = solo_states(m, pm, 64, seed=2)
    act = np.ones((64, 4), dtype=np.int32)
    ref = m.inverse(q, v, a, threads=1, contacts=cs, active=act)
    got = m.inverse(q, v, a, threads=2, contacts=cs)
    for k in range(len(ref)):
        assert np.array_equal(got[k], ref[k]), k
    for s in (0, 31, 63):
        one = m.inverse(q[s], v[s], a[s], contacts=cs, active=[1, 1, 1, 1])
        assert one.contact_force.shape == (4, 3)
        for k in range(len(ref)):
            assert np.array_equal(one[k], ref[k][s]), (s, k)
    plain = m.inverse(q, v, a)  # no contacts: the root carries it, no forces
    assert plain.contact_force.shape == (64, 0, 3) and np.abs(plain.effort[:, 2]).min() > 1.0


BOX_MASS, BOX_SIZE = 12.0, (0.4, 0.2, 0.1)
CORNERS = [(sx * BOX_SIZE[0] / 2, sy * BOX_SIZE[1] / 2, -BOX_SIZE[2] / 2) for sx in (1, -1) for sy in (1, -1)]


@pytest.fixture(scope="module")
def box(tmp_path_factory):
    lx, ly, lz = BOX_SIZE
    ixx, iyy, izz = (BOX_MASS / 12 * (ly * ly + lz * lz), BOX_MASS / 12 * (lx * lx + lz * lz),
                     BOX_MASS / 12 * (lx * lx + ly * ly))
    text = ('<robot name="box"><link name="box"><inertial><mass value="%r"/>'
            '<inertia ixx="%r" ixy="0" ixz="0" iyy="%r" iyz="0" izz="%r"/></inertial></link>' % (BOX_MASS, ixx, iyy, izz))
    for k, (x, y, z) in enumerate(CORNERS + [(0.0, 0.0, -lz / 2)]):
        text += ('<link name="c%d"/><joint name="j%d" type="fixed"><parent link="box"/><child link="c%d"/>'
                 '<origin xyz="%r %r %r"/></joint>' % (k, k, k, x, y, z))
    path = tmp_path_factory.mktemp("box") / "box.urdf"
    path.write_text(text + "</robot>")
    m = vtdyn.load_urdf(str(path), floating=True)
    return m, np.diag([ixx, iyy, izz])


def box_state(m, pos=(0.0, 0.0, 0.05), w=(0.0, 0.0, 0.0), acc=(0.0, 0.0, 0.0), alpha=(0.0, 0.0, 0.0)):
    q = m.q0.copy()
    q[:3] = pos
    v = np.r_[0.0, 0.0, 0.0, w]
    a = np.r_[acc, alpha]
    return q, v, a


def test_box_closed_form(box):
    m, inertia = box
    cs = m.contacts([vtdyn.Contact(frame="c%d" % k) for k in range(4)])
    q, v, a = box_state(m)
    r = m.inverse(q, v, a, contacts=cs)
    weight = BOX_MASS * G
    assert np.abs(r.contact_force - [0.0, 0.0, weight / 4]).max() <= 1e-12 * weight
    assert np.abs(r.effort).max() <= 1e-12 * weight
    # accelerated and turning (box axes = world axes at this q): the six equations
    # sum f = m (a - g), sum p_c x f = I alpha + w x I w, their minimum-norm solution
    w, acc, alpha = np.array([0.1, -0.2, 0.3]), np.array([0.8, -0.5, 1.0]), np.array([0.4, 0.3, -0.6])
    q, v, a = box_state(m, w=w, acc=acc, alpha=alpha)
    r = m.inverse(q, v, a, contacts=cs)
    A = np.zeros((6, 12))
    for c, p in enumerate(CORNERS):
        A[:3, 3 * c:3 * c + 3] = np.eye(3)
        A[3:, 3 * c:3 * c + 3] = np.array([[0, -p[2], p[1]], [p[2], 0, -p[0]], [-p[1], p[0], 0]])
    rhs = np.r_[BOX_MASS * (acc - [0, 0, -G]), inertia @ alpha + np.cross(w, inertia @ w)]
    f = np.linalg.lstsq(A, rhs, rcond=None)[0].reshape(4, 3)
    assert np.abs(r.contact_force - f).max() <= 1e-12 * weight, np.abs(r.contact_force - f).max()
    # the same corners as points on the bottom centre's frame c4, in its axes from its origin
    lz = BOX_SIZE[2]
    on_c4 = m.contacts([vtdyn.Contact(frame="c4", point=(x, y, z + lz / 2), name="k%d" % k)
                        for k, (x, y, z) in enumerate(CORNERS)])
    r4 = m.inverse(q, v, a, contacts=on_c4)
    assert np.abs(r4.contact_force - f).max() <= 1e-12 * weight
    # five points, only the centre one on the ground: it carries the weight, the others nothing
    cs5 = m.contacts([vtdyn.Contact(frame="c%d" % k, name="p%d" % k) for k in range(5)])
    assert cs5.names == ("p0", "p1", "p2", "p3", "p4") and len(cs5) == 5
    q, v, a = box_state(m)
    r = m.inverse(np.tile(q, (3, 1)), np.tile(v, (3, 1)), np.tile(a, (3, 1)), contacts=cs5,
                  active=np.array([[0, 0, 0, 0, 1]] * 3, dtype=bool))
    assert np.all(r.contact_force[:, :4] == 0.0)
    assert np.abs(r.contact_force[:, 4] - [0, 0, weight]).max() <= 1e-12 * weight


def test_infeasible_rows(box):
    m, _ = box
    cs = m.contacts([vtdyn.Contact(frame="c%d" % k, mu=0.5) for k in range(4)])
    rows = [box_state(m) for _ in range(6)]
    rows[4] = box_state(m, acc=(0.0, 0.0, -2 * G))  # falling faster than gravity: a foot would pull
    q, v, a = (np.array(x) for x in zip(*rows))
    with pytest.raises(vtdyn.Error) as e:
        m.inverse(q, v, a, threads=2, contacts=cs)
    assert e.value.status == "VT_ERR_CONTACT" and e.value.code == -35 and e.value.row == 4
    assert str(e.value).startswith("row 4: ") and "pull" in str(e.value)
    rows[1] = box_state(m, acc=(G, 0.0, 0.0))  # sideways beyond mu 0.5: a slip, the first row failing
    q, v, a = (np.array(x) for x in zip(*rows))
    with pytest.raises(vtdyn.Error) as e:
        m.inverse(q, v, a, contacts=cs)
    assert e.value.row == 1 and "slip" in str(e.value)
    with pytest.raises(vtdyn.Error) as e:
        m.inverse(q[1], v[1], a[1], contacts=cs)
    assert e.value.row is None and e.value.status == "VT_ERR_CONTACT" and not str(e.value).startswith("row")


def test_contact_errors(box, solo):
    m, _ = box
    cs = m.contacts([vtdyn.Contact(frame="c%d" % k) for k in range(4)])
    q, v, a = box_state(m)
    for kw, name in [({"active": [1, 1, 1]}, "active"), ({"active": [[1, 1, 1, 1]]}, "active"),
                     ({"active": [1, 2, 1, 1]}, "active"), ({"active": [0.5, 1, 1, 1]}, "active"),
                     ({"contacts": solo[2]}, "contacts"), ({"contacts": [1, 2]}, "contacts")]:
        kw.setdefault("contacts", cs)
        with pytest.raises(ValueError, match="^%s: " % name):
            m.inverse(q, v, a, **kw)
    with pytest.raises(ValueError, match="^active: "):
        m.inverse(q, v, a, active=[1, 1, 1, 1])  # without contacts
    with pytest.raises(ValueError, match="^active: "):
        m.inverse(np.tile(q, (2, 1)), np.tile(v, (2, 1)), np.tile(a, (2, 1)), contacts=cs, active=np.ones((3, 4)))
    with pytest.raises(vtdyn.Error) as e:
        m.contacts([vtdyn.Contact(frame="no_such_frame")])
    assert e.value.status == "VT_ERR_NOT_FOUND" and "no_such_frame" in str(e.value)
    with pytest.raises(vtdyn.Error) as e:
        m.contacts([vtdyn.Contact(frame="c0", mu=-1.0)])
    assert e.value.status == "VT_ERR_BAD_OPTION"
    with pytest.raises(vtdyn.Error) as e:
        m.contacts([vtdyn.Contact(frame="c0", faces=2)])
    assert e.value.status == "VT_ERR_BAD_OPTION"
    with pytest.raises(ValueError, match=r"^contacts\[1\]\.kind: "):
        m.contacts([vtdyn.Contact(frame="c0"), vtdyn.Contact(frame="c1", kind="sticky")])
    with pytest.raises(ValueError, match=r"^contacts\[0\]\.mu: "):
        m.contacts([vtdyn.Contact(frame="c0", mu="high")])
    with pytest.raises(ValueError, match=r"^contacts\[0\]\.point: "):
        m.contacts([vtdyn.Contact(body=1, point=(0, 0))])
    with pytest.raises(ValueError, match="^contacts: "):
        m.contacts([])
    with pytest.raises(ValueError, match="^effort_weight: "):
        m.contacts([vtdyn.Contact(frame="c0")], effort_weight=[1.0, 2.0])


def test_contact_on_another_body():
    """a box standing on a plate carried up by a lift (Contact.other): the lift's force is the three
    bodies' weight and acceleration, (m_l + m_p + m_b)(a + g), and the box's corner forces sum to
    m_b (a + g) up, closed forms; other = the box itself is refused"""
    b = vtdyn.Builder(gravity=(0.0, 0.0, -9.81))
    lift = b.add_body(joint="translational", mass=3.0, inertia=np.eye(3) * 0.1)
    plate = b.add_body(parent=lift, mass=5.0, inertia=np.eye(3) * 0.2, axis1=(1.0, 0.0, 0.0))
    box = b.add_body(joint="free", mass=2.0, inertia=np.diag([0.13, 0.2, 0.25]) * 2.0 / 12.0)
    m = b.build()
    corners = [(x, y, -0.1) for x in (0.2, -0.2) for y in (0.15, -0.15)]
    cs = m.contacts([vtdyn.Contact(body=box, point=p, other=plate, mu=0.5) for p in corners])
    acc = 1.5
    q, v, a = np.zeros(m.nq), np.zeros(m.nv), np.zeros(m.nv)
    q[0] = 0.3
    qb = m.body_index[box - 1][0]
    q[qb:qb + 7] = (0.0, 0.0, 0.4, 1.0, 0.0, 0.0, 0.0)
    a[0] = acc
    a[m.body_index[box - 1][2] + 2] = acc
    r = m.inverse(q, v, a, contacts=cs)
    W = 10.0 * (9.81 + acc)
    assert abs(r.effort[0] - W) <= 1e-12 * W
    assert np.allclose(r.contact_force.sum(axis=0), (0.0, 0.0, 2.0 * (9.81 + acc)), rtol=0, atol=1e-12 * W)
    assert np.allclose(r.contact_force[:, 2], 2.0 * (9.81 + acc) / 4, rtol=0, atol=1e-9 * W)
    with pytest.raises(vtdyn.Error, match="other"):
        m.contacts([vtdyn.Contact(body=box, other=box)])


def test_unique_against_another_rule(solo):
    """ContactSet.unique: what it calls fixed is the same under another rule (other effort and
    force weights: another distribution among the forces the base's equations allow; bilateral
    feet), to 1e-9;
    what it calls the rule's differs for some; on three feet the lifted leg's torques are fixed,
    its foot's force too (zero)"""
    m, pm, _ = solo
    # bilateral feet: the flags are those of bilateral contacts, and on three feet near the stand
    # the centre of mass is close to the line of two of them, where a unilateral foot might pull
    cs = m.contacts([vtdyn.Contact(frame=f, kind="bilateral") for f in FEET])
    other = m.contacts([vtdyn.Contact(frame=f, kind="bilateral", weight=3e-3 * (k + 1)) for k, f in enumerate(FEET)],
                       effort_weight=np.linspace(0.5, 3.0, m.nv))
    _, (q, v, a) = solo_states(m, pm, 4, seed=7)
    weight = sum(pm.inertias[i].mass for i in range(pm.njoints)) * G
    lifted_leg = [va for b, (qa, nq, va, nv) in enumerate(m.body_index)
                  if nq == 1 and m.body_joint_names[b].startswith("FL_")]
    for s in range(4):
        for active in ((1, 1, 1, 1), (0, 1, 1, 1)):
            eu, fu, ru = cs.unique(q[s], v[s], a[s], active=active)
            assert eu.shape == (m.nv,) and fu.shape == (4, 3) and ru.shape == (m.nbody, 6)
            act = np.array([active])
            r1 = m.inverse(q[s:s + 1], v[s:s + 1], a[s:s + 1], contacts=cs, active=act, threads=1)
            r2 = m.inverse(q[s:s + 1], v[s:s + 1], a[s:s + 1], contacts=other, active=act, threads=1)
            de = np.abs(r1.effort[0] - r2.effort[0])
            df = np.abs(r1.contact_force[0] - r2.contact_force[0])
            dr = np.abs(r1.reaction[0] - r2.reaction[0])
            assert de[eu].max(initial=0) <= 1e-9 * weight and df[fu].max(initial=0) <= 1e-9 * weight
            assert dr[ru].max(initial=0) <= 1e-9 * weight
            assert de[~eu].max() > 1e-6 * weight  # the rule's choice shows
            assert eu[:6].all()  # the base: zero whatever the rule
            if active[0] == 0:
                assert eu[lifted_leg].all() and fu[0].all()
    with pytest.raises(ValueError, match="active: 4 entries"):
        cs.unique(q[0], v[0], a[0], active=(1, 1))
    with pytest.raises(ValueError, match="one state"):
        cs.unique(q, v, a)
