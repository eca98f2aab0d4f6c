#!/usr/bin/env python3
"""The chains of vt_test_ratio_chain (tests/vt_test.h: five planar rods of 0.4 m, masses falling
by 1e6 a rod from 1e12 to 1e-12 kg, or by 1e3 from 1e6 to 1e-6, rising, or all 1 kg; partly or
fully driven) solved exactly, at 50 digits with mpmath, from their own equations of motion
written here, and vtdyn's answers on both paths (tests/ratio_chain.c prints them) held to them.

The equations (nothing of vtdyn's method: absolute angles and Kane's form of Newton-Euler).
Rod k (k = 0..4) turns by theta_k = q_0 + ... + q_k about z; its joint is at P_k (P_0 = 0), its
centre at c_k = P_k + h u_k and P_{k+1} = P_k + 2 h u_k, h = 0.2 m, u_k = (cos, sin) theta_k,
n_k = (-sin, cos) theta_k. With J_k = dc_k/dq (column j: sum over i = j..k of l_ik n_i, l_ik = 2h
for i < k and h for i = k) and the bias b_k = -sum_i l_ik w_i^2 u_i (w_i = d theta_i / dt),

    M = sum_k m_k J_k^T J_k + I_k e_k e_k^T,  e_k = (1 .. 1 (k+1 ones), 0 ..),
    Q = sum_k J_k^T m_k (g - b_k),            g = (0, -9.81),

and a joint drive of rate k is the row e_k^T q'' = f_k''(t), a tip drive (the point 2h along rod 4
from its centre, the chain's end) J_tip,c q'' = f_c''(t) - b_tip,c. Then

    [M  Phi^T] [ q''  ]   [Q    ]
    [Phi  0  ] [ -lam ] = [gamma]

solved by mpmath's LU at 50 digits; lam is vtdyn's lambda of M* q'' = Q + Phi_q^T lam.

The data (masses, inertias, q, q', t) are read from vtdyn's output, 17 digits, so the oracle
solves the very problem vtdyn was given. Checks:
 1. the 1 kg chains: both paths' q'' and lambda to 1e-13 of their largest entry (the oracle and
    vtdyn describe the same mechanism);
 2. the problem's own condition on the spread chains: the exact derivative of q'' and lambda
    with respect to a relative change of each mass (the whole rod: mass and inertia), normwise,
    is below 2, and with respect to each q and q' (differences at 1e-25) below 50 per radian: no
    spread chain's answer hangs on the masses or the pose;
 3. vtdyn's error on every chain and path, normwise: q'' and lambda within 20 eps / rcond (at
    least 100 eps) of the exact ones;
 4. no warning and no failure on any chain (no chain's answer hangs on its masses or its pose);
 5. the routes: the rising chains with joints 1-2 and the tip driven stay on their own routes, the
    recursive one on the articulated route and the dense one on the Schur route (the driven
    rates known, only the tip's rows in the Schur complement: 8.5e-3 and up), so that 3. holds
    those routes; the rising chains driven at joint 1 alone (the free-rate routes' estimate below
    1e-3, and the joint-1 effort the difference of terms of the tip's size in M* q'' - Q and in
    the inward sums) and the chain falling by 1e6 with joints 1-2 and the tip driven at its
    first state (the Schur estimate below rcond_warn) are solved by the maximal-coordinate route
    on both paths (the recursive path hands the instant to the dense stages), which keeps each
    rod's Newton-Euler equations apart.
It prints every case: route, rcond, the problem's condition and vtdyn's errors in eps.

    ratio_oracle.py RATIO_CHAIN        (exit 77, skipped, without mpmath)
"""
import json
import subprocess
import sys

try:
    import mpmath as mp
except ImportError:
    print("ratio_oracle: mpmath is not installed (pip install mpmath): skipped")
    sys.exit(77)

mp.mp.dps = 50
EPS = 2.0 ** -52
N = 5
ROUTE_SCHUR = 4  # VT_ROUTE_SCHUR
ROUTE_ARTICULATED = 5  # VT_ROUTE_ARTICULATED
ROUTE_MAXIMAL = 9  # VT_ROUTE_MAXIMAL


