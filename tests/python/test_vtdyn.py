"""The Python package vtdyn (python/vtdyn) against Pinocchio and against itself.

Run by tests/python/run.sh (the meson test 'python') with the venv of tests/peers, which has pin
and example-robot-data, after `pip install .` of this tree into it.

* UR5, Panda, Solo-12 (root welded and floating) and Talos at 1,000 random states each:
  Model.inverse's efforts against pin.rnea and its world-axes joint reactions against
  Pinocchio's data.f less the actuation (f - S tau, turned into world axes), to 1e-12 of the
  largest torque or wrench component of the state; the reactions in the joint's frame
  (reaction_joint) against Pinocchio's local data.f less the actuation itself, and the bearing
  split along the joint's axis from it. A floating root's state is turned into
  Pinocchio's free flyer here: vtdyn's q = (x, y, z, w, qx, qy, qz) and world-axes rates
  (v = the root origin's velocity then the angular velocity; a = the origin's classical
  acceleration then the angular acceleration); Pinocchio's q = (x, y, z, qx, qy, qz, w) and
  root-frame rates: v_lin = R^T pdot, w = R^T omega, a_lin = R^T pddot - w x v_lin,
  a_ang = R^T omegadot; its tau of the root is vtdyn's world wrench turned into the root
  frame (R^T f, R^T n) (the formulas of tests/peers/pinocchio_reference.py).
* One state equals its row of a batch bitwise; threads 1, 2 and 4 give bitwise the same arrays;
  strided, Fortran-ordered, integer and list inputs give the same arrays as C-contiguous ones.
* Every error path: a wrong shape or a non-convertible dtype (ValueError naming the argument),
  a NaN row (vtdyn.Error with .row, .status, .code), a missing file (VT_ERR_FILE).
"""
import math
import threading
from importlib.metadata import distribution
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

import vtdyn

NSTATES = 1000
TOL = 1e-12
ROBOTS = {
    "UR5": "ur_description/urdf/ur5_robot.urdf",
    "Panda": "panda_description/urdf/panda.urdf",
    "Solo-12": "solo_description/robots/solo12.urdf",
    "Talos": "talos_data/robots/talos_reduced.urdf",
}


def robots_dir():
    dist = distribution("example-robot-data")
    urdf = next(Path(dist.locate_file(f)) for f in dist.files or [] if str(f).endswith(".urdf"))
    return Path(*urdf.parts[: urdf.parts.index("robots") + 1])


ROOT = robots_dir()


def urdf(name):
    return str(ROOT / ROBOTS[name])


def quat_to_rot(w, x, y, z):
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
    ])


def random_states(model, n, seed):
    """n random states in vtdyn's layout: joint coordinates within the limits (else [-pi, pi]),
    a floating root at a random position in [-1, 1]^3 with a uniform random unit quaternion;
    v and a uniform in [-2, 2]."""
    rng = np.random.default_rng(seed)
    q = np.empty((n, model.nq))
    lim = model.limits
    for b, (qa, nq, va, nv) in enumerate(model.body_index):
        if nq == 7:  # the floating root
            q[:, qa:qa + 3] = rng.uniform(-1, 1, (n, 3))
            e = rng.normal(size=(n, 4))
            q[:, qa + 3:qa + 7] = e / np.linalg.norm(e, axis=1, keepdims=True)
            continue
        assert nq == 1 and nv == 1, model.body_joint_names[b]
        lo, hi = lim[va, 0], lim[va, 1]
        if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
            lo, hi = -math.pi, math.pi
        q[:, qa] = rng.uniform(lo, hi, n)
    v = rng.uniform(-2, 2, (n, model.nv))
    a = rng.uniform(-2, 2, (n, model.nv))
    return q, v, a


