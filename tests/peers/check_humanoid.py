#!/usr/bin/env python3
"""`vtdyn inverse --floating --contacts` on a humanoid standing on its soles' corners, against
Pinocchio (run by run_peer.sh with the venv's python, which has pin, numpy and example-robot-data).

    check_humanoid.py VTDYN WORKDIR

Talos (example-robot-data's talos_reduced.urdf, 90.3 kg, 32 joints, a free root; --ideal-joints,
as Pinocchio's rnea leaves the file's <dynamics> damping and friction out) on eight
contacts: the four corners of each sole, given in the links left_sole_link and right_sole_link's
frames (x = +-0.1 m, y = +-0.065 m, z = 0: the contacts file's columns x,y,z) and named
left_1 ... right_4 (its column name), mu 0.7. States made here in Pinocchio's terms and written as
vtdyn's columns (world axes, docs/command.md, as check_contacts.py does):
  (a) the neutral pose (legs straight), the base at the height that puts both soles on z = 0, at
      rest, both feet on the ground;
  (b) 20 random states near it (joints within 0.05 rad of it, their rates and accelerations, a
      small turn, velocity and acceleration of the base), both feet;
  (c) the right foot lifted (right_1 ... right_4 inactive: C_active 0), the base accelerated
      sideways so that the ground's moment about the left sole's x axis vanishes (the centre of
      pressure on the sole's centre line; a, found here from two rnea calls, rnea affine in it).
For every row, with Pinocchio's free-flyer model of the same file and a frame at each corner (the
sole frame's placement times the corner's offset):
  * tau = rnea(q, v, a) - sum_c J_c^T f_c (J_c the corner frame's Jacobian, LOCAL_WORLD_ALIGNED,
    linear rows; f_c vtdyn's C_fx C_fy C_fz): the base's six components zero to 1e-9 of the
    weight (the free root carries nothing) and the 32 joints' equal to vtdyn's J_effort to 1e-9
    of the larger of the row's largest effort and the weight; vtdyn's own root efforts zero to
    the same;
  * every force pushes and lies in its 4-face pyramid; an inactive corner's exactly 0;
  * the forces are the rule's (least squared joint efforts, then 1e-4 N^-2 the squared forces):
    check_contacts.rule_kkt's KKT system on the faces vtdyn's forces lie on gives the same
    forces with non-negative multipliers and every other face satisfied.
Without the corners' x,y,z (every contact at its sole's origin: one point a sole) the run is
refused at its first row, named: two points give no moment about the line through them, which
standing needs (Talos's centre of mass is not exactly above that line).
Exit 0 when every check holds, 1 otherwise.
"""
import sys
from pathlib import Path

import numpy as np
import pinocchio as pin

from check_contacts import COS, TOL, Robot, read_out_csv, rule_kkt, run, write_csv
from run_pinocchio import robots_dir

SOLES = ("left_sole_link", "right_sole_link")
HALF = (0.1, 0.065)  # m, half the sole's length and width
MU = 0.7
ROOT = "base_link"
ROOT_IN = [ROOT + "_" + c for c in "x y z qw qx qy qz vx vy vz wx wy wz ax ay az alx aly alz".split()]
ROOT_EFFORT = [ROOT + "_effort_" + c for c in ("fx", "fy", "fz", "nx", "ny", "nz")]
CORNERS = [(s, k, (sx * HALF[0], sy * HALF[1], 0.0))
           for s in SOLES for k, (sx, sy) in enumerate(((1, 1), (1, -1), (-1, 1), (-1, -1)))]
NAMES = ["%s_%d" % (s.split("_")[0], k + 1) for s, k, _ in CORNERS]


def parent_joint(frame):
    return frame.parentJoint if hasattr(frame, "parentJoint") else frame.parent


