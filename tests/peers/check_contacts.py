#!/usr/bin/env python3
"""`vtdyn inverse --floating --contacts` on Solo-12 against Pinocchio (run by run_peer.sh with the
venv's python, which has pin, numpy and example-robot-data).

    check_contacts.py VTDYN WORKDIR

Solo-12 (example-robot-data's solo12.urdf) on its four feet FL_FOOT ... HR_FOOT (the URDF links
whose frame origins are the feet's points; the front feet mu 0.8, the hind 0.6) at states made
here in Pinocchio's terms (q with the free flyer's (x y z qx qy qz qw), v and a in the base's
LOCAL axes) and written as vtdyn's columns (world axes, docs/command.md):
  (a) standing: HAA 0, HFE +-0.8, KFE -+1.6, the base level at the height that puts the four
      feet (Pinocchio's frames) on z = 0, at rest, four feet on the ground;
  (b) random states near it (joints, velocities, accelerations, a small base motion), four feet;
  (c) three feet on the ground (C_active 0 on the fourth, the base accelerated toward the
      lifted foot so that the load can stay inside the three), and rows on a diagonal pair with
      the motion given whole (refused: the pair's forces make no moment about their line);
  (t) trotting: a diagonal pair on the ground (FL + HR or FR + HL), the rest as (c)'s, but the
      base's angular acceleration along the pair's line chosen here with Pinocchio alone so that
      the base's wrench has no moment about that line: n . rnea(q, v, a)[:6] = 0, n the base
      twist that leaves both feet still (the null vector of the feet's base Jacobian rows, by
      SVD: a turn about their line), rnea affine in a, so two calls give the value;
  (d) a row falling faster than gravity and one thrown sideways beyond friction, four feet.
vtdyn stops a run at the first row its contacts cannot carry: the row it names is removed and the
file run again, until it runs through. Each refusal must name its row and say why (a contact that
would pull or slip, or the active contacts that cannot give the root's force); a two-foot row's
refusal is checked independently (no ground forces at the two points balance the base: the least
squares residual of the base's six equations is not zero), (d)'s by the total force the base
needs (downward, or more sideways than mu cos(pi/4) times its upward part), and any other
refusal when quadprog is importable (the same QP reported infeasible). Which contact a
refusal names is the solver's choice among those that fail together: not checked.

For every accepted row, with Pinocchio's free-flyer model of the same file:
  * tau = rnea(q, v, a) - sum_c J_c^T f_c (J_c the foot frame's Jacobian, LOCAL_WORLD_ALIGNED,
    linear rows; f_c vtdyn's C_fx C_fy C_fz): the base's six components zero to 1e-9 of the
    weight (the free root carries nothing) and the twelve joints' equal to vtdyn's J_effort to
    1e-9 of the larger of the row's largest effort and the weight; vtdyn's own root efforts zero
    to the same;
  * every trotting row accepted;
  * the forces: an active foot's fz >= 0 and |fx|, |fy| <= mu cos(pi/4) fz (the 4-face pyramid,
    x and y its tangents), an inactive foot's exactly 0;
  * the forces are the rule's (docs/contact.md: least squared joint efforts, then 1e-4 N^-2 the
    squared forces): the KKT system of that QP, solved here with numpy on the pyramid faces vtdyn's
    forces lie on, gives the same forces to 1e-9 of the weight with non-negative multipliers and
    every other face satisfied: the optimum, certified without vtdyn's solver;
  * standing: on a copy of the URDF made exactly left/right symmetric (its right upper legs'
    centre of mass x of -1.377e-5 m set to the left's +1.377e-5) the left and right feet carry
    the same force (fz equal, fx equal, fy opposite) to 1e-9 of the weight; on the file itself
    the difference is printed.
The same states as a NumPy .npy file (numpy.save of a structured array, -j 2) give the same
doubles as the CSV run, bitwise (the documented contract: a CSV cell reads back as the double).
Exit 0 when every check holds, 1 otherwise.
"""
import csv
import math
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pinocchio as pin