def pinocchio_pair(name, floating):
    """the robot loaded by vtdyn and by Pinocchio, and vtdyn's bodies matched to Pinocchio's joints
    by the URDF joint's name ("root_joint": the free flyer): (b, j, qa, nq, va, nv, iq, iv) each"""
    m = vtdyn.load_urdf(urdf(name), floating=floating)
    pm = (pin.buildModelFromUrdf(urdf(name), pin.JointModelFreeFlyer()) if floating
          else pin.buildModelFromUrdf(urdf(name)))
    assert m.nv == pm.nv and m.nq == pm.nq
    joints = []
    for b, (qa, nq, va, nv) in enumerate(m.body_index):
        jname = "root_joint" if nq == 7 else m.body_joint_names[b]
        j = pm.getJointId(jname)
        assert j < pm.njoints, jname
        joints.append((b, j, qa, nq, va, nv, pm.joints[j].idx_q, pm.joints[j].idx_v))
    return m, pm, joints


def to_pinocchio(pm, joints, q, v, a):
    """one state in Pinocchio's layout: a free flyer's x y z, x y z w and its rates in the root's
    axes (its acceleration the spatial one: less ω × v); the root's rotation, its rates' indices"""
    qp, vp, ap = np.empty(pm.nq), np.empty(pm.nv), np.empty(pm.nv)
    root_R = None
    for b, j, qa, nq, va, nv, iq, iv in joints:
        if nq == 7:
            w, x, y, z = q[qa + 3:qa + 7]
            R = quat_to_rot(w, x, y, z)
            root_R = (R, iv, va)
            qp[iq:iq + 7] = np.r_[q[qa:qa + 3], x, y, z, w]
            vl, wl = R.T @ v[va:va + 3], R.T @ v[va + 3:va + 6]
            vp[iv:iv + 6] = np.r_[vl, wl]
            ap[iv:iv + 6] = np.r_[R.T @ a[va:va + 3] - np.cross(wl, vl), R.T @ a[va + 3:va + 6]]
        else:
            qp[iq], vp[iv], ap[iv] = q[qa], v[va], a[va]
    return qp, vp, ap, root_R


def effort_to_pinocchio(pm, joints, effort, root_R):
    """vtdyn's efforts of one state in Pinocchio's order, a free root's turned into its axes"""
    tau = np.empty(pm.nv)
    for b, j, qa, nq, va, nv, iq, iv in joints:
        tau[iv:iv + nv] = effort[va:va + nv]
    if root_R is not None:
        R, iv, va = root_R
        tau[iv:iv + 3] = R.T @ effort[va:va + 3]
        tau[iv + 3:iv + 6] = R.T @ effort[va + 3:va + 6]
    return tau