class Humanoid(Robot):
    """Pinocchio's free-flyer Talos with a frame at each sole corner (self.feet: Robot's row and
    tau0_and_jacobians take them as the contacts)"""

    def __init__(self, urdf):  # pylint: disable=super-init-not-called (Robot's is Solo-12's)
        self.model = pin.buildModelFromUrdf(str(urdf), pin.JointModelFreeFlyer())
        self.joints = [self.model.names[j] for j in range(2, self.model.njoints)]
        self.iq = {n: self.model.joints[self.model.getJointId(n)].idx_q for n in self.joints}
        self.iv = {n: self.model.joints[self.model.getJointId(n)].idx_v for n in self.joints}
        self.feet = []
        for (sole, _, p), name in zip(CORNERS, NAMES):
            fid = self.model.getFrameId(sole)
            if fid >= len(self.model.frames):
                raise ValueError("Pinocchio has no frame " + sole)
            f = self.model.frames[fid]
            placement = f.placement * pin.SE3(np.eye(3), np.array(p))
            self.feet.append(self.model.addFrame(
                pin.Frame("corner_" + name, parent_joint(f), fid, placement, pin.FrameType.OP_FRAME)))
        self.soles = [self.model.getFrameId(s) for s in SOLES]
        self.data = self.model.createData()
        self.weight = sum(self.model.inertias[i].mass for i in range(self.model.njoints)) * 9.81

    def standing_q(self):
        q = pin.neutral(self.model)
        pin.framesForwardKinematics(self.model, self.data, q)
        z = [self.data.oMf[f].translation[2] for f in self.soles]
        if abs(z[0] - z[1]) > 1e-12:
            raise ValueError("the neutral pose's soles are not level: z %s" % z)
        q[2] = -z[0]
        return q

    def columns(self):
        return ROOT_IN + sum(([j, j + "_vel", j + "_acc"] for j in self.joints), []) + [n + "_active" for n in NAMES]

    def sole_moment_x(self, q, a):
        """the ground's moment about the left sole's x axis (through its origin) that carries the
        base's wrench at rest with acceleration a: rnea's base wrench moved there"""
        tau0 = pin.rnea(self.model, self.data, q, np.zeros(self.model.nv), a)
        pin.framesForwardKinematics(self.model, self.data, q)
        R = pin.Quaternion(q[3:7]).toRotationMatrix()
        f, n = R @ tau0[:3], R @ tau0[3:6]  # world axes, about the base's origin
        sole = self.data.oMf[self.soles[0]]
        n_sole = n + np.cross(q[:3] - sole.translation, f)
        return sole.rotation[:, 0] @ n_sole