def chain(case, q=None, qd=None, scale=None):
    """each rod's share of M and Q, the rows and gamma (scale: a factor on each rod's mass)"""
    m = [mp.mpf(x) for x in case["mass"]]
    inertia = [mp.mpf(x) for x in case["izz"]]
    if scale:
        m = [a * s for a, s in zip(m, scale)]
        inertia = [a * s for a, s in zip(inertia, scale)]
    q = q or [mp.mpf(x) for x in case["q"]]
    qd = qd or [mp.mpf(x) for x in case["qd"]]
    t = mp.mpf(case["time"])
    h = mp.mpf(0.2)
    theta = [mp.fsum(q[:k + 1]) for k in range(N)]
    w = [mp.fsum(qd[:k + 1]) for k in range(N)]
    u = [(mp.cos(a), mp.sin(a)) for a in theta]
    n = [(-mp.sin(a), mp.cos(a)) for a in theta]

    def point(k, end):
        """Jacobian and bias of rod k's centre, or of its far end"""
        J = mp.zeros(2, N)
        b = [mp.mpf(0), mp.mpf(0)]
        for i in range(k + 1):
            lev = 2 * h if (i < k or end) else h
            for j in range(i + 1):
                J[0, j] += lev * n[i][0]
                J[1, j] += lev * n[i][1]
            b[0] -= lev * w[i] ** 2 * u[i][0]
            b[1] -= lev * w[i] ** 2 * u[i][1]
        return J, b

    g = (mp.mpf(0), mp.mpf(-9.81))
    Mk, Qk = [], []
    for k in range(N):
        J, b = point(k, False)
        M = mp.zeros(N, N)
        Q = mp.zeros(N, 1)
        for a in range(N):
            for c in range(N):
                M[a, c] = m[k] * (J[0, a] * J[0, c] + J[1, a] * J[1, c]) + (inertia[k] if a <= k and c <= k else 0)
            Q[a] = J[0, a] * m[k] * (g[0] - b[0]) + J[1, a] * m[k] * (g[1] - b[1])
        Mk.append(M)
        Qk.append(Q)
    drive = case["drive"]
    rows, gamma = [], []
    for k in range({0: 5, 1: 3, 2: 2, 3: 1}[drive]):
        rows.append([mp.mpf(1) if a == k else mp.mpf(0) for a in range(N)])
        gamma.append(-mp.mpf(0.4) * mp.mpf(1.5) ** 2 * mp.sin(mp.mpf(1.5) * t + mp.mpf(0.2 * k)))
    if drive in (1, 2):
        J, b = point(N - 1, True)
        for c in range(2):
            rows.append([J[c, a] for a in range(N)])
            gamma.append(-mp.mpf(0.05) * mp.sin(t + mp.mpf(0.3 * c)) - b[c])
    return Mk, Qk, rows, gamma


def augmented(Mk, Qk, rows, gamma):
    nc = len(rows)
    A = mp.zeros(N + nc, N + nc)
    rhs = mp.zeros(N + nc, 1)
    for k in range(N):
        for a in range(N):
            for c in range(N):
                A[a, c] += Mk[k][a, c]
            rhs[a] += Qk[k][a]
    for r in range(nc):
        for a in range(N):
            A[N + r, a] = A[a, N + r] = rows[r][a]
        rhs[N + r] = gamma[r]
    return A, rhs


def exact(case, **kw):
    """q'', lambda"""
    A, rhs = augmented(*chain(case, **kw))
    x = mp.lu_solve(A, rhs)
    return [x[a] for a in range(N)], [-x[N + r] for r in range(len(x) - N)]


def norm(v):
    return max(abs(a) for a in v)


def rel(a, b):
    """normwise relative difference of a from b"""
    return norm([x - y for x, y in zip(a, b)]) / norm(b)