from run_pinocchio import robots_dir

FEET = ("FL_FOOT", "FR_FOOT", "HL_FOOT", "HR_FOOT")
MU = {"FL_FOOT": 0.8, "FR_FOOT": 0.8, "HL_FOOT": 0.6, "HR_FOOT": 0.6}
MIRROR = {"FL_FOOT": "FR_FOOT", "HL_FOOT": "HR_FOOT"}
COS = math.cos(math.pi / 4)  # the command's pyramid: 4 faces inscribed in the cone
W_CONTACT = 1e-4  # VT_CONTACT_WEIGHT, the rule's weight on the squared forces (N^-2)
TOL = 1e-9
ROOT = "base_link"  # --floating with no floating joint: the columns take the root link's name
ROOT_IN = [ROOT + "_" + c for c in "x y z qw qx qy qz vx vy vz wx wy wz ax ay az alx aly alz".split()]
ROOT_EFFORT = [ROOT + "_effort_" + c for c in ("fx", "fy", "fz", "nx", "ny", "nz")]
STAND = {"HAA": 0.0, "F_HFE": 0.8, "F_KFE": -1.6, "H_HFE": -0.8, "H_KFE": 1.6}


def run(*args):
    return subprocess.run([str(a) for a in args], capture_output=True, text=True)


class Robot:
    """Pinocchio's free-flyer Solo-12 and the conversions to vtdyn's columns"""

    def __init__(self, urdf):
        self.model = pin.buildModelFromUrdf(str(urdf), pin.JointModelFreeFlyer())
        self.data = self.model.createData()
        self.joints = [self.model.names[j] for j in range(2, self.model.njoints)]
        self.iq = {n: self.model.joints[self.model.getJointId(n)].idx_q for n in self.joints}
        self.iv = {n: self.model.joints[self.model.getJointId(n)].idx_v for n in self.joints}
        self.feet = [self.model.getFrameId(f) for f in FEET]
        for f, fid in zip(FEET, self.feet):
            if fid >= len(self.model.frames):
                raise ValueError("Pinocchio has no frame " + f)
        self.weight = sum(self.model.inertias[i].mass for i in range(self.model.njoints)) * 9.81

    def standing_q(self):
        """the standing pose, its base level and at the height that puts the feet on z = 0"""
        q = pin.neutral(self.model)
        for n in self.joints:
            leg, kind = n.split("_")
            q[self.iq[n]] = STAND["HAA"] if kind == "HAA" else STAND[leg[0] + "_" + kind]
        z = self.feet_positions(q)[:, 2]
        if np.ptp(z) > 1e-12:  # the legs are alike and bent alike: their feet level
            raise ValueError("the standing pose's feet are not level: z %s" % z)
        q[2] = -z.mean()
        return q

    def feet_positions(self, q):
        pin.framesForwardKinematics(self.model, self.data, q)
        return np.array([self.data.oMf[f].translation for f in self.feet])

    def columns(self):
        return ROOT_IN + sum(([j, j + "_vel", j + "_acc"] for j in self.joints), []) + [f + "_active" for f in FEET]

    def row(self, q, v, a, active):
        """vtdyn's columns of the state: the root in world axes (docs/command.md, Robots):
        R_v = R v_lin, R_w = R w, R_a = R (a_lin + w x v_lin), R_al = R dw"""
        R = pin.Quaternion(q[3:7]).toRotationMatrix()  # Pinocchio's quaternion: (x, y, z, w)
        vl, w, al, dw = v[0:3], v[3:6], a[0:3], a[3:6]
        root = list(q[0:3]) + [q[6], q[3], q[4], q[5]]
        root += list(R @ vl) + list(R @ w) + list(R @ (al + np.cross(w, vl))) + list(R @ dw)
        js = sum(([q[self.iq[j]], v[self.iv[j]], a[self.iv[j]]] for j in self.joints), [])
        return [float(x) for x in root + js] + [1.0 if x else 0.0 for x in active]

    def tau0_and_jacobians(self, q, v, a):
        """rnea (no contact force) and the feet's Jacobians (linear rows, LOCAL_WORLD_ALIGNED:
        the point's velocity in world axes for Pinocchio's v, so J^T f is f's generalized force)"""
        tau0 = pin.rnea(self.model, self.data, q, v, a).copy()
        pin.computeJointJacobians(self.model, self.data, q)
        pin.updateFramePlacements(self.model, self.data)
        J = [pin.getFrameJacobian(self.model, self.data, f, pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)[:3].copy()
             for f in self.feet]
        return tau0, J