def compare_with_pinocchio(name, floating):
    m, pm, joints = pinocchio_pair(name, floating)
    pd, kin = pm.createData(), pm.createData()
    q, v, a = random_states(m, NSTATES, seed=len(name) + 10 * floating)
    r = m.inverse(q, v, a)
    assert r.effort.shape == (NSTATES, m.nv) and r.reaction.shape == (NSTATES, m.nbody, 6)
    worst = 0.0
    for s in range(NSTATES):
        qp, vp, ap, root_R = to_pinocchio(pm, joints, q[s], v[s], a[s])
        tau = pin.rnea(pm, pd, qp, vp, ap) + pm.damping * vp + pm.friction * np.sign(vp)  # <dynamics>, as vtdyn
        pin.forwardKinematics(pm, kin, qp)
        mine_tau = effort_to_pinocchio(pm, joints, r.effort[s], root_R)
        ref_w, mine_w = [], []
        for b, j, qa, nq, va, nv, iq, iv in joints:
            S = np.asarray(pd.joints[j].S).reshape(6, nv)
            fr = pd.f[j].vector - S @ (S.T @ pd.f[j].vector)  # less the actuation (the joint's S^T f)
            Rj = kin.oMi[j].rotation
            ref_w.append(np.r_[Rj @ fr[:3], Rj @ fr[3:]])
            mine_w.append(r.reaction[s, b])
            # in the joint's frame: Pinocchio's own (the URDF joint frame); the bearing split
            # along its axis (S's angular part for a revolute joint, linear for a prismatic one)
            ref_w.append(fr)
            mine_w.append(r.reaction_joint[s, b])
            if nv == 1:
                u = S[3:, 0] if np.linalg.norm(S[3:, 0]) > 0 else S[:3, 0]
                u = u / np.linalg.norm(u)
                fa, na = u @ fr[:3], u @ fr[3:]
                ref_w.append(np.r_[fa, np.linalg.norm(fr[:3] - fa * u), na, np.linalg.norm(fr[3:] - na * u), 0, 0])
                mine_w.append(np.r_[r.bearing[s, b], 0, 0])
        ref_w, mine_w = np.array(ref_w), np.array(mine_w)
        scale = max(1.0, np.abs(tau).max(), np.abs(ref_w).max())
        worst = max(worst, np.abs(mine_tau - tau).max() / scale, np.abs(mine_w - ref_w).max() / scale)
    assert worst <= TOL, "%s%s: largest relative difference %.3g" % (name, " floating" if floating else "", worst)
    # the body axes' arrays are the world ones turned: the same norms per force and moment
    for world, body in ((r.reaction, r.reaction_body), (r.total, r.total_body)):
        for part in (slice(0, 3), slice(3, 6)):
            nw, nb = np.linalg.norm(world[..., part], axis=-1), np.linalg.norm(body[..., part], axis=-1)
            assert np.allclose(nw, nb, rtol=1e-12, atol=1e-12 * max(1.0, nw.max()))
    return worst


@pytest.mark.parametrize("name,floating", [("UR5", False), ("Panda", False), ("Solo-12", False),
                                           ("Solo-12", True), ("Talos", False), ("Talos", True)])
def test_against_pinocchio(name, floating):
    worst = compare_with_pinocchio(name, floating)
    print("%s%s: %d states, largest relative difference %.2g" % (name, " floating" if floating else "", NSTATES, worst))


@pytest.mark.parametrize("name,floating,frames", [("UR5", False, ["tool0", "wrist_1_link", "tool0"]),
                                                  ("Solo-12", True, ["FL_FOOT", "HR_FOOT", "base_link"])])
def test_loads_against_pinocchio(name, floating, frames):
    """loads at frames (force, then moment about the frame's origin, world axes) against
    Pinocchio's rnea with fext: each wrench moved to the world origin and into its frame's parent
    joint's axes (oMi.actInv), a frame named twice summed; 200 random states (1e-12 of the
    largest effort); one state as its row; shapes and names refused naming the argument"""
    m, pm, joints = pinocchio_pair(name, floating)
    pd = pm.createData()
    n = 200
    q, v, a = random_states(m, n, seed=31)
    rng = np.random.default_rng(32)
    w = rng.uniform(-30, 30, (n, len(frames), 6))
    r = m.inverse(q, v, a, loads=w, load_frames=frames, threads=2)
    pos, _ = m.frame_poses(q, frames)
    fids = [pm.getFrameId(f, pin.FrameType.BODY) for f in frames]
    worst = 0.0
    for s in range(n):
        qp, vp, ap, root_R = to_pinocchio(pm, joints, q[s], v[s], a[s])
        pin.forwardKinematics(pm, pd, qp)
        fext = [pin.Force.Zero() for _ in range(pm.njoints)]
        for k, f in enumerate(fids):
            j = pm.frames[f].parentJoint
            at_origin = pin.Force(w[s, k, :3], w[s, k, 3:] + np.cross(pos[s, k], w[s, k, :3]))
            fext[j] += pd.oMi[j].actInv(at_origin)
        tau = pin.rnea(pm, pd, qp, vp, ap, fext) + pm.damping * vp + pm.friction * np.sign(vp)
        mine = effort_to_pinocchio(pm, joints, r.effort[s], root_R)
        worst = max(worst, np.abs(mine - tau).max() / max(1.0, np.abs(tau).max()))
    print("%s: loads at %s, largest relative difference %.2g" % (name, frames, worst))
    assert worst <= TOL, worst
    none = m.inverse(q, v, a, threads=2)
    assert np.abs(none.effort - r.effort).max() > 1.0  # the loads change the efforts
    one = m.inverse(q[5], v[5], a[5], loads=w[5], load_frames=frames)
    assert np.array_equal(one.effort, r.effort[5]) and np.array_equal(one.reaction, r.reaction[5])
    with pytest.raises(ValueError, match="loads given without load_frames"):
        m.inverse(q, v, a, loads=w)
    with pytest.raises(ValueError, match="load_frames: 'nose' is not a frame"):
        m.inverse(q, v, a, loads=w[:, :1], load_frames=["nose"])
    with pytest.raises(ValueError, match="loads: expected N x 3 x 6"):
        m.inverse(q, v, a, loads=w[:, :, :5], load_frames=frames)
    with pytest.raises(ValueError, match="loads: expected N x 3 x 6"):
        m.inverse(q, v, a, loads=w[:7], load_frames=frames)
    w[9, 1, 2] = np.nan
    with pytest.raises(vtdyn.Error) as e:
        m.inverse(q, v, a, loads=w, load_frames=frames)
    assert e.value.status == "VT_ERR_NONFINITE" and e.value.row == 9


