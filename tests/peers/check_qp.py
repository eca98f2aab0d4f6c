#!/usr/bin/env python3
"""The distribution QP (src/numeric/qp.c) against quadprog (PyPI `quadprog`, in the venv of
setup_venv.sh with VT_PEERS_SET=qp): tests/peers/qp_problems.c writes a fixed set of problems
(random, contact pyramids under a wrench balance, pyramids at their apex, duplicated
constraints, infeasible balances) with vtdyn's answers; quadprog.solve_qp solves each again.

    minimize 1/2 x'Gx + c'x  s.t.  A_eq x = b_eq,  A_in x >= b_in
    quadprog.solve_qp(G, -c, A.T, b, meq)

Held: the status (quadprog raises ValueError on an infeasible problem); x to 1e-9 relative to
X = |x|_inf + |c|_inf / max G_jj (the size of x the problem speaks of: near an apex x is about
0); the objective to 1e-9 of |x'Gx| + |c'x| + 1e-300; the multipliers to 1e-8 of |lambda|_inf
where they are unique (the normals of the constraints either solver has active are independent).
Prints the worst differences; exit 0 when everything holds, 1 otherwise.

    check_qp.py QP_PROBLEMS WORKDIR
"""
import json
import os
import subprocess
import sys

from importlib.metadata import version

import numpy as np
import quadprog

X_TOL = 1e-9
F_TOL = 1e-9
L_TOL = 1e-8


def kkt_failure(G, c, A, b, meq, x, lam, tol=1e-12):
    """'' when x and lam satisfy the KKT conditions to tol (relative to each term's size),
    the first that fails otherwise"""
    X = np.max(np.abs(x)) + np.max(np.abs(c)) / np.max(np.diag(G))
    res = G @ x + c - A.T @ lam
    mag = np.abs(G) @ np.abs(x) + np.abs(c) + np.abs(A.T) @ np.abs(lam)
    if np.any(np.abs(res) > tol * mag):
        return f"stationarity {np.max(np.abs(res) / mag):.3g}"
    s = A @ x - b
    scale = np.abs(A).sum(axis=1) * X + np.abs(b)
    if np.any(np.abs(s[:meq]) > tol * scale[:meq]):
        return "an equality"
    if np.any(s[meq:] < -tol * scale[meq:]):
        return "an inequality"
    if np.any(lam[meq:] < 0.0):
        return "a negative multiplier"
    if np.any(np.abs(lam[meq:] * s[meq:]) > tol * lam[meq:] * scale[meq:]):
        return "complementarity"
    return ""


