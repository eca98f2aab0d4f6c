"""Model.kinematic_analysis and Model.dynamic_analysis (python/vtdyn/analysis.c) on models built
with vtdyn.Builder, against closed forms written out here.

* The paper's double link falling from rest with joint 2 locked (a dynamic analysis, SUNDIALS
  IDA): the 4 m rod about its end, theta'' = (3 g / 2 l) cos theta and theta'^2 = (3 g / l)
  sin theta (l = 4 m; the paper's 3.67875 and 7.3575), and, at each row's theta, the ground's
  force on link 1 (eq. 29 of the paper: f = [-2207.25 sin 2 theta, 4905 sin^2 theta + 490.5
  cos^2 theta] N, derived here from the rod's centre's acceleration), link 1's force on link 2
  and the locking torque (link 2's angular momentum balance about its joint), each against the
  run to 1e-7 of the weight; the forward check's deviation below 1e-6.
* The double link fully driven (q1 a sine, q2 a polynomial, then q1 a spline through samples of
  a cubic): the kinematic analysis's q, q', q'' against the functions' exact values and its
  drive efforts against the Lagrange equations (test_builder.lagrange) to 1e-10 of the largest;
  the spline drive equals the cubic's polynomial drive (a not-a-knot spline reproduces cubics).
* A parallelogram four-bar closed by a planar pin (add_cut_joint planar=True), its crank driven:
  the crank torque against energy balance, tau = I_eff phi'' + 2 m g a cos phi with
  I_eff = 2 m a^2 / 3 + m a^2 (the coupler translates); the pin's reaction in its plane only.
  Model.inverse with a wrench at a frame on the coupler (loads=): the same closed form plus the
  load's power per unit crank rate, at 50 random states (1e-12), in effort and drive_effort; the
  loop's solved qdd (-phi'' and phi'' for coupler and rocker). Model.kinematic_analysis with the
  wrench over the run (loads=, constant or a function of t): the same closed form at every row,
  and the forward check.
* Model.inverse's t on a coupled planar arm whose end's x is a point drive x(t) = 0.3 sin 2t: the
  end's x'' from the planar closed form at the solved qdd against x''(t) (1e-12); refused without
  t; on a tree t changes nothing.
* Errors: a model not fully driven, bad options and shapes.
"""
import numpy as np
import pytest

import vtdyn
from test_builder import G, J, L, M, double_link, lagrange

sundials = pytest.mark.skipif(not vtdyn.VT_HAVE_SUNDIALS, reason="built without SUNDIALS")