@pytest.fixture(scope="module")
def ur5():
    return vtdyn.load_urdf(urdf("UR5"))


def test_model(ur5):
    assert ur5.nq == ur5.nv == ur5.nbody == 6
    assert ur5.joint_names == ("shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint", "wrist_1_joint",
                               "wrist_2_joint", "wrist_3_joint")
    assert ur5.body_names[0] == "shoulder_link" and "tool0" in ur5.frame_names
    assert ur5.masses.shape == (6,) and ur5.masses[0] == 3.7
    assert list(ur5.gravity) == [0.0, 0.0, -9.81]
    assert not ur5.floating
    solo = vtdyn.load_urdf(urdf("Solo-12"), floating=True)
    assert solo.floating and solo.nq == 19 and solo.nv == 18
    assert solo.joint_names[0] == "base_link" and list(solo.q0[:7]) == [0, 0, 0, 1, 0, 0, 0]
    assert isinstance(vtdyn.__version__, str) and vtdyn.__version__.count(".") == 2


def test_one_state_is_its_row_bitwise(ur5):
    q, v, a = random_states(ur5, 50, seed=3)
    r = ur5.inverse(q, v, a)
    for s in (0, 17, 49):
        one = ur5.inverse(q[s], v[s], a[s])
        assert one.effort.shape == (6,) and one.reaction.shape == (6, 6)
        for k in range(5):
            assert np.array_equal(one[k], r[k][s])


def test_outputs_selected(ur5):
    """outputs= gives the fields asked for bitwise as the full call, None for the others; names
    that are not Result's fields are refused, naming the argument"""
    q, v, a = random_states(ur5, 64, seed=11)
    full = ur5.inverse(q, v, a, threads=1)
    some = ur5.inverse(q, v, a, threads=1, outputs=("effort", "reaction", "bearing"))
    assert vtdyn.Result.n_fields == 12
    for name in ("effort", "reaction", "reaction_body", "total", "total_body", "reaction_joint", "bearing",
                 "limit_excess", "effort_parts", "contact_force", "qdd", "drive_effort"):
        if name in ("effort", "reaction", "bearing"):
            assert np.array_equal(getattr(some, name), getattr(full, name)), name
        else:
            assert getattr(some, name) is None, name
    # a tree: q'' is a's back, bitwise; no drives, no drive efforts
    assert np.array_equal(full.qdd, a) and full.drive_effort.shape == (64, 0)
    one = ur5.inverse(q[3], v[3], a[3], outputs=["effort"])
    assert np.array_equal(one.effort, full.effort[3]) and one.reaction is None
    assert ur5.inverse(q, v, a, outputs=()).effort is None
    for bad, says in ((("effort", "torque"), "'torque' is not a field"), ("effort", "not one string"),
                      (3, "not int"), ((1,), "1 is not a field")):
        with pytest.raises(ValueError, match="outputs: .*" + says):
            ur5.inverse(q, v, a, outputs=bad)


