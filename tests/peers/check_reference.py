#!/usr/bin/env python3
"""Self-check of CSV files written by pinocchio_reference.py, from the CSV alone.

    python check_reference.py FILE.csv [FILE.csv ...]

Uses the CSV's columns only (the masses in it are Pinocchio's model's inertias' masses, written
by the reference script; rnea is not called here). Checks, for every row:

  1. every R:JOINT is a rotation (R^T R = I, det R = 1); for a free flyer, the quaternion
     q:root:3..6 read as (x, y, z, w) gives R:root, and p:root equals q:root:0..2;
  2. fw = R f and frw = R fr, part by part (force and moment);
  3. joints with one velocity (S:JOINT columns): tau = S^T f, fr = f - S tau, S^T fr = 0
     (the reaction has no component along the motion: a revolute joint's reaction moment is
     perpendicular to its axis);
  4. a free-flyer root: f = tau and fr = 0;
and, for the rows with v = a = 0 (written with --static), statics:
  5. every joint j carries exactly the weight of the bodies beyond it: with m_sub and c_sub the
     mass and centre of mass of the subtree rooted at j (from the parent:, mass: and com:
     columns), fw force = -m_sub g and fw moment about joint j's origin = (c_sub - p_j) x fw
     force;
  6. the first joint: its vertical force equals the weight of everything but the universe's
     share, total_mass - sum of the joints' masses (for a fixed base, the links merged into the
     universe; zero for a free flyer, where joint 1 carries total_mass).

Prints one line per file and a closing "N passed, N failed" line; exit status 0 when every
check passed.
"""
import csv
import sys

import numpy as np

REL = 1e-9  # relative to the scale of the quantity compared


def read(path):
    with open(path, newline="", encoding="utf-8") as fh:
        rows = list(csv.reader(fh))
    header, body = rows[0], rows[1:]
    idx = {name: i for i, name in enumerate(header)}
    values = np.array([[float(x) for x in r] for r in body])
    joints = []
    for name in header:
        if name.startswith("parent:"):
            joints.append(name[len("parent:"):])
    return header, idx, values, joints


class Checker:
    def __init__(self, path):
        self.path = path
        self.failures = []
        self.count = 0
        self.worst = 0.0

    def close(self, what, got, want, scale):
        self.count += 1
        got, want = np.atleast_1d(got), np.atleast_1d(want)
        err = float(np.max(np.abs(got - want))) / max(scale, 1.0)
        self.worst = max(self.worst, err)
        if not err <= REL:
            self.failures.append(f"{what}: got {got}, want {want} (relative error {err:.3g})")


def vec(row, idx, names):
    return np.array([row[idx[n]] for n in names])


def quat_to_matrix(x, y, z, w):
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ])