@sundials
def test_double_link_falls_as_a_rod():
    m = double_link([dict(body=2, f=0.0, name="lock")])
    tr = m.dynamic_analysis(1.5, nout=30, rtol=1e-10, atol=1e-12, max_step=0.005)
    assert isinstance(tr, vtdyn.Trajectory) and tr.time.shape == (31,) and tr.q.shape == (31, 2)
    assert tr.reaction.shape == (31, 2, 6) and tr.drive_effort.shape == (31, 1) and tr.steps > 0
    assert np.allclose(tr.time, np.linspace(0, 1.5, 31), rtol=0, atol=1e-15)
    weight = 2 * M * G
    lr = 2 * L  # the locked pair: one rod of 4 m, 200 kg, about its end
    theta = -tr.q[:, 0]  # the angle fallen below x
    assert np.abs(tr.q[:, 1]).max() <= 1e-9  # locked
    thdd = 3 * G / (2 * lr) * np.cos(theta)
    thd2 = 3 * G / lr * np.sin(theta)  # theta'^2, the first integral
    assert abs(3 * G / (2 * lr) - 3.67875) < 1e-12 and abs(3 * G / lr - 7.3575) < 1e-12  # the paper's
    assert np.abs(tr.qd[:, 0] ** 2 - thd2).max() <= 1e-7
    assert np.abs(-tr.qdd[:, 0] - thdd).max() <= 1e-7
    e = np.stack([np.cos(theta), -np.sin(theta)], axis=1)  # along the rod
    de = np.stack([-np.sin(theta), -np.cos(theta)], axis=1)  # d e / d theta
    acc = lambda r: r * (thdd[:, None] * de - thd2[:, None] * e)  # a point at r along the rod
    g = np.array([0.0, -G])
    f1 = 2 * M * (acc(lr / 2) - g)  # the ground on link 1: the whole rod's Newton
    f29 = np.stack([-2207.25 * np.sin(2 * theta), 4905.0 * np.sin(theta) ** 2 + 490.5 * np.cos(theta) ** 2], axis=1)
    assert np.abs(f1 - f29).max() <= 1e-9 * weight  # (29) as the paper prints it
    f2 = M * (acc(1.5 * L) - g)  # link 1 on link 2
    arm = 0.5 * L * e  # link 2's centre from joint 2
    tau2 = J * (-thdd) + (arm[:, 0] * f2[:, 1] - arm[:, 1] * f2[:, 0])  # about z: I alpha + r x m (a - g)
    assert np.abs(tr.reaction[:, 0, :2] - f1).max() <= 1e-7 * weight
    assert np.abs(tr.reaction[:, 1, :2] - f2).max() <= 1e-7 * weight
    assert np.abs(tr.reaction[:, :, 2]).max() <= 1e-9 * weight  # in the plane
    assert np.abs(tr.drive_effort[:, 0] - tau2).max() <= 1e-7 * weight * L
    assert np.abs(tr.qfrc_drive[:, 1] - tau2).max() <= 1e-7 * weight * L and np.all(tr.qfrc_drive[:, 0] == 0)
    assert np.abs(np.abs(tau2) - 245.25 * np.abs(np.cos(theta))).max() <= 1e-9 * weight * L
    # the forward check: the torque applied, the drive removed, the same motion
    assert tr.q_fwd.shape == (31, 2) and tr.fwd_err_q <= 1e-6 and tr.fwd_err_force <= 1e-6 * weight
    assert np.abs(tr.q_fwd - tr.q).max() <= tr.fwd_err_q and tr.steps_fwd > 0
    assert tr.fwd_window_row.tolist() == [0] and tr.fwd_window_err_q[0] == tr.fwd_err_q
    # from another start: q and qd given, rows at the times given
    tr2 = m.dynamic_analysis(1.0, q=[-0.3, 0.0], qd=[0.0, 0.0], tout=[0.25, 0.5, 1.0], forward_check=False)
    assert tr2.time.tolist() == [0.0, 0.25, 0.5, 1.0] and tr2.q_fwd is None and tr2.q[0, 0] == -0.3
    th, thd = -tr2.q[:, 0], -tr2.qd[:, 0]
    assert np.abs(thd ** 2 - 3 * G / lr * (np.sin(th) - np.sin(0.3))).max() <= 1e-6


C = (0.2, -0.4, 0.3, 0.5)  # q2's polynomial; q1 = 0.5 + 0.8 sin(2 t + 0.1)
CUBIC = (0.1, 0.7, -0.9, 0.35)