def test_out_reused(ur5):
    """out= writes an earlier Result's arrays again: the same objects, bitwise the fresh call's
    values; a Result of other shapes, a field left out, read-only arrays and arrays sharing the
    inputs' memory are refused, naming the field"""
    q, v, a = random_states(ur5, 32, seed=12)
    q2, v2, a2 = random_states(ur5, 32, seed=13)
    outs = ("effort", "reaction", "total")
    r = ur5.inverse(q, v, a, threads=1, outputs=outs)
    keep = r.effort
    r2 = ur5.inverse(q2, v2, a2, threads=1, outputs=outs, out=r)
    fresh = ur5.inverse(q2, v2, a2, threads=1, outputs=outs)
    assert r2.effort is keep and r.effort is keep
    for name in outs:
        assert np.array_equal(getattr(r2, name), getattr(fresh, name)), name
    with pytest.raises(ValueError, match="out.effort: not a writeable C-contiguous"):
        ur5.inverse(q[:5], v[:5], a[:5], outputs=outs, out=r)
    with pytest.raises(ValueError, match="out.reaction_body: an array is needed"):
        ur5.inverse(q, v, a, outputs=outs + ("reaction_body",), out=r)
    with pytest.raises(ValueError, match="out: a vtdyn.Result"):
        ur5.inverse(q, v, a, out=(1, 2))
    keep.flags.writeable = False
    with pytest.raises(ValueError, match="out.effort: not a writeable"):
        ur5.inverse(q, v, a, outputs=outs, out=r)
    keep.flags.writeable = True
    buf = np.zeros((32, 6))
    alias = ur5.inverse(buf, v, a, outputs=("effort",))
    with pytest.raises(ValueError, match="out.effort: shares memory with q"):
        ur5.inverse(alias.effort, v, a, outputs=("effort",), out=alias)


@pytest.mark.parametrize("name,floating", [("UR5", False), ("Talos", False), ("Solo-12", True)])
def test_threads_bitwise(name, floating):
    m = vtdyn.load_urdf(urdf(name), floating=floating)
    q, v, a = random_states(m, 257, seed=5)
    ref = m.inverse(q, v, a, threads=1)
    for t in (2, 4, 0):
        got = m.inverse(q, v, a, threads=t)
        for k in range(5):
            assert np.array_equal(got[k], ref[k]), (t, k)


def test_layouts_and_types(ur5):
    q, v, a = random_states(ur5, 40, seed=9)
    ref = ur5.inverse(q, v, a)
    wide = np.zeros((40, 20))
    wide[:, 3:9], wide[:, 10:16] = q, v  # rows in a wider table: strided, passed as they are
    wa = np.zeros((80, 6))
    wa[::2] = a  # every other row: strided rows
    for args in ((wide[:, 3:9], wide[:, 10:16], wa[::2]),
                 (np.asfortranarray(q), v.tolist(), a),  # copies
                 (q[::-1][::-1], v.astype(">f8"), a)):  # big-endian: converted
        got = ur5.inverse(*args)
        for k in range(5):
            assert np.array_equal(got[k], ref[k])
    zi = ur5.inverse(np.zeros((2, 6), dtype=np.int32), [[0] * 6] * 2, np.zeros((2, 6), dtype=np.int64))
    z = ur5.inverse(np.zeros((2, 6)), np.zeros((2, 6)), np.zeros((2, 6)))
    assert np.array_equal(zi.effort, z.effort)
    empty = ur5.inverse(np.zeros((0, 6)), np.zeros((0, 6)), np.zeros((0, 6)))
    assert empty.effort.shape == (0, 6) and empty.reaction.shape == (0, 6, 6)