def condition(case, qdd, lam):
    """largest normwise relative change of q'' and lambda per relative change of a mass
    (d/ds at m_k e^s, exact: A dx = db - dA x), and per radian of a q or rad/s of a q' (differences)"""
    Mk, Qk, rows, gamma = chain(case)
    A, _ = augmented(Mk, Qk, rows, gamma)
    x = mp.matrix(list(qdd) + [-v for v in lam])
    nc = len(lam)
    mass = [mp.mpf(0), mp.mpf(0)]
    for k in range(N):
        dA = mp.zeros(N + nc, N + nc)
        db = mp.zeros(N + nc, 1)
        for a in range(N):
            for c in range(N):
                dA[a, c] = Mk[k][a, c]
            db[a] = Qk[k][a]
        dx = mp.lu_solve(A, db - dA * x)
        mass[0] = max(mass[0], norm([dx[a] for a in range(N)]) / norm(qdd))
        mass[1] = max(mass[1], norm([dx[N + r] for r in range(nc)]) / norm(lam))
    pose = [mp.mpf(0), mp.mpf(0)]
    step = mp.mpf("1e-25")
    for key in ("q", "qd"):
        for j in range(N):
            v = [mp.mpf(x) for x in case[key]]
            v[j] += step
            qdd2, lam2 = exact(case, **{key: v})
            pose[0] = max(pose[0], norm([a - b for a, b in zip(qdd2, qdd)]) / step / norm(qdd))
            pose[1] = max(pose[1], norm([a - b for a, b in zip(lam2, lam)]) / step / norm(lam))
    return mass, pose


def main():
    out = subprocess.run([sys.argv[1]], capture_output=True, text=True, check=True).stdout
    cases = [json.loads(line) for line in out.splitlines()]
    failures = []
    solved = {}
    print("step rising drive state path route rcond | exact q'' and lambda per relative change of a mass, "
          "per rad of q, q' | vtdyn's error/eps: q'' lambda (bound)")
    for case in cases:
        key = (case["step"], case["rising"], case["drive"], case["state"])
        name = "step %d rising %d drive %d state %d %s" % (key + ("recursive" if case["path"] else "dense",))
        if case["status"] != 0:
            failures.append("%s: status %d" % (name, case["status"]))
            continue
        if key not in solved:
            qdd, lam = exact(case)
            solved[key] = (qdd, lam, condition(case, qdd, lam) if case["rising"] >= 0 else None)
        qdd, lam, cond = solved[key]
        eq = rel([mp.mpf(v) for v in case["qdd"]], qdd) if norm(qdd) > 0 else norm([mp.mpf(v) for v in case["qdd"]])
        el = rel([mp.mpf(v) for v in case["lambda"]], lam)
        rcond = case["rcond"]
        bound = max(100 * EPS, 20 * EPS / rcond)
        line = "%d %2d %d %d %-9s %d %.2e |" % (key + ("recursive" if case["path"] else "dense", case["route"], rcond))
        if cond:
            line += " mass %.1e %.1e, pose %.1e %.1e |" % (cond[0][0], cond[0][1], cond[1][0], cond[1][1])
        line += " %.2e %.2e (%.1e)" % (eq / EPS, el / EPS, bound / EPS)
        if case["rising"] < 0:
            bound = 1e-13
            if not (eq <= bound and el <= bound):
                failures.append("%s: the 1 kg chain off the exact answer by %.3g (q'') and %.3g (lambda)" % (name, eq, el))
        else:
            if not (cond[0][0] < 2 and cond[0][1] < 2 and cond[1][0] < 50 and cond[1][1] < 50):
                failures.append("%s: the problem itself is ill-conditioned (%s)" % (name, line))
            if not eq <= bound:
                failures.append("%s: q'' off by %.3g, more than 20 eps / rcond = %.3g" % (name, eq, bound))
            if not el <= bound:
                failures.append("%s: lambda off by %.3g, more than 20 eps / rcond = %.3g" % (name, el, bound))
            if case["warning"]:
                failures.append("%s: warns (rcond %.3g)" % (name, rcond))
            want = None
            if case["drive"] == 2 and case["rising"] == 1:
                want = ROUTE_ARTICULATED if case["path"] else ROUTE_SCHUR
            elif (case["drive"] == 3 and case["rising"] == 1) or (case["drive"] == 2 and case["step"] == 6
                                                                  and case["rising"] == 0 and case["state"] == 0):
                want = ROUTE_MAXIMAL
            if want is not None and case["route"] != want:
                failures.append("%s: route %d, not route %d" % (name, case["route"], want))
        print(line)
    for f in failures:
        print("FAIL " + f)
    print("%d answers against the exact ones, %d failures" % (len(cases), len(failures)))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