def pyramid(mu):
    """the unilateral contact's constraints g . f >= 0: pushing, and the 4 faces (tangents x, y)"""
    m = mu * COS
    return np.array([[0, 0, 1], [-1, 0, m], [1, 0, m], [0, -1, m], [0, 1, m]], dtype=float)


def pyramid_rows(idx, n3, mus=None):
    """the active feet's pyramid rows (5 a foot) over the stacked forces (n3 = 3 a foot); mus:
    each contact's mu (default Solo-12's feet's)"""
    mus = mus or [MU[f] for f in FEET]
    G = np.zeros((5 * len(idx), n3))
    for k, c in enumerate(idx):
        G[5 * k:5 * k + 5, 3 * k:3 * k + 3] = pyramid(mus[c])
    return G


def rule_kkt(tau0, J, act, force, weight, mus=None):
    """The rule's optimum, certified: minimize 1/2 |tau_j|^2 + 1/2 w |F|^2, tau = tau0 - Jall^T F,
    subject to tau_base = 0 and the pyramids. The faces vtdyn's forces lie on (within 1e-9 of the
    weight) are taken as equalities and the KKT system solved by numpy; returns the forces, the
    smallest multiplier of those faces and the worst violation of the other faces. Convex: if the
    multipliers are >= 0 and every face holds, these forces are the optimum. J, act, force: one
    a contact; mus: each contact's mu (default Solo-12's feet's)."""
    idx = [c for c in range(len(act)) if act[c]]
    Jall = np.vstack([J[c] for c in idx])  # 3n x 18
    Jb, Jj = Jall[:, :6], Jall[:, 6:]
    n3 = Jall.shape[0]
    H = Jj @ Jj.T + W_CONTACT * np.eye(n3)
    g = Jj @ tau0[6:]
    G = pyramid_rows(idx, n3, mus)
    Fv = np.concatenate([force[c] for c in idx])
    on = np.abs(G @ Fv) <= TOL * weight
    GA = G[on]
    na = GA.shape[0]
    K = np.zeros((n3 + 6 + na, n3 + 6 + na))
    K[:n3, :n3] = H
    K[:n3, n3:n3 + 6] = -Jb
    K[:n3, n3 + 6:] = -GA.T
    K[n3:n3 + 6, :n3] = Jb.T
    K[n3 + 6:, :n3] = GA
    rhs = np.concatenate([g, tau0[:6], np.zeros(na)])
    sol = np.linalg.lstsq(K, rhs, rcond=None)[0]
    F = sol[:n3]
    mult = sol[n3 + 6:]
    full = np.zeros((len(act), 3))
    for k, c in enumerate(idx):
        full[c] = F[3 * k:3 * k + 3]
    viol = max(0.0, -(G[~on] @ F).min()) if (~on).any() else 0.0
    scale = max(1.0, np.abs(sol[n3:]).max()) if sol.size > n3 else 1.0
    return full, (mult.min() / scale if na else 0.0), viol, int(na), float(np.linalg.norm(K @ sol - rhs))