def main():
    if len(sys.argv) != 3:
        print(__doc__)
        return 2
    exe, work = sys.argv[1], sys.argv[2]
    os.makedirs(work, exist_ok=True)
    out = os.path.join(work, "qp_problems.json")
    subprocess.run([exe, out], check=True)
    with open(out) as f:
        problems = json.load(f)["problems"]

    worst_x = worst_f = worst_l = 0.0
    worst_x_at = worst_f_at = worst_l_at = ""
    failures = []
    counts = {}
    lam_checked = 0
    declined = []
    family_x = {}
    for p in problems:
        tag = f"{p['family']} {p['id']} (n {p['n']}, meq {p['meq']}, min {p['min']})"
        counts[p["family"]] = counts.get(p["family"], 0) + 1
        n, meq, m = p["n"], p["meq"], p["meq"] + p["min"]
        G = np.array(p["G"], dtype=float).reshape(n, n)
        c = np.array(p["c"], dtype=float)
        A = np.array(p["A"], dtype=float).reshape(m, n)
        b = np.array(p["b"], dtype=float)
        try:
            xq, fq, _, _, lq, _ = quadprog.solve_qp(G, -c, A.T.copy(), b, meq)
            status_q = "optimal"
        except ValueError as e:
            status_q = "infeasible" if "inconsistent" in str(e) else f"error: {e}"
        if status_q == "infeasible" and p["status"] == "optimal":
            # quadprog's own tolerances can call a feasible but degenerate vertex (more
            # constraints through the optimum than unknowns) inconsistent: vtdyn's answer then
            # needs its own certificate (the KKT conditions, here) and quadprog's answer to the
            # problem with the inequalities relaxed by 1e-10 of their scale, to 1e-7
            why = kkt_failure(G, c, A, b, meq, np.array(p["x"]), np.array(p["lambda"]))
            scale = np.abs(A[meq:]).sum(axis=1) * (np.max(np.abs(p["x"])) + 1.0) + np.abs(b[meq:])
            b_relaxed = b.copy()
            b_relaxed[meq:] -= 1e-10 * scale
            try:
                xr = quadprog.solve_qp(G, -c, A.T.copy(), b_relaxed, meq)[0]
                X = np.max(np.abs(xr)) + np.max(np.abs(c)) / np.max(np.diag(G))
                dr = np.max(np.abs(np.array(p["x"]) - xr)) / X
                if dr > 1e-7:
                    why = (why + "; " if why else "") + f"x differs from the relaxed problem's by {dr:.3g}"
            except ValueError as e:
                why = (why + "; " if why else "") + f"quadprog: relaxed too: {e}"
            if why:
                failures.append(f"{tag}: vtdyn optimal, quadprog infeasible: {why}")
            else:
                declined.append(tag)
            continue
        if status_q != p["status"]:
            failures.append(f"{tag}: vtdyn {p['status']}, quadprog {status_q}")
            continue
        if status_q != "optimal":
            continue
        xv = np.array(p["x"])
        lv = np.array(p["lambda"])
        X = np.max(np.abs(xq)) + np.max(np.abs(c)) / np.max(np.diag(G))
        dx = np.max(np.abs(xv - xq)) / X
        fv = 0.5 * xv @ G @ xv + c @ xv
        df = abs(fv - fq) / (abs(xq @ G @ xq) + abs(c @ xq) + 1e-300)
        family_x[p["family"]] = max(family_x.get(p["family"], 0.0), dx)
        if dx > worst_x:
            worst_x, worst_x_at = dx, tag
        if df > worst_f:
            worst_f, worst_f_at = df, tag
        if not dx <= X_TOL:
            failures.append(f"{tag}: x differs by {dx:.3g} of X")
        if not df <= F_TOL:
            failures.append(f"{tag}: objective {fv:.17g} vs {fq:.17g} ({df:.3g})")
        # the multipliers, where unique: the active normals independent
        act = [i for i in range(m) if i < meq or lv[i] != 0.0 or lq[i] != 0.0]
        if act and np.linalg.matrix_rank(A[act], tol=1e-10 * np.linalg.norm(A[act], 2)) == len(act):
            lam_checked += 1
            dl = np.max(np.abs(lv - lq)) / max(np.max(np.abs(lq)), 1e-300)
            if dl > worst_l:
                worst_l, worst_l_at = dl, tag
            if not dl <= L_TOL:
                failures.append(f"{tag}: multipliers differ by {dl:.3g} of their largest")

    fam = ", ".join(f"{k} {v}" for k, v in counts.items())
    print(f"check_qp.py: {len(problems)} problems ({fam}); quadprog {version('quadprog')}")
    print(f"  worst x difference        {worst_x:.3g} of X   ({worst_x_at})")
    print("  by family: " + ", ".join(f"{k} {v:.2g}" for k, v in family_x.items()))
    print(f"  worst objective difference {worst_f:.3g}        ({worst_f_at})")
    print(f"  worst multiplier difference {worst_l:.3g} of max ({worst_l_at}; {lam_checked} problems with unique multipliers)")
    for d in declined:
        print(f"  quadprog declined {d} as inconsistent (a degenerate vertex): vtdyn's KKT conditions hold, "
              "and its x is quadprog's on the problem relaxed by 1e-10")
    for f in failures:
        print("FAIL " + f)
    print(f"check_qp.py: {len(problems)} problems, {len(failures)} differences beyond tolerance")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
