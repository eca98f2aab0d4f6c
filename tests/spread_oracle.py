#!/usr/bin/env python3
"""The knee four-bar of tests/spread_loop.c (vt_scene_knee's loop: thigh, crank, coupler, shank,
closed by a planar pin) with its masses spread over up to 11.5 orders (1e-6 ... 3e5 kg), fully
driven (hip and knee motor) and partly driven (one drive removed), solved exactly at 50 digits
with mpmath from its own equations written here, and vtdyn's answers on both paths held to them.

The equations (nothing of vtdyn's method: absolute angles and Kane's form of Newton-Euler, as
tests/ratio_oracle.py). The rates q = (hip, crank on the thigh, coupler on the crank, shank on
the thigh); the links' absolute angles theta_1 = q1, theta_2 = q1 + q2, theta_3 = q1 + q2 + q3,
theta_4 = q1 + q4, u = (cos, sin) theta. Centres: thigh D/2 u1, crank A/2 u2, coupler
A u2 + B/2 u3, shank D u1 + cs u4 (cs = (C + L)/2 - C); the pin joins the shank's lever point
D u1 - C u4 to the coupler's end A u2 + B u3, its two rows that difference d along the shank's
y and -x (vtdyn's rows: the planar pin's two line rows on the shank). With J_k = dc_k/dq and the
bias b_k = d^2/ds^2 c_k(q + s q') (mpmath's diff at 50 digits),

    M = sum_k m_k J_k^T J_k + I_k e_k e_k^T,   Q = sum_k J_k^T m_k (g - b_k),   g = (0, -9.81),

the drives' rows e_k^T q'' = f_k''(t) and the pin's Phi q'' = -d^2/ds^2 Phi(q + s q'). Then

    [M  Phi^T] [ q''  ]   [Q    ]
    [Phi  0  ] [ -lam ] = [gamma]

by mpmath's LU; lam is vtdyn's lambda of M* q'' = Q + Phi_q^T lam (drives first, then the pin).

The data (masses, q, q', t) are read from vtdyn's output, 17 digits, so the oracle solves the
very problem vtdyn was given. Checks:
 1. the problem's own condition, partly driven: the exact derivative of q'' and lambda with
    respect to a relative change of each mass (the whole link), normwise relative, below 2, and
    with respect to each q and q' (differences at 1e-25) below 60 per radian (rad/s): a regular
    pose, no answer that hangs on the masses or the pose;
 2. fully driven, both paths: q'' and lambda within 1e-13 of the exact ones, normwise relative;
 3. partly driven, both paths: q'' within 1e-12 (before the Schur route's refinement below
    sqrt(rcond_warn): 5.2e-12 with the 3e5 kg crank and the 1e-6 kg coupler), lambda within
    1e-11 (before: 1.7e-11), normwise relative;
 4. no failure and no warning (the estimates stay above 3e-6);
 5. the estimate covers the loss: q'' and lambda within 20 eps / rcond on every case (before the
    componentwise estimate over a spread of masses, numeric/skeel.c: lambda off by 1.1e-12 with
    the 3e5 kg crank on the 1e-6 kg thigh at rcond 0.84, 4.4e3 eps / rcond).
It prints every case: route, rcond, and vtdyn's errors, with eps / rcond beside them. lambda's
errors on the partly driven loops with a 3e5 kg crank (up to 3.4e-12, 4e-12 on a joint effort
relative to itself) are those of M* and Q formed in double (the exact solution of vtdyn's own
M*, Q, Phi_q and gamma is as far off): docs/accuracy.md, "Mass ratios".

    spread_oracle.py SPREAD_LOOP        (exit 77, skipped, without mpmath)
"""
import copy
import json
import subprocess
import sys

try:
    import mpmath as mp
except ImportError:
    print("spread_oracle: mpmath is not installed (pip install mpmath): skipped")
    sys.exit(77)