def refusal_is_infeasible(q, tau0, J, act):
    """Independent evidence that a row cannot be carried: True when the total force the base needs
    points down or beyond friction, or when the base's six equations
    Jb^T F = tau0_base have no solution at all (least squares residual, two point feet cannot
    give a moment about their line); else, with quadprog importable, its verdict on the same
    QP; None when neither can say."""
    idx = [c for c in range(len(FEET)) if act[c]]
    if not idx:
        return True
    # the feet's forces add up to the force the base needs, R tau0[:3] in world axes (tau0's base
    # force is in the base's axes): pushing feet give an upward total, and friction a sideways one
    # of at most max(mu) cos(pi/4) times it
    R = pin.Quaternion(q[3:7]).toRotationMatrix()
    total = R @ tau0[:3]
    if total[2] < 0 or max(abs(total[0]), abs(total[1])) > max(MU[FEET[c]] for c in idx) * COS * total[2]:
        return True
    Jall = np.vstack([J[c] for c in idx])
    Jb, Jj = Jall[:, :6], Jall[:, 6:]
    F = np.linalg.lstsq(Jb.T, tau0[:6], rcond=None)[0]
    resid = np.linalg.norm(Jb.T @ F - tau0[:6])
    if resid > 1e-6 * max(1.0, np.linalg.norm(tau0[:6])):
        return True
    try:
        import quadprog
    except ImportError:
        return None
    n3 = Jall.shape[0]
    G = pyramid_rows(idx, n3)
    H = Jj @ Jj.T + W_CONTACT * np.eye(n3)
    C = np.hstack([Jb, G.T])
    b = np.concatenate([tau0[:6], np.zeros(G.shape[0])])
    try:
        quadprog.solve_qp(H, Jj @ tau0[6:], C, b, 6)
    except ValueError:
        return True  # "constraints are inconsistent, no solution"
    return False


def rule_quadprog(tau0, J, act):
    """The same QP solved by quadprog (PyPI, Goldfarb-Idnani in Fortran): the base's equations
    reduced to their independent rows by numpy's SVD first (a diagonal pair gives rank 5), which
    quadprog needs; the forces (4 x 3), or None when quadprog is not importable."""
    try:
        import quadprog
    except ImportError:
        return None
    idx = [c for c in range(len(FEET)) if act[c]]
    Jall = np.vstack([J[c] for c in idx])
    Jb, Jj = Jall[:, :6], Jall[:, 6:]
    n3 = Jall.shape[0]
    U, sv, _ = np.linalg.svd(Jb.T)
    r = int((sv > 64 * (6 + n3) * np.finfo(float).eps * sv[0]).sum())
    Aeq, beq = U[:, :r].T @ Jb.T, U[:, :r].T @ tau0[:6]
    G = pyramid_rows(idx, n3)
    H = Jj @ Jj.T + W_CONTACT * np.eye(n3)
    C = np.hstack([Aeq.T, G.T])
    b = np.concatenate([beq, np.zeros(G.shape[0])])
    F = quadprog.solve_qp(H, Jj @ tau0[6:], C, b, r)[0]
    full = np.zeros((len(FEET), 3))
    for k, c in enumerate(idx):
        full[c] = F[3 * k:3 * k + 3]
    return full


def write_csv(path, cols, rows):
    with open(path, "w") as f:
        f.write(",".join(cols) + "\n")
        for r in rows:
            f.write(",".join(repr(x) for x in r) + "\n")


def small_rotation(rng, amp):
    return pin.exp3(rng.uniform(-amp, amp, 3))