def test_double_link_driven():
    sine = vtdyn.Function.sine(0.5, 0.8, 2.0, 0.1)
    m = double_link([dict(body=1, f=sine), dict(body=2, f=vtdyn.Function.polynomial(*C))])
    fwd = bool(vtdyn.VT_HAVE_SUNDIALS)
    tr = m.kinematic_analysis(2.0, nout=40, forward_check=fwd)
    t = tr.time
    q1 = 0.5 + 0.8 * np.sin(2 * t + 0.1)
    q1d, q1dd = 1.6 * np.cos(2 * t + 0.1), -3.2 * np.sin(2 * t + 0.1)
    q2 = C[0] + C[1] * t + C[2] * t ** 2 + C[3] * t ** 3
    q2d, q2dd = C[1] + 2 * C[2] * t + 3 * C[3] * t ** 2, 2 * C[2] + 6 * C[3] * t
    exact = [np.stack(x, axis=1) for x in ((q1, q2), (q1d, q2d), (q1dd, q2dd))]
    for got, ref in zip((tr.q, tr.qd, tr.qdd), exact):
        assert np.abs(got - ref).max() <= 1e-10 * max(1.0, np.abs(ref).max())
    tau = lagrange(*exact)
    assert np.abs(tr.qfrc_drive - tau).max() <= 1e-10 * np.abs(tau).max()
    assert np.abs(tr.drive_effort - tau).max() <= 1e-10 * np.abs(tau).max()
    assert tr.lambda_.shape == (41, 2) and tr.drive_force.shape == (41, 2, 3) and tr.steps == 0
    if fwd:
        assert tr.fwd_err_q <= 1e-6
    # a spline through samples of a cubic is the cubic: the same run as the polynomial drive
    ts = np.linspace(-0.5, 2.5, 9)
    ys = CUBIC[0] + CUBIC[1] * ts + CUBIC[2] * ts ** 2 + CUBIC[3] * ts ** 3
    a = double_link([dict(body=1, f=vtdyn.Function.spline(ts, ys)), dict(body=2, f=0.25)])
    b = double_link([dict(body=1, f=vtdyn.Function.polynomial(*CUBIC)), dict(body=2, f=vtdyn.Function.constant(0.25))])
    ra, rb = a.kinematic_analysis(2.0, nout=20, forward_check=False), b.kinematic_analysis(2.0, nout=20, forward_check=False)
    assert np.abs(ra.q - rb.q).max() <= 1e-12 and np.abs(ra.drive_effort - rb.drive_effort).max() <= 1e-9 * np.abs(rb.drive_effort).max()


def parallelogram(a, bl, m):
    """the four-bar: crank and rocker a, coupler and ground bl, each link m; a frame 'grip' on the
    coupler off its line"""
    ja = m * a * a / 12
    b = vtdyn.Builder()
    b.add_body(mass=m, inertia=(0, ja, ja), joint_child=(-a / 2, 0, 0), name="crank")
    b.add_body(parent=1, mass=m, inertia=(0, m * bl * bl / 12, m * bl * bl / 12), joint_parent=(a / 2, 0, 0),
               joint_child=(-bl / 2, 0, 0), name="coupler")
    b.add_body(parent=2, mass=m, inertia=(0, ja, ja), joint_parent=(bl / 2, 0, 0), joint_child=(-a / 2, 0, 0), name="rocker")
    assert b.add_cut_joint(body_a=0, body_b=3, point_a=(bl, 0, 0), point_b=(a / 2, 0, 0), planar=True, name="pin") == 0
    b.add_drive(body=1, f=vtdyn.Function.sine(1.0, 0.3, 2.0))
    b.add_frame("grip", body=2, point=(0.2, -0.3, 0.1))
    return b.build()


def test_four_bar_planar_pin():
    a, bl, m = 0.5, 1.2, 2.0
    four = parallelogram(a, bl, m)
    phi0 = 1.0
    tr = four.kinematic_analysis(3.0, nout=60, q=[phi0, -phi0, phi0 + np.pi], forward_check=False)
    t = tr.time
    phi, phidd = 1.0 + 0.3 * np.sin(2 * t), -1.2 * np.sin(2 * t)
    assert np.abs(tr.q[:, 0] - phi).max() <= 1e-10 and np.abs(tr.q[:, 1] + phi).max() <= 1e-9
    tau = (2 * m * a * a / 3 + m * a * a) * phidd + 2 * m * G * a * np.cos(phi)
    assert np.abs(tr.drive_effort[:, 0] - tau).max() <= 1e-9 * np.abs(tau).max()
    assert tr.cut_reaction.shape == (61, 1, 6)
    assert np.abs(tr.cut_reaction[:, 0, 2:]).max() <= 1e-12 * np.abs(tr.cut_reaction).max()  # in-plane force only