def check_file(path):
    header, idx, values, joints = read(path)
    ck = Checker(path)
    fc = ("fx", "fy", "fz", "mx", "my", "mz")
    nstatic = 0
    for row in values:
        s = int(row[idx["state"]])
        g = vec(row, idx, ("gravity_x", "gravity_y", "gravity_z"))
        total = row[idx["total_mass"]]
        weight_scale = total * float(np.linalg.norm(g))
        parent = {j: int(row[idx[f"parent:{j}"]]) for j in joints}
        mass = {j: row[idx[f"mass:{j}"]] for j in joints}
        com = {j: vec(row, idx, [f"com:{j}:{c}" for c in "xyz"]) for j in joints}
        p = {j: vec(row, idx, [f"p:{j}:{c}" for c in "xyz"]) for j in joints}
        R = {j: vec(row, idx, [f"R:{j}:{r}{c}" for r in range(3) for c in range(3)]).reshape(3, 3)
             for j in joints}
        f = {j: vec(row, idx, [f"f:{j}:{c}" for c in fc]) for j in joints}
        fr = {j: vec(row, idx, [f"fr:{j}:{c}" for c in fc]) for j in joints}
        fw = {j: vec(row, idx, [f"fw:{j}:{c}" for c in fc]) for j in joints}
        frw = {j: vec(row, idx, [f"frw:{j}:{c}" for c in fc]) for j in joints}
        tau = {j: vec(row, idx, [h for h in header if h.startswith(f"tau:{j}:")]) for j in joints}
        fscale = max([np.max(np.abs(f[j])) for j in joints] + [1.0])
        for j in joints:
            tag = f"state {s} joint {j}"
            ck.close(f"{tag}: R^T R", R[j].T @ R[j], np.eye(3), 1.0)
            ck.close(f"{tag}: det R", np.linalg.det(R[j]), 1.0, 1.0)
            for part, sl in (("force", slice(0, 3)), ("moment", slice(3, 6))):
                ck.close(f"{tag}: fw {part} = R f", fw[j][sl], R[j] @ f[j][sl], fscale)
                ck.close(f"{tag}: frw {part} = R fr", frw[j][sl], R[j] @ fr[j][sl], fscale)
            if f"S:{j}:0" in idx:
                S = vec(row, idx, [f"S:{j}:{r}" for r in range(6)])
                ck.close(f"{tag}: tau = S^T f", tau[j], S @ f[j], fscale)
                ck.close(f"{tag}: fr = f - S tau", fr[j], f[j] - S * tau[j][0], fscale)
                ck.close(f"{tag}: S^T fr = 0", S @ fr[j], 0.0, fscale)
        root = joints[0]
        if f"q:{root}:6" in idx:  # a free flyer: 7 coordinates
            qr = vec(row, idx, [f"q:{root}:{k}" for k in range(7)])
            ck.close(f"state {s}: quaternion (x,y,z,w) -> R:{root}", quat_to_matrix(*qr[3:]),
                     R[root], 1.0)
            ck.close(f"state {s}: p:{root} = q:{root}:0..2", p[root], qr[:3], 1.0)
            ck.close(f"state {s}: free flyer f = tau", f[root], tau[root], fscale)
            ck.close(f"state {s}: free flyer fr = 0", fr[root], 0.0, fscale)

        v = vec(row, idx, [h for h in header if h.startswith("v:")])
        a = vec(row, idx, [h for h in header if h.startswith("a:")])
        if np.any(v) or np.any(a):
            continue
        nstatic += 1
        # subtree masses and centres of mass, children after parents in Pinocchio's order
        msub = dict(mass)
        msum = {j: mass[j] * com[j] for j in joints}
        for k in range(len(joints) - 1, -1, -1):
            j = joints[k]
            if parent[j] > 0:
                pj = joints[parent[j] - 1]
                msub[pj] += msub[j]
                msum[pj] = msum[pj] + msum[j]
        for j in joints:
            tag = f"state {s} joint {j} (static)"
            F = -msub[j] * g
            csub = msum[j] / msub[j] if msub[j] > 0 else p[j]
            lever = max(1.0, float(np.max(np.abs(csub - p[j]))))
            ck.close(f"{tag}: force = -m_sub g", fw[j][:3], F, weight_scale)
            ck.close(f"{tag}: moment = (c_sub - p) x F", fw[j][3:],
                     np.cross(csub - p[j], F), weight_scale * lever)
        carried = total - sum(mass.values())
        first = [j for j in joints if parent[j] == 0]
        if len(first) == 1:
            want = (total - carried) * float(np.linalg.norm(g))
            ck.close(f"state {s}: joint {first[0]} vertical force = weight of the "
                     f"{total - carried:.6g} kg beyond the universe ({carried:.6g} kg merged "
                     "into it)", fw[first[0]][:3] @ (-g / np.linalg.norm(g)), want,
                     weight_scale)
    return ck, len(values), nstatic, joints


def main(argv):
    if not argv:
        print(__doc__, file=sys.stderr)
        return 2
    passed = failed = 0
    for path in argv:
        ck, nrows, nstatic, joints = check_file(path)
        status = "ok" if not ck.failures else "FAILED"
        print(f"{status}: {path}: {nrows} states ({nstatic} static), {len(joints)} joints, "
              f"{ck.count} comparisons, worst relative error {ck.worst:.2e}")
        for msg in ck.failures[:20]:
            print("  " + msg)
        if ck.failures:
            failed += 1
        else:
            passed += 1
    print(f"{passed} passed, {failed} failed")
    return 0 if failed == 0 else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