def test_python_threads(ur5):
    q, v, a = random_states(ur5, 2000, seed=11)
    ref = ur5.inverse(q, v, a, threads=1)
    out = [None] * 4

    def work(k):
        out[k] = ur5.inverse(q, v, a, threads=1 + k % 2)

    ts = [threading.Thread(target=work, args=(k,)) for k in range(4)]
    for t in ts:
        t.start()
    for t in ts:
        t.join()
    for r in out:
        assert np.array_equal(r.effort, ref.effort) and np.array_equal(r.reaction, ref.reaction)


def test_value_errors(ur5):
    z6, z7 = np.zeros(6), np.zeros(7)
    cases = [
        ((z7, z6, z6), "q"),  # a state of 7
        ((z6, z7, z6), "v"),
        ((z6, z6, z7), "a"),
        ((np.zeros((2, 6)), np.zeros((3, 6)), np.zeros((2, 6))), "v"),  # row counts
        ((np.zeros((2, 6)), np.zeros((2, 6)), np.zeros((1, 6))), "a"),
        ((np.zeros((2, 6)), z6, z6), "v"),  # 2-D and 1-D mixed
        ((np.zeros((2, 2, 6)), z6, z6), "q"),  # 3-D
        ((np.float64(1.0), z6, z6), "q"),  # 0-D
        ((z6, np.zeros(6, dtype=complex), z6), "v"),  # not convertible
        ((z6, z6, ["x"] * 6), "a"),
        ((z6, z6, None), "a"),
    ]
    for args, name in cases:
        with pytest.raises(ValueError, match="^%s: " % name):
            ur5.inverse(*args)
    with pytest.raises(ValueError, match="^threads: "):
        ur5.inverse(z6, z6, z6, threads=-1)
    with pytest.raises(TypeError):
        ur5.inverse(z6, z6)


def test_library_errors(ur5):
    q, v, a = random_states(ur5, 100, seed=13)
    v[37, 2] = np.nan
    a[60, 0] = np.inf
    with pytest.raises(vtdyn.Error) as e:
        ur5.inverse(q, v, a, threads=2)
    err = e.value
    assert err.row == 37 and err.status == "VT_ERR_NONFINITE" and err.code == -3
    assert str(err).startswith("row 37: ")
    assert isinstance(err, RuntimeError)
    with pytest.raises(vtdyn.Error) as e:
        ur5.inverse(q[37], v[37], a[37])
    assert e.value.row is None and e.value.status == "VT_ERR_NONFINITE" and not str(e.value).startswith("row")
    with pytest.raises(vtdyn.Error) as e:
        vtdyn.load_urdf("/nonexistent/robot.urdf")
    assert e.value.status == "VT_ERR_FILE" and e.value.code == -31 and e.value.row is None
    assert "/nonexistent/robot.urdf" in str(e.value)
    # a floating root's quaternion of zero norm
    solo = vtdyn.load_urdf(urdf("Solo-12"), floating=True)
    q = solo.q0.copy()
    q[3] = 0.0
    with pytest.raises(vtdyn.Error) as e:
        solo.inverse(q, np.zeros(18), np.zeros(18))
    assert e.value.status == "VT_ERR_QUATERNION"