def test_four_bar_loads():
    """Model.inverse with a wrench at the coupler's frame (a loop: the crank's motion given): the
    coupler translates with the crank's tip, v = a phi' (-sin phi, cos phi, 0), so the crank's
    torque less the load's power per unit rate, tau - a (F_x sin phi - F_y cos phi), is the
    unloaded closed form whatever the frame's offset and the moment (the pin takes those)"""
    a, bl, m = 0.5, 1.2, 2.0
    four = parallelogram(a, bl, m)
    rng = np.random.default_rng(7)
    n = 50
    phi, phid, phidd = rng.uniform(-3, 3, n), rng.uniform(-2, 2, n), rng.uniform(-5, 5, n)
    q = np.stack([phi, -phi, phi + np.pi], axis=1)
    v = np.stack([phid, -phid, phid], axis=1)
    acc = np.zeros((n, 3))
    acc[:, 0] = phidd  # the crank's: the others follow from the loop
    w = rng.uniform(-30, 30, (n, 1, 6))
    r = four.inverse(q, v, acc, loads=w, load_frames=["grip"])
    tau = (2 * m * a * a / 3 + m * a * a) * phidd + 2 * m * G * a * np.cos(phi)
    tau += a * (w[:, 0, 0] * np.sin(phi) - w[:, 0, 1] * np.cos(phi))
    scale = np.abs(tau).max()
    assert np.abs(r.effort[:, 0] - tau).max() <= 1e-12 * scale
    assert np.abs(r.effort[:, 1:]).max() <= 1e-12 * scale  # the passive joints carry no torque
    bare = four.inverse(q, v, acc)
    assert np.abs(r.effort[:, 0] - bare.effort[:, 0]).max() > 1.0  # the loads reached the crank
    # the loop's q'' solved (coupler and rocker turn as -phi and phi), the crank drive's effort
    want = np.stack([phidd, -phidd, phidd], axis=1)
    assert r.qdd.shape == (n, 3) and np.abs(r.qdd - want).max() <= 1e-12 * np.abs(want).max()
    assert r.drive_effort.shape == (n, 1) and np.abs(r.drive_effort[:, 0] - tau).max() <= 1e-12 * scale


def test_four_bar_loads_over_time():
    """Model.kinematic_analysis with a wrench at the coupler's frame (loads=, load_frames=): the
    crank torque at every row is the closed form plus the load's power per unit crank rate,
    a (F_x sin phi - F_y cos phi) (1e-9 of the largest), for a constant wrench and for one given
    as a function of t; the forward check under the loaded torque and the wrench follows the
    motion; a loads function that raises ends the run with its own exception"""
    a, bl, m = 0.5, 1.2, 2.0
    four = parallelogram(a, bl, m)
    phi0 = 1.0
    start = dict(q=[phi0, -phi0, phi0 + np.pi], forward_check=bool(vtdyn.VT_HAVE_SUNDIALS))
    const = np.array([[12.0, -30.0, 4.0, 1.0, -2.0, 3.0]])

    def varying(t):
        return [[10.0 * np.sin(3 * t), -25.0 + 5.0 * np.cos(t), 0.0, 0.0, 0.0, 2.0 * t]]

    for loads in (const, varying):
        tr = four.kinematic_analysis(3.0, nout=60, loads=loads, load_frames=["grip"], **start)
        t = tr.time
        phi, phidd = 1.0 + 0.3 * np.sin(2 * t), -1.2 * np.sin(2 * t)
        w = np.array([(loads(x) if callable(loads) else loads)[0] for x in t])
        tau = (2 * m * a * a / 3 + m * a * a) * phidd + 2 * m * G * a * np.cos(phi)
        tau += a * (w[:, 0] * np.sin(phi) - w[:, 1] * np.cos(phi))
        assert np.abs(tr.drive_effort[:, 0] - tau).max() <= 1e-9 * np.abs(tau).max()
        if vtdyn.VT_HAVE_SUNDIALS:
            assert tr.fwd_err_q <= 1e-8, tr.fwd_err_q

    def broken(t):
        if t > 1.0:
            raise RuntimeError("the sensor log ends")
        return const

    with pytest.raises(RuntimeError, match="the sensor log ends"):
        four.kinematic_analysis(3.0, nout=60, loads=broken, load_frames=["grip"], **start)
    with pytest.raises(ValueError, match="^loads given without load_frames"):
        four.kinematic_analysis(3.0, loads=const, **start)
    with pytest.raises(ValueError, match="^loads: expected 1 x 6"):
        four.kinematic_analysis(3.0, loads=np.zeros(6), load_frames=["grip"], **start)
    with pytest.raises(ValueError, match="^loads\\(0\\): 3 values"):
        four.kinematic_analysis(3.0, loads=lambda t: [1.0, 2.0, 3.0], load_frames=["grip"], **start)