def make_states(robot, rng):
    """(kind, q, v, a, active) rows: standing; near it on four feet; three feet; two given whole;
    trotting; and two that no forces carry"""
    m = robot.model
    q0 = robot.standing_q()
    rows = [("standing", q0, np.zeros(m.nv), np.zeros(m.nv), (1, 1, 1, 1))]

    def near(joint_amp, vel_amp, acc_amp, base_acc):
        q = q0.copy()
        for j in robot.joints:
            q[robot.iq[j]] += rng.uniform(-joint_amp, joint_amp)
        q[0:3] += rng.uniform(-0.02, 0.02, 3)
        q[3:7] = pin.Quaternion(small_rotation(rng, 0.08)).coeffs()
        v = np.zeros(m.nv)
        a = np.zeros(m.nv)
        v[0:3], v[3:6] = rng.uniform(-0.2, 0.2, 3), rng.uniform(-0.3, 0.3, 3)
        a[0:3], a[3:6] = base_acc, rng.uniform(-1.0, 1.0, 3)
        for j in robot.joints:
            v[robot.iv[j]] = rng.uniform(-vel_amp, vel_amp)
            a[robot.iv[j]] = rng.uniform(-acc_amp, acc_amp)
        return q, v, a

    for _ in range(24):  # (b): four feet
        q, v, a = near(0.15, 1.5, 4.0, rng.uniform(-0.5, 0.5, 3))
        rows.append(("four feet", q, v, a, (1, 1, 1, 1)))
    # (c) three feet: the torso's weight sits on the diagonal between the lifted foot's neighbours
    # (the rectangle's centre); accelerating it toward the lifted foot moves the ground's centre of
    # pressure away from that foot, into the triangle of the three (~ 0.24 m / 9.81 * 1.5 m/s^2)
    feet_xy = robot.feet_positions(q0)[:, :2] - q0[:2]
    for k in range(12):
        up = k % 4
        act = tuple(0 if c == up else 1 for c in range(4))
        d = feet_xy[up] / np.linalg.norm(feet_xy[up])
        # (Pinocchio's a is in the base's axes, turned by at most 0.08 rad from the world's: near
        # enough to the direction meant)
        q, v, a = near(0.05, 0.5, 1.0, np.append(1.5 * d, rng.uniform(-0.3, 0.3)))
        a[3:6] *= 0.3
        rows.append(("three feet", q, v, a, act))
    for k in range(3):  # one diagonal pair on the ground, the motion given whole: refused
        act = (1, 0, 0, 1) if k % 2 == 0 else (0, 1, 1, 0)
        q, v, a = near(0.05, 0.5, 1.0, rng.uniform(-0.3, 0.3, 3))
        rows.append(("two feet", q, v, a, act))
    for k in range(8):  # (t) trotting: the same, the base's turn about the pair's line solved
        act = (1, 0, 0, 1) if k % 2 == 0 else (0, 1, 1, 0)
        q, v, a = near(0.05, 0.5, 1.0, rng.uniform(-0.3, 0.3, 3))
        a[3:6] *= 0.3
        rows.append(("trot", q, v, trot_acceleration(robot, q, v, a, act), act))
    # rows no forces can carry: the torso falling faster than gravity (the feet would pull) and
    # thrown sideways beyond what friction gives (9 m/s^2 against mu cos(pi/4) g <= 5.5 m/s^2)
    q, v, a = near(0.05, 0.5, 1.0, np.array([0.0, 0.0, -14.0]))
    rows.append(("pull", q, v, a, (1, 1, 1, 1)))
    q, v, a = near(0.05, 0.5, 1.0, np.array([9.0, 0.0, 0.0]))
    rows.append(("slip", q, v, a, (1, 1, 1, 1)))
    return rows


def trot_acceleration(robot, q, v, a, act):
    """a with the base's angular acceleration along the stance pair's line set so that the base
    wrench rnea(q, v, a)[:6] has no moment about the line: n . tau_base = 0 with n the base twist
    (Pinocchio's local v) that moves neither foot, the null vector of their base Jacobian rows"""
    _, J = robot.tau0_and_jacobians(q, v, a)
    Jb = np.vstack([J[c][:, :6] for c in range(len(FEET)) if act[c]])
    sv, n = np.linalg.svd(Jb)[1:]
    if sv[4] < 1e-3 * sv[0] or sv[5] > 1e-12 * sv[0]:
        raise ValueError("the pair's base Jacobian is not of rank 5: %s" % sv)
    n = n[5]
    w = n[3:6] / np.linalg.norm(n[3:6])  # the line's direction, base axes (n turns about it)
    def moment(s):
        b = a.copy()
        b[3:6] += (s - b[3:6] @ w) * w
        return n @ pin.rnea(robot.model, robot.data, q, v, b)[:6], b
    r0, r1 = moment(0.0)[0], moment(1.0)[0]
    r, b = moment(-r0 / (r1 - r0))
    if abs(r) > 1e-9 * robot.weight:
        raise ValueError("rnea is not affine in the base's angular acceleration: %g" % r)
    return b