def test_joint_params_and_parts():
    """joint_params on Panda (whose file declares <dynamics>): each effort is the ideal joints'
    (dynamics=False) plus armature a + damping v + friction sign(v) of the values given, to 1e-12
    of the largest; effort_parts those three; the file's own <dynamics> by default, likewise"""
    path = urdf("Panda")
    ideal = vtdyn.load_urdf(path, dynamics=False)
    names = ideal.joint_names
    params = {n: (0.1 + 0.05 * k, 0.5 + 0.1 * k, 0.2 * k) for k, n in enumerate(names)}
    robot = vtdyn.load_urdf(path, joint_params=params)
    q, v, a = random_states(robot, 200, seed=21)
    r0, r = ideal.inverse(q, v, a), robot.inverse(q, v, a)
    arm = np.array([params[n][0] for n in names])
    damp = np.array([params[n][1] for n in names])
    fric = np.array([params[n][2] for n in names])
    parts = np.stack([arm * a, damp * v, fric * np.sign(v)], axis=1)
    scale = np.abs(r.effort).max()
    assert np.abs(r.effort - r0.effort - parts.sum(axis=1)).max() <= 1e-12 * scale
    assert np.abs(r.effort_parts - parts).max() <= 1e-12 * scale
    assert np.abs(r.reaction - r0.reaction).max() <= 1e-12 * np.abs(r0.reaction).max()  # reactions unchanged
    # the file's <dynamics>: friction and damping only, as Pinocchio reads them
    own = vtdyn.load_urdf(path).inverse(q, v, a)
    pm = pin.buildModelFromUrdf(path)
    assert np.abs(own.effort_parts[:, 0]).max() == 0.0
    d = own.effort - r0.effort
    assert np.abs(d).max() > 0.0
    assert np.abs(own.effort_parts.sum(axis=1) - d).max() <= 1e-12 * scale
    with pytest.raises(vtdyn.Error) as e:
        vtdyn.load_urdf(path, joint_params={"no_such_joint": (0, 0, 0)})
    assert e.value.status == "VT_ERR_NOT_FOUND" and "no_such_joint" in str(e.value)
    with pytest.raises(vtdyn.Error) as e:
        vtdyn.load_urdf(path, joint_params={names[0]: (0, -1, 0)})
    assert e.value.status == "VT_ERR_BAD_OPTION"
    with pytest.raises(ValueError):
        vtdyn.load_urdf(path, joint_params={names[0]: (0, 1)})
    assert pm.nv == robot.nv


def test_payload_as_edited_file(tmp_path):
    """a payload given to load_urdf equals the file with the payload written in as a link fixed to
    its link (the loader's own merge), to 1e-15 of the largest output"""
    path = urdf("UR5")
    text = open(path).read()
    link = vtdyn.load_urdf(path).body_names[-1]
    com, inertia = (0.02, -0.05, 0.11), ((0.03, 0.001, -0.002), (0.001, 0.02, 0.003), (-0.002, 0.003, 0.025))
    cut = text.rindex("</robot>")
    edited = tmp_path / "ur5_payload.urdf"
    edited.write_text(text[:cut] + (
        '<link name="payload"><inertial><origin xyz="%r %r %r"/><mass value="2.5"/>'
        '<inertia ixx="%r" ixy="%r" ixz="%r" iyy="%r" iyz="%r" izz="%r"/></inertial></link>'
        '<joint name="grip" type="fixed"><parent link="%s"/><child link="payload"/></joint>'
        % (com + (inertia[0][0], inertia[0][1], inertia[0][2], inertia[1][1], inertia[1][2], inertia[2][2], link)))
        + text[cut:])
    a_model = vtdyn.load_urdf(path, payloads=[(link, 2.5, com, inertia)])
    b_model = vtdyn.load_urdf(str(edited))
    q, v, a = random_states(a_model, 50, seed=22)
    ra, rb = a_model.inverse(q, v, a), b_model.inverse(q, v, a)
    for x, y in ((ra.effort, rb.effort), (ra.reaction, rb.reaction), (ra.reaction_joint, rb.reaction_joint)):
        assert np.abs(x - y).max() <= 1e-15 * np.abs(y).max()
    plain = vtdyn.load_urdf(path).inverse(q, v, a)
    assert np.abs(plain.effort - ra.effort).max() > 1e-3
    with pytest.raises(ValueError):
        vtdyn.load_urdf(path, payloads=[(link, 2.5)])
    with pytest.raises(vtdyn.Error) as e:
        vtdyn.load_urdf(path, payloads=[("no_link", 1.0, (0, 0, 0))])
    assert e.value.status == "VT_ERR_NOT_FOUND"