def coupled_arm(lengths, r, c0):
    """a planar arm of len(lengths) links about z, joint 2 following joint 1 by a coupling
    q2 = r q1 + c0, joint 1 driven, and the last link's end's x a point drive, 0.3 sin 2t"""
    b = vtdyn.Builder()
    for i, li in enumerate(lengths):
        mass = 1.0 + 0.5 * i
        b.add_body(parent=i, mass=mass, inertia=(0.01, mass * li * li / 12, mass * li * li / 12), axis1=(0, 0, 1),
                   joint_parent=(lengths[i - 1] / 2 if i else 0.0, 0, 0), joint_child=(-li / 2, 0, 0))
    b.add_coupling(body_a=2, body_b=1, ratio=r, offset=c0)
    b.add_drive(body=1)
    b.add_drive(body=len(lengths), kind="point", index=0, point=(lengths[-1] / 2, 0, 0),
                f=vtdyn.Function.sine(0.0, 0.3, 2.0), name="end_x")
    return b.build()


def test_inverse_time():
    """Model.inverse's t: a coupled arm whose end's x is a point drive, x(t) = 0.3 sin 2t (its
    rows kept by the given motion, γ = x''(t)): the end's x'' from the planar closed form at the
    solved qdd equals x''(t) at each state's t; without t the call is refused (naming the drive);
    a number is every state's time; on a tree t changes nothing"""
    lengths, r, c0 = (0.7, 0.5, 0.4), -0.6, 0.4
    arm = coupled_arm(lengths, r, c0)
    rng = np.random.default_rng(11)
    n = 30
    t = rng.uniform(0, 3, n)
    q1, q3 = rng.uniform(-2, 2, n), rng.uniform(-2, 2, n)
    v1, v3 = rng.uniform(-1, 1, n), rng.uniform(-1, 1, n)
    a1 = rng.uniform(-3, 3, n)
    q = np.stack([q1, r * q1 + c0, q3], axis=1)
    v = np.stack([v1, r * v1, v3], axis=1)
    acc = np.stack([a1, r * a1, np.zeros(n)], axis=1)  # q3'': the point drive's
    res = arm.inverse(q, v, acc, t=t)
    phi, phid, phidd = np.cumsum(q, axis=1), np.cumsum(v, axis=1), np.cumsum(res.qdd, axis=1)
    xdd = sum(li * (-np.sin(phi[:, i]) * phidd[:, i] - np.cos(phi[:, i]) * phid[:, i] ** 2)
              for i, li in enumerate(lengths))
    want = -1.2 * np.sin(2 * t)
    assert np.abs(xdd - want).max() <= 1e-12 * (1 + np.abs(want).max())
    with pytest.raises(ValueError, match='^t: needed: drive 1 \\("end_x"\\) is a point drive'):
        arm.inverse(q, v, acc)
    at1 = arm.inverse(q, v, acc, t=1.0)
    assert np.array_equal(at1.effort, arm.inverse(q, v, acc, t=np.full(n, 1.0)).effort)
    assert np.array_equal(at1.effort[3], arm.inverse(q[3], v[3], acc[3], t=1.0).effort)
    assert np.abs(at1.effort - res.effort).max() > 1.0  # the time reached the answer
    with pytest.raises(ValueError, match="^t: 2 values"):
        arm.inverse(q, v, acc, t=[0.0, 1.0])
    with pytest.raises(ValueError, match="^t: 2 values"):
        arm.inverse(q[0], v[0], acc[0], t=[0.0, 1.0])
    with pytest.raises(ValueError, match="^t: a number"):
        arm.inverse(q, v, acc, t="soon")
    tree = double_link([dict(body=1, f=vtdyn.Function.sine(0.5, 0.8, 2.0, 0.1))])
    qt, vt, at = rng.uniform(-1, 1, (5, 2)), rng.uniform(-1, 1, (5, 2)), rng.uniform(-1, 1, (5, 2))
    assert np.array_equal(tree.inverse(qt, vt, at).effort, tree.inverse(qt, vt, at, t=rng.uniform(0, 3, 5)).effort)