def main():
    vtdyn, work = sys.argv[1], Path(sys.argv[2])
    work.mkdir(parents=True, exist_ok=True)
    urdf = robots_dir()[0] / "talos_data/robots/talos_reduced.urdf"
    robot = Humanoid(urdf)
    W, nv = robot.weight, robot.model.nv
    rng = np.random.default_rng(5)
    q0 = robot.standing_q()
    both = [True] * 8
    states = [(q0, np.zeros(nv), np.zeros(nv), both)]
    for _ in range(20):
        q = q0.copy()
        for j in robot.joints:
            q[robot.iq[j]] += rng.uniform(-0.05, 0.05)
        q[3:7] = pin.Quaternion(pin.exp3(rng.uniform(-0.02, 0.02, 3))).coeffs()
        v = np.r_[rng.uniform(-0.05, 0.05, 6), rng.uniform(-0.3, 0.3, nv - 6)]
        a = np.r_[rng.uniform(-0.2, 0.2, 6), rng.uniform(-0.5, 0.5, nv - 6)]
        states.append((q, v, a, both))
    # single support on the left sole: the base's sideways acceleration that zeroes the moment
    # about the sole's x axis (affine in it: two evaluations)
    a0, a1 = np.zeros(nv), np.zeros(nv)
    a1[1] = 1.0
    m0, m1 = robot.sole_moment_x(q0, a0), robot.sole_moment_x(q0, a1)
    a_left = np.zeros(nv)
    a_left[1] = -m0 / (m1 - m0)
    states.append((q0, np.zeros(nv), a_left, [True] * 4 + [False] * 4))
    cols = robot.columns()
    path = work / "humanoid_states.csv"
    write_csv(path, cols, [robot.row(*s) for s in states])
    contacts = work / "soles.csv"
    with open(contacts, "w") as f:
        f.write("name,frame,mu,x,y,z\n")
        for (sole, _, p), name in zip(CORNERS, NAMES):
            f.write("%s,%s,%r,%r,%r,%r\n" % (name, sole, MU, *p))
    out = work / "humanoid_out.csv"
    r = run(vtdyn, "inverse", "--floating", "--ideal-joints", "--contacts", contacts, urdf, path, "-o", out)
    failures = []
    if r.returncode:
        print(r.stderr)
        print("FAILED: the command refused the humanoid's rows")
        return 1
    got = read_out_csv(out)
    worst = {"joint": 0.0, "base": 0.0, "vtdyn root": 0.0, "pyramid": 0.0, "rule": 0.0}
    faces = 0
    for i, (q, v, a, act) in enumerate(states):
        tau0, J = robot.tau0_and_jacobians(q, v, a)
        force = [np.array([got["%s_%s" % (n, c)][i] for c in ("fx", "fy", "fz")]) for n in NAMES]
        tau = tau0 - sum(Jc.T @ fc for Jc, fc in zip(J, force))
        effort = np.array([got[j + "_effort"][i] for j in robot.joints])
        mine = np.array([tau[robot.iv[j]] for j in robot.joints])
        scale = max(W, np.abs(mine).max())
        worst["joint"] = max(worst["joint"], np.abs(effort - mine).max() / scale)
        worst["base"] = max(worst["base"], np.abs(tau[:6]).max() / W)
        worst["vtdyn root"] = max(worst["vtdyn root"], max(abs(got[c][i]) for c in ROOT_EFFORT) / W)
        for c, n in enumerate(NAMES):
            if not act[c]:
                if np.any(force[c] != 0.0):
                    failures.append("row %d: inactive %s carries %s" % (i, n, force[c]))
                continue
            lim = MU * COS * force[c][2]
            worst["pyramid"] = max(worst["pyramid"],
                                   max(-force[c][2], abs(force[c][0]) - lim, abs(force[c][1]) - lim) / W)
        F, mult, viol, na, res = rule_kkt(tau0, J, act, force, W, [MU] * 8)
        faces += na
        worst["rule"] = max(worst["rule"], np.abs(F - force).max() / W)
        if mult < -TOL or viol > TOL * W or res > 1e-9 * W:
            failures.append("row %d: the KKT check fails: multiplier %.3g, a face violated by %.3g N, residual %.3g"
                            % (i, mult, viol, res))
    last = len(states) - 1
    left = [np.array([got["%s_fz" % n][last]]) for n in NAMES[:4]]
    print("Talos on its soles' corners (talos_reduced.urdf, weight %.6g N): %d rows; largest differences (of the "
          "weight, or of the largest effort)" % (W, len(states)))
    print("  joint efforts vs rnea - J^T f: %.2g; Pinocchio's base tau: %.2g; vtdyn's root efforts: %.2g"
          % (worst["joint"], worst["base"], worst["vtdyn root"]))
    print("  pyramid excess: %.2g; forces vs the rule's KKT solution: %.2g (%d faces on the boundary)"
          % (worst["pyramid"], worst["rule"], faces))
    print("  standing: fz %s N" % " ".join("%s %.3f" % (n, got[n + "_fz"][0]) for n in NAMES))
    print("  on the left foot (base accelerated %.4g m/s^2 sideways): fz %s N"
          % (a_left[1], " ".join("%.3f" % x[0] for x in left)))
    for key, val in worst.items():
        if val > TOL:
            failures.append("%s: %.3g > %g" % (key, val, TOL))
    # the same contacts without their corners' offsets: one point a sole
    with open(contacts, "w") as f:
        f.write("name,frame,mu\n" + "".join("%s,%s,%r\n" % (n, s, MU) for (s, _, _), n in zip(CORNERS, NAMES)))
    r = run(vtdyn, "inverse", "--floating", "--ideal-joints", "--contacts", contacts, urdf, path, "-o",
            work / "origins.csv")
    print("  every contact at its sole's origin: %s" % ("carried" if r.returncode == 0 else r.stderr.strip()))
    if r.returncode != 1 or "humanoid_states.csv:2" not in r.stderr:
        failures.append("one point a sole: not refused at the standing row")
    for f in failures:
        print("FAILED: " + f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