def read_out_csv(path):
    with open(path) as f:
        rd = csv.reader(f)
        head = next(rd)
        vals = np.array([[float(x) for x in r] for r in rd])
    return {h: vals[:, k] for k, h in enumerate(head)}


def main():
    vtdyn, work = sys.argv[1], Path(sys.argv[2])
    work.mkdir(parents=True, exist_ok=True)
    root, _ = robots_dir()
    urdf = root / "solo_description/robots/solo12.urdf"
    failures = []
    robot = Robot(urdf)
    r = run(vtdyn, "info", "--floating", urdf)
    lines = r.stdout.splitlines() if r.returncode == 0 else []
    k = lines.index("frames (their names):") if "frames (their names):" in lines else -1
    frames = lines[k + 1].split(",") if 0 <= k < len(lines) - 1 else []
    for f in FEET:  # the feet are frames of vtdyn's model too (URDF links merged by fixed joints)
        if f not in frames:
            failures.append("vtdyn info --floating: no frame %s (%s)" % (f, r.stderr.strip()))
    contacts = work / "contacts.csv"
    with open(contacts, "w") as f:
        f.write("frame,mu\n" + "".join("%s,%r\n" % (c, MU[c]) for c in FEET))

    rng = np.random.default_rng(42)
    states = make_states(robot, rng)
    cols = robot.columns()
    refs = [robot.tau0_and_jacobians(q, v, a) for _, q, v, a, _ in states]

    # run, and on a refusal drop the row named (states.csv:LINE:) and run again
    keep = list(range(len(states)))
    refused = []
    path = work / "contact_states.csv"
    out = work / "contact_out.csv"
    for _ in range(len(states) + 1):
        write_csv(path, cols, [robot.row(*states[i][1:]) for i in keep])
        r = run(vtdyn, "inverse", "--floating", "--contacts", contacts, "-j", "1", urdf, path, "-o", out)
        if r.returncode == 0:
            break
        msg = r.stderr.strip()
        m = re.search(re.escape(str(path)) + r":(\d+):", msg)
        if r.returncode != 1 or not m:
            failures.append("vtdyn refused a run without naming a row (exit %d): %s" % (r.returncode, msg))
            keep = []
            break
        i = keep.pop(int(m.group(1)) - 2)  # line 1 is the header
        kind, act = states[i][0], states[i][4]
        why = ("cannot give" if "cannot give" in msg else "pull" if "would have to pull" in msg
               else "slip" if "would have to slip" in msg else None)
        named = [f for f in FEET if '"%s"' % f in msg]
        if why is None or (why != "cannot give" and not named):
            failures.append("row %d (%s): the refusal says neither which contact nor why: %s" % (i, kind, msg))
        proof = refusal_is_infeasible(states[i][1], *refs[i], act)
        if proof is False:
            failures.append("row %d (%s): refused (%s), but quadprog finds the QP feasible" % (i, kind, msg))
        if kind == "trot":
            failures.append("row %d (trot): refused: %s" % (i, msg))
        if kind == "two feet" and why != "cannot give":
            failures.append("row %d (two feet): not refused for the root's moment: %s" % (i, msg))
        if kind in ("pull", "slip") and why not in ("pull", "slip"):
            failures.append("row %d (%s): not refused for a contact's pull or slip: %s" % (i, kind, msg))
        refused.append((i, kind, why, named, proof, msg))
    else:
        failures.append("vtdyn kept refusing rows")
    for i, kind, why, named, proof, msg in refused:
        print("refused row %d (%s): %s%s [independently: %s]" % (
            i, kind, why, (" " + ",".join(named)) if named else "",
            {True: "infeasible", None: "not checked"}[proof]))
    for k in ("two feet", "pull", "slip"):
        ex = [x[5] for x in refused if x[1] == k]
        print("  e.g. " + (ex[0].splitlines()[-1] if ex else "(no %s row refused)" % k))
    kinds = ("standing", "four feet", "three feet", "two feet", "trot", "pull", "slip")
    print("rows accepted / refused: " + ", ".join(
        "%s %d/%d" % (k, sum(1 for i in keep if states[i][0] == k), sum(1 for x in refused if x[1] == k))
        for k in kinds))
    for k in ("two feet", "pull", "slip"):
        if not any(x[1] == k for x in refused):
            failures.append("no %s row refused" % k)
    if 0 not in keep:
        failures.append("the standing row was refused")
    if sum(1 for i in keep if states[i][0] == "four feet") < 12 or sum(
            1 for i in keep if states[i][0] == "three feet") < 4 or sum(
            1 for i in keep if states[i][0] == "trot") < 8:
        failures.append("too few rows accepted to say much")

    if keep:
        got = read_out_csv(out)
        W = robot.weight
        worst = {"joint": 0.0, "base": 0.0, "vtdyn root": 0.0, "pyramid": 0.0, "rule": 0.0}
        faces = 0
        trot = {"joint": 0.0, "base": 0.0, "fz": np.inf, "friction": 0.0}
        for k, i in enumerate(keep):
            kind, q, v, a, act = states[i]
            tau0, J = refs[i]
            force = np.array([[got["%s_%s" % (f, c)][k] for c in ("fx", "fy", "fz")] for f in FEET])
            tau = tau0 - sum(J[c].T @ force[c] for c in range(4))
            effort = np.array([got[j + "_effort"][k] for j in robot.joints])
            mine = np.array([tau[robot.iv[j]] for j in robot.joints])
            scale = max(W, np.abs(mine).max())
            worst["joint"] = max(worst["joint"], np.abs(effort - mine).max() / scale)
            worst["base"] = max(worst["base"], np.abs(tau[:6]).max() / W)
            worst["vtdyn root"] = max(worst["vtdyn root"], max(abs(got[c][k]) for c in ROOT_EFFORT) / W)
            if kind == "trot":
                trot["joint"] = max(trot["joint"], np.abs(effort - mine).max() / scale)
                trot["base"] = max(trot["base"], np.abs(tau[:6]).max() / W)
                for c, f in enumerate(FEET):
                    if act[c]:
                        trot["fz"] = min(trot["fz"], force[c][2])
                        trot["friction"] = max(trot["friction"], np.abs(force[c][:2]).max() / (MU[f] * COS * force[c][2]))
            for c, f in enumerate(FEET):
                if not act[c]:
                    if np.any(force[c] != 0.0):
                        failures.append("row %d: inactive %s carries %s" % (i, f, force[c]))
                    continue
                lim = MU[f] * COS * force[c][2]
                over = max(-force[c][2], abs(force[c][0]) - lim, abs(force[c][1]) - lim) / W
                worst["pyramid"] = max(worst["pyramid"], over)
            F, mult, viol, na, res = rule_kkt(tau0, J, act, force, W)
            faces += na
            Fq = rule_quadprog(tau0, J, act)
            if Fq is not None:
                worst["quadprog"] = max(worst.get("quadprog", 0.0), np.abs(Fq - force).max() / W)
            diff = np.abs(F - force).max() / W
            worst["rule"] = max(worst["rule"], diff)
            if mult < -TOL or viol > TOL * W or res > 1e-9 * W:
                failures.append("row %d (%s): the KKT check fails: multiplier %.3g, a face violated by %.3g N, "
                                "residual %.3g" % (i, kind, mult, viol, res))
        print("accepted rows: %d; largest differences (of the weight %.4g N, or of the largest effort)"
              % (len(keep), W))
        print("  joint efforts vs rnea - J^T f: %.2g; Pinocchio's base tau: %.2g; vtdyn's root efforts: %.2g"
              % (worst["joint"], worst["base"], worst["vtdyn root"]))
        print("  pyramid excess: %.2g; forces vs the rule's KKT solution: %.2g (%d faces on the boundary)"
              % (worst["pyramid"], worst["rule"], faces))
        print("  forces vs quadprog on the same QP: %s" % ("%.2g" % worst["quadprog"] if "quadprog" in worst
                                                          else "skipped (quadprog not importable)"))
        print("  trotting rows: joint efforts %.2g, Pinocchio's base tau %.2g; lowest stance fz %.3g N, "
              "friction used at most %.0f %%" % (trot["joint"], trot["base"], trot["fz"], 100 * trot["friction"]))
        for key, val in worst.items():
            if val > TOL:
                failures.append("%s: %.3g > %g" % (key, val, TOL))

        # standing: the left and right feet
        st = {f: np.array([got["%s_%s" % (f, c)][0] for c in ("fx", "fy", "fz")]) for f in FEET}
        print("standing on solo12.urdf: fz %s N (sum %.6g, weight %.6g); |left - right| %.2g N"
              % (" ".join("%s %.6f" % (f, st[f][2]) for f in FEET), sum(st[f][2] for f in FEET), W,
                 max(abs(st[l][2] - st[r][2]) for l, r in MIRROR.items())))

        # the same rows as .npy (-j 2): the same doubles
        data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
        np.save(work / "contact_states.npy", np.rec.fromarrays(list(data.T), names=",".join(cols)))
        r = run(vtdyn, "inverse", "--floating", "--contacts", contacts, "-j", "2", urdf,
                work / "contact_states.npy", "-o", work / "contact_out.npy")
        if r.returncode:
            failures.append("the .npy run: %s" % r.stderr.strip())
        else:
            npy = np.load(work / "contact_out.npy")
            differ = [n for n in got if n not in npy.dtype.names or not np.array_equal(npy[n], got[n])]
            print(".npy in and out (-j 2): %d rows, %d columns, %d differ from the CSV run"
                  % (npy.shape[0], len(npy.dtype.names), len(differ)))
            if differ or len(npy.dtype.names) != len(got):
                failures.append(".npy run differs from the CSV run: %s" % differ[:5])

    # standing on the left/right symmetric copy: the mirror feet carry mirrored forces
    sym = work / "solo12_symmetric.urdf"
    text = urdf.read_text()
    right = 'xyz="-0.00001377 -0.01935853 -0.07870700"'
    if text.count(right) != 2:
        failures.append("solo12.urdf: the right upper legs' centre of mass is not where expected")
    else:
        sym.write_text(text.replace(right, 'xyz="0.00001377 -0.01935853 -0.07870700"'))
        srob = Robot(sym)
        q0 = srob.standing_q()
        spath, sout = work / "symmetric_standing.csv", work / "symmetric_out.csv"
        write_csv(spath, cols, [srob.row(q0, np.zeros(18), np.zeros(18), (1, 1, 1, 1))])
        r = run(vtdyn, "inverse", "--floating", "--contacts", contacts, sym, spath, "-o", sout)
        if r.returncode:
            failures.append("symmetric standing: %s" % r.stderr.strip())
        else:
            g = read_out_csv(sout)
            st = {f: np.array([g["%s_%s" % (f, c)][0] for c in ("fx", "fy", "fz")]) for f in FEET}
            d = max(max(abs(st[l][0] - st[r][0]), abs(st[l][1] + st[r][1]), abs(st[l][2] - st[r][2]))
                    for l, r in MIRROR.items()) / srob.weight
            print("standing, symmetric copy: FL %s HL %s N; mirror difference %.2g of the weight"
                  % (np.round(st["FL_FOOT"], 6), np.round(st["HL_FOOT"], 6), d))
            if d > TOL:
                failures.append("symmetric standing: left and right differ by %.3g of the weight" % d)

    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