def test_analysis_errors():
    m = double_link([dict(body=2, f=0.0)])
    with pytest.raises(vtdyn.Error) as e:
        m.kinematic_analysis(1.0, forward_check=False)
    assert e.value.status == "VT_ERR_NOT_FULLY_DRIVEN" and str(e.value).startswith("kinematic_analysis: ")
    with pytest.raises(ValueError, match="^formulation: "):
        m.dynamic_analysis(1.0, formulation="implicit")
    with pytest.raises(ValueError, match="^q: "):
        m.dynamic_analysis(1.0, q=[0, 0, 0])
    with pytest.raises(ValueError, match="^qd: "):
        m.dynamic_analysis(1.0, qd=np.zeros((2, 2)))
    with pytest.raises(vtdyn.Error) as e:
        m.dynamic_analysis(1.0, tout=[0.5, 0.2])
    assert e.value.status == "VT_ERR_BAD_OPTION"
    with pytest.raises(vtdyn.Error) as e:
        m.dynamic_analysis(1.0, rtol=-1.0)
    assert e.value.status == "VT_ERR_BAD_OPTION"
    with pytest.raises(vtdyn.Error) as e:
        m.dynamic_analysis(1.0, nout=0)
    assert e.value.status == "VT_ERR_BAD_OPTION"