@pytest.mark.parametrize("name,floating", [("UR5", False), ("Solo-12", True)])
def test_frame_poses_against_pinocchio(name, floating):
    """Model.frame_poses against Pinocchio's framesForwardKinematics (oMf) for every link frame
    at 100 random configurations (1e-12)"""
    m = vtdyn.load_urdf(urdf(name), floating=floating)
    pm = (pin.buildModelFromUrdf(urdf(name), pin.JointModelFreeFlyer()) if floating
          else pin.buildModelFromUrdf(urdf(name)))
    pd = pm.createData()
    q, _, _ = random_states(m, 100, seed=21)
    frames = [f for f in m.frame_names if pm.existFrame(f, pin.FrameType.BODY)]
    pos, rot = m.frame_poses(q, frames)
    assert pos.shape == (100, len(frames), 3) and rot.shape == (100, len(frames), 3, 3)
    ids = [pm.getFrameId(f, pin.FrameType.BODY) for f in frames]
    jq = {n: pm.joints[pm.getJointId(n)].idx_q for n in m.joint_names if pm.existJointName(n)}
    worst = 0.0
    for s in range(100):
        qp = pin.neutral(pm)
        if floating:  # vtdyn: x y z, w x y z; Pinocchio: x y z, x y z w
            qp[:3], qp[3:6], qp[6] = q[s, :3], q[s, 4:7], q[s, 3]
        for k, n in enumerate(m.joint_names):
            if n in jq:
                qp[jq[n]] = q[s, m.body_index[k][0]]
        pin.framesForwardKinematics(pm, pd, qp)
        for k, f in enumerate(ids):
            worst = max(worst, np.abs(pos[s, k] - pd.oMf[f].translation).max(),
                        np.abs(rot[s, k] - pd.oMf[f].rotation).max())
    assert worst <= 1e-12, worst
    one = m.frame_poses(q[7], frames[0])
    assert np.array_equal(one[0][0], pos[7, 0]) and np.array_equal(one[1][0], rot[7, 0])
    with pytest.raises(ValueError, match="frames: 'nose' is not a frame"):
        m.frame_poses(q, ["nose"])
    with pytest.raises(ValueError, match="q: "):
        m.frame_poses(q[:, :3])


def test_qfrc_applied(ur5):
    """qfrc: the efforts less the applied generalized forces (the instant is linear in them);
    the reactions unchanged on joints whose rates only carry it (every UR5 joint: one rate each,
    the applied force acting along it), shapes refused naming the argument"""
    q, v, a = random_states(ur5, 40, seed=14)
    rng = np.random.default_rng(15)
    qf = rng.uniform(-5, 5, (40, 6))
    r0 = ur5.inverse(q, v, a, threads=1)
    r1 = ur5.inverse(q, v, a, threads=1, qfrc=qf)
    scale = np.abs(r0.effort).max() + 5
    assert np.abs(r1.effort - (r0.effort - qf)).max() <= 1e-12 * scale
    assert np.abs(r1.reaction - r0.reaction).max() <= 1e-12 * np.abs(r0.reaction).max()
    one = ur5.inverse(q[3], v[3], a[3], qfrc=qf[3])
    assert np.array_equal(one.effort, r1.effort[3])
    with pytest.raises(ValueError, match="qfrc: "):
        ur5.inverse(q, v, a, qfrc=qf[:5])
    with pytest.raises(ValueError, match="qfrc: "):
        ur5.inverse(q, v, a, qfrc=qf[:, :4])