mp.mp.dps = 50
EPS = 2.0 ** -52
# VT_KN_* of examples/scenes.h, as the doubles the model holds
A, B, C, D, L = (mp.mpf(x) for x in (0.05, 0.30, 0.045, 0.30, 0.30))
CS = mp.mpf(0.5 * (0.045 + 0.30) - 0.045)
LENGTH = [D, A, B, mp.mpf(0.045 + 0.30)]
TH = [[1, 0, 0, 0], [1, 1, 0, 0], [1, 1, 1, 0], [1, 0, 0, 1]]  # absolute angles from q
OMEGA, TIME_PHASE = 2.0, 0.9  # the drives: a + b sin(OMEGA t + phase), spread_loop.c


def theta(q, k):
    return mp.fsum(TH[k][j] * q[j] for j in range(4))


def point(terms):
    """a point as a sum of lever * u(theta_k)"""
    return lambda q: [mp.fsum(lv * mp.cos(theta(q, k)) for lv, k in terms),
                      mp.fsum(lv * mp.sin(theta(q, k)) for lv, k in terms)]


CENTRE = [point([(D / 2, 0)]), point([(A / 2, 1)]), point([(A, 1), (B / 2, 2)]), point([(D, 0), (CS, 3)])]
LEVER, END = point([(D, 0), (-C, 3)]), point([(A, 1), (B, 2)])


def pin(q):
    """the pin's rows: the coupler's end less the shank's lever point along the shank's y and -x"""
    a, b = LEVER(q), END(q)
    dx, dy = b[0] - a[0], b[1] - a[1]
    c, s = mp.cos(theta(q, 3)), mp.sin(theta(q, 3))
    return [-s * dx + c * dy, -(c * dx + s * dy)]


def jacobian(f, q, qd):
    """df/dq and the bias d^2/ds^2 f(q + s q')"""
    rows = len(f(q))
    J = [[mp.diff(lambda h: f([q[a] + (h if a == j else 0) for a in range(4)])[i], 0) for j in range(4)]
         for i in range(rows)]
    b = [mp.diff(lambda h: f([q[a] + h * qd[a] for a in range(4)])[i], 0, 2) for i in range(rows)]
    return J, b


def exact(case, q=None, qd=None, mass=None):
    """q'', lambda"""
    m = mass or [mp.mpf(x) for x in case["mass"]]
    inertia = [m[k] * mp.mpf(3.0 * 0.01 * 0.01 + float(LENGTH[k]) ** 2) / 12 for k in range(4)]
    q = q or [mp.mpf(x) for x in case["q"]]
    qd = qd or [mp.mpf(x) for x in case["qd"]]
    t = mp.mpf(case["time"])
    M, Q, g = mp.zeros(4, 4), mp.zeros(4, 1), (mp.mpf(0), mp.mpf(-9.81))
    for k in range(4):
        J, b = jacobian(CENTRE[k], q, qd)
        for a in range(4):
            for c in range(4):
                M[a, c] += m[k] * (J[0][a] * J[0][c] + J[1][a] * J[1][c]) + inertia[k] * TH[k][a] * TH[k][c]
            Q[a] += J[0][a] * m[k] * (g[0] - b[0]) + J[1][a] * m[k] * (g[1] - b[1])
    rows, gamma = [], []
    for k in range(2):  # the drives, hip then motor: f'' of a + b sin(OMEGA t + phase)
        if case["drives"] & (1 << k):
            amp = mp.mpf(0.4 if k else 0.35)
            phase = mp.mpf((0.8 if k else 0.0) + TIME_PHASE * case["pose"])
            rows.append([mp.mpf(1) if a == k else mp.mpf(0) for a in range(4)])
            gamma.append(-amp * mp.mpf(OMEGA) ** 2 * mp.sin(mp.mpf(OMEGA) * t + phase))
    J, b = jacobian(pin, q, qd)
    rows += J
    gamma += [-v for v in b]
    nc = len(rows)
    K, rhs = mp.zeros(4 + nc, 4 + nc), mp.zeros(4 + nc, 1)
    for a in range(4):
        for c in range(4):
            K[a, c] = M[a, c]
        rhs[a] = Q[a]
    for r in range(nc):
        for a in range(4):
            K[4 + r, a] = K[a, 4 + r] = rows[r][a]
        rhs[4 + r] = gamma[r]
    x = mp.lu_solve(K, rhs)
    return [x[a] for a in range(4)], [-x[4 + r] for r in range(nc)]