def test_kinematic_analysis_on_contacts():
    """a box heaving on its four corners, every rate driven: each corner carries m (g + z'') / 4
    (the rule's minimum forces, symmetric), the free root's efforts vanish, and the forward check
    under the ground's forces gives the motion back; a dynamic analysis refuses contacts; a fifth
    point put on the ground by the schedule takes its fifth of the load; pressed on its top (loads=)
    the corners carry the push too"""
    mass, (lx, ly, lz) = 12.0, (0.4, 0.2, 0.1)
    inertia = (mass / 12 * (ly * ly + lz * lz), mass / 12 * (lx * lx + lz * lz), mass / 12 * (lx * lx + ly * ly))
    b = vtdyn.Builder(gravity=(0, 0, -G))
    b.add_body(joint="free", mass=mass, inertia=inertia, name="box")
    b.add_drive(body=1, index=0, f=0.0)
    b.add_drive(body=1, index=1, f=0.0)
    b.add_drive(body=1, index=2, f=vtdyn.Function.sine(0.05, 0.02, 2.0))
    b.add_drive(body=1, kind="orientation", f=0.0)
    b.add_frame("top", body=1, point=(0.0, 0.0, lz / 2))
    m = b.build()
    corners = [(sx * lx / 2, sy * ly / 2, -lz / 2) for sx in (1, -1) for sy in (1, -1)]
    cs = m.contacts([vtdyn.Contact(body=1, point=p) for p in corners])
    q0 = np.array([0, 0, 0.05, 1, 0, 0, 0], dtype=float)
    tr = m.kinematic_analysis(2.0, nout=40, q=q0, contacts=cs, forward_check=bool(vtdyn.VT_HAVE_SUNDIALS))
    weight = mass * G
    zdd = -0.08 * np.sin(2 * tr.time)
    assert tr.contact_force.shape == (41, 4, 3)
    assert np.abs(tr.contact_force[:, :, 2] - (mass * (G + zdd) / 4)[:, None]).max() <= 1e-10 * weight
    assert np.abs(tr.contact_force[:, :, :2]).max() <= 1e-10 * weight
    assert np.abs(tr.qfrc_drive).max() <= 1e-10 * weight  # the box has no motor
    if bool(vtdyn.VT_HAVE_SUNDIALS):
        assert tr.fwd_err_q <= 1e-9
        with pytest.raises(vtdyn.Error) as e:
            m.dynamic_analysis(1.0, q=q0, contacts=cs)
        assert e.value.status == "VT_ERR_BAD_OPTION" and "contacts" in str(e.value)
    assert m.kinematic_analysis(1.0, nout=4, q=q0, forward_check=False).contact_force is None
    # pressed down on its top (loads= at the frame 'top'): the corners carry the push too
    tr = m.kinematic_analysis(2.0, nout=40, q=q0, contacts=cs, loads=[[0, 0, -50.0, 0, 0, 0]], load_frames="top",
                              forward_check=bool(vtdyn.VT_HAVE_SUNDIALS))
    assert np.abs(tr.contact_force[:, :, 2] - ((mass * (G + zdd) + 50.0) / 4)[:, None]).max() <= 1e-10 * weight
    if bool(vtdyn.VT_HAVE_SUNDIALS):
        assert tr.fwd_err_q <= 1e-9
    # a fifth point, under the centre, on the ground from t = 1 s on (active(t)): the five then
    # share the load equally (the smallest forces that hold it, the moments balanced by symmetry)
    cs5 = m.contacts([vtdyn.Contact(body=1, point=p) for p in corners + [(0.0, 0.0, -lz / 2)]])
    tr = m.kinematic_analysis(2.0, nout=40, q=q0, contacts=cs5, active=lambda t: [1, 1, 1, 1, t >= 1.0],
                              forward_check=bool(vtdyn.VT_HAVE_SUNDIALS))
    load = mass * (G - 0.08 * np.sin(2 * tr.time))
    on = tr.time >= 1.0
    assert 0 < on.sum() < len(on)
    assert np.abs(tr.contact_force[~on, :4, 2] - (load[~on] / 4)[:, None]).max() <= 1e-10 * weight
    assert np.abs(tr.contact_force[~on, 4]).max() == 0.0
    assert np.abs(tr.contact_force[on, :, 2] - (load[on] / 5)[:, None]).max() <= 1e-10 * weight
    if vtdyn.VT_HAVE_SUNDIALS:
        assert tr.fwd_err_q <= 1e-9
    # the schedule's own exception comes back as itself; a wrong length is a ValueError
    def broken(t):
        raise KeyError("no such gait")
    with pytest.raises(KeyError):
        m.kinematic_analysis(1.0, nout=4, q=q0, contacts=cs5, active=broken, forward_check=False)
    with pytest.raises(ValueError, match="^active\\(0\\): 2 flags for 5 contacts"):
        m.kinematic_analysis(1.0, nout=4, q=q0, contacts=cs5, active=lambda t: [1, 1], forward_check=False)
    with pytest.raises(ValueError):
        m.kinematic_analysis(1.0, nout=4, q=q0, active=lambda t: [1], forward_check=False)