def norm(v):
    return max(abs(a) for a in v)


def rel(a, b):
    return norm([mp.mpf(x) - y for x, y in zip(a, b)]) / norm(b)


def condition(case, qdd, lam):
    """largest normwise relative change of q'' and lambda per relative change of a mass, per rad
    of a q and per rad/s of a q' (differences at 1e-25)"""
    h = mp.mpf("1e-25")
    worst = [mp.mpf(0), mp.mpf(0)]
    for key in ("mass", "q", "qd"):
        for j in range(4):
            v = [mp.mpf(x) for x in case[key]]
            v[j] = v[j] * (1 + h) if key == "mass" else v[j] + h
            q2, l2 = exact(case, **{key: v})
            worst[0] = max(worst[0], norm([a - b for a, b in zip(q2, qdd)]) / h / norm(qdd))
            worst[1] = max(worst[1], norm([a - b for a, b in zip(l2, lam)]) / h / norm(lam))
    return worst


def main():
    out = subprocess.run([sys.argv[1]], capture_output=True, text=True, check=True).stdout
    cases = [json.loads(line) for line in out.splitlines()]
    failures, solved = [], {}
    print("masses (thigh crank coupler shank) drives pose path route rcond warning | problem's condition "
          "| vtdyn's error: q'' lambda (eps / rcond)")
    for case in cases:
        key = (case["dist"], case["drives"], case["pose"])
        full = case["drives"] == 3
        name = "masses %s drives %d pose %d %s" % (case["mass"], case["drives"], case["pose"],
                                                   "recursive" if case["path"] else "dense")
        if case["status"] != 0:
            failures.append("%s: status %d" % (name, case["status"]))
            continue
        if key not in solved:
            qdd, lam = exact(case)
            solved[key] = (qdd, lam, None if full else condition(case, qdd, lam))
        qdd, lam, cond = solved[key]
        eq, el = rel(case["qdd"], qdd), rel(case["lambda"], lam)
        line = "%-34s %d %d %-9s %d %.2e %d |" % (case["mass"], case["drives"], case["pose"],
                                                 "recursive" if case["path"] else "dense", case["route"],
                                                 case["rcond"], case["warning"])
        line += " %.1e %.1e |" % (cond[0], cond[1]) if cond else " - |"
        line += " %.2e %.2e (%.1e)" % (eq, el, EPS / case["rcond"])
        print(line)
        if cond and not (cond[0] < 60 and cond[1] < 60):
            failures.append("%s: the problem itself is ill-conditioned (%s)" % (name, line))
        bq, bl = (1e-13, 1e-13) if full else (1e-12, 1e-11)
        if not eq <= bq:
            failures.append("%s: q'' off by %.3g, more than %.0e" % (name, eq, bq))
        if not el <= bl:
            failures.append("%s: lambda off by %.3g, more than %.0e" % (name, el, bl))
        if case["warning"]:
            failures.append("%s: warns (rcond %.3g)" % (name, case["rcond"]))
        if not max(eq, el) <= 20 * EPS / case["rcond"]:
            failures.append("%s: off by %.3g, more than 20 eps / rcond = %.3g" % (name, max(eq, el), 20 * EPS / case["rcond"]))
    for f in failures:
        print("FAIL " + f)
    print("%d answers against the exact ones, %d failures" % (len(cases), len(failures)))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
