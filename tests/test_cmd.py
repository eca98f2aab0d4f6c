#!/usr/bin/env python3
"""The command vtdyn (cmd/vtdyn.c) on the paper's double link as a URDF file (gravity -9.81
along z, the hinges about z: the arm moves in the horizontal plane, no gravity torque), held to
the closed forms of a planar two-link arm (m = 100 kg, l = 2 m, centres at l/2, I = m l^2/12):

    tau1 = (2 I + m lc^2 + m (l^2 + lc^2 + 2 l lc c2)) a1 + (I + m (lc^2 + l lc c2)) a2
           - m l lc s2 (2 v1 v2 + v2^2)
    tau2 = (I + m (lc^2 + l lc c2)) a1 + (I + m lc^2) a2 + m l lc s2 v1^2

and the joint-1 reaction: the arm's total momentum rate, f = sum m a_c (gravity balanced by
the hinge's vertical force, f_z = 2 m g). States given (to 1e-9), states as samples of a smooth
motion (velocities and accelerations from the splines, to 1e-4 of the largest torque at the
interior samples), the link axes' reaction, and the errors: a missing column, a bad number
(file, row and column named, exit 1, no output file left), samples whose t does not increase (the
row and 't' named), --help. A floating body (a URDF floating joint from the world, and a root
link with --floating): its six efforts against Newton-Euler written here (1e-12), zero in free
flight; a non-unit quaternion refused. The floating body as samples (t and its position and
quaternion alone) against Newton-Euler at the exact motion (1e-5 of the largest effort, second
order in the spacing), a floating arm's samples against its states, a sign-flipped quaternion
sequence, and the samples' refusals. --payload against the payload written into the file as a
fixed link (1e-15). --loads against the closed forms, on states and samples; samples of cubics
(which the splines reproduce) against the states with the exact rates, with --contacts and
--loads.

    test_cmd.py VTDYN URDF_DIR WORKDIR
"""
import ast
import csv
import math
import os
import random
import struct
import subprocess
import sys

M, L, LC, G = 100.0, 2.0, 1.0, 9.81
I = M * L * L / 12.0


def exact(q1, q2, v1, v2, a1, a2):
    c2, s2 = math.cos(q2), math.sin(q2)
    m11 = 2 * I + M * LC * LC + M * (L * L + LC * LC + 2 * L * LC * c2)
    m12 = I + M * (LC * LC + L * LC * c2)
    m22 = I + M * LC * LC
    t1 = m11 * a1 + m12 * a2 - M * L * LC * s2 * (2 * v1 * v2 + v2 * v2)
    t2 = m12 * a1 + m22 * a2 + M * L * LC * s2 * v1 * v1
    # the centres' accelerations (planar), for the ground's force on link 1
    th1, th12 = q1, q1 + q2
    w1, w12, al1, al12 = v1, v1 + v2, a1, a1 + a2

    def acc(r, th, w, al):
        return (-r * math.sin(th) * al - r * math.cos(th) * w * w, r * math.cos(th) * al - r * math.sin(th) * w * w)

    ac1 = acc(LC, th1, w1, al1)
    e1 = acc(L, th1, w1, al1)
    ac2r = acc(LC, th12, w12, al12)
    ac2 = (e1[0] + ac2r[0], e1[1] + ac2r[1])
    f = (M * (ac1[0] + ac2[0]), M * (ac1[1] + ac2[1]), 2 * M * G)
    return t1, t2, f


def motion(t):
    q1, v1, a1 = 0.5 * math.sin(1.3 * t), 0.65 * math.cos(1.3 * t), -0.845 * math.sin(1.3 * t)
    q2, v2, a2 = 0.8 + 0.4 * math.cos(0.9 * t), -0.36 * math.sin(0.9 * t), -0.324 * math.cos(0.9 * t)
    return q1, q2, v1, v2, a1, a2


def run(vtdyn, *args):
    return subprocess.run([vtdyn, *args], capture_output=True, text=True)


def read(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return [{k: float(v) for k, v in r.items()} for r in rows]


# ---- a floating body: one rigid link, its inertial frame off and turned ----------------------
def mat(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)] for i in range(3)]


def tr(a):
    return [[a[j][i] for j in range(3)] for i in range(3)]


def mv(a, x):
    return [sum(a[i][k] * x[k] for k in range(3)) for i in range(3)]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def rpy(r, p, y):
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    rx = [[1, 0, 0], [0, cr, -sr], [0, sr, cr]]
    ry = [[cp, 0, sp], [0, 1, 0], [-sp, 0, cp]]
    rz = [[cy, -sy, 0], [sy, cy, 0], [0, 0, 1]]
    return mat(rz, mat(ry, rx))


def quat_matrix(w, x, y, z):
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]


def solve3(a, b):  # Cramer's rule
    def det(m):
        return (m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
                + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]))
    d = det(a)
    out = []
    for c in range(3):
        m = [[b[i] if j == c else a[i][j] for j in range(3)] for i in range(3)]
        out.append(det(m) / d)
    return out


FM, FC, FRPY = 2.0, [0.1, -0.05, 0.2], [0.3, 0.2, -0.1]
FJ = [[0.3, 0.01, -0.02], [0.01, 0.4, 0.03], [-0.02, 0.03, 0.5]]  # inertial axes


def floater_urdf(path, explicit):
    inertial = ('<inertial><origin xyz="%r %r %r" rpy="%r %r %r"/><mass value="%r"/>'
                '<inertia ixx="%r" ixy="%r" ixz="%r" iyy="%r" iyz="%r" izz="%r"/></inertial>'
                % (*FC, *FRPY, FM, FJ[0][0], FJ[0][1], FJ[0][2], FJ[1][1], FJ[1][2], FJ[2][2]))
    with open(path, "w") as f:
        f.write('<robot name="floater">')
        if explicit:
            f.write('<link name="world"/><joint name="float" type="floating"><parent link="world"/>'
                    '<child link="body"/></joint>')
        f.write('<link name="body">%s</link></robot>\n' % inertial)


def floater_wrench(q, v, a):
    """the wrench at the link origin O, world axes, for the motion (q, v, a) of the link frame"""
    R = quat_matrix(*q[3:7])
    RI = rpy(*FRPY)
    J = mat(R, mat(RI, mat(FJ, tr(mat(R, RI)))))
    c = mv(R, FC)  # centre of mass from O, world
    w, acc, al = v[3:6], a[0:3], a[3:6]
    wc = cross(w, c)
    ac = [acc[k] + cross(al, c)[k] + cross(w, wc)[k] for k in range(3)]
    f = [FM * (ac[k] - (-G if k == 2 else 0.0)) for k in range(3)]
    Jw = mv(J, w)
    n = [mv(J, al)[k] + cross(w, Jw)[k] + cross(c, f)[k] for k in range(3)]
    return f, n, R, J, c


def floating(vtdyn, work, check):
    """A floating root, implicit (--floating) and as a URDF floating joint from the world: its six
    efforts against Newton-Euler by hand (the wrench at the link frame's origin, world and link
    axes), zero for a free flight (a = g at the centre of mass, J alpha + w x J w = 0); samples
    refused, a bad quaternion named"""
    import random
    rnd = random.Random(7)
    for explicit in (0, 1):
        urdf = os.path.join(work, "floater%d.urdf" % explicit)
        floater_urdf(urdf, explicit)
        name = "float" if explicit else "body"
        cols = ["%s_%s" % (name, s) for s in ("x y z qw qx qy qz vx vy vz wx wy wz ax ay az alx aly alz".split())]
        rows, expect = [], []
        for k in range(8):
            qv = [rnd.uniform(-1, 1) for _ in range(4)]
            nq = math.sqrt(sum(x * x for x in qv))
            q = [rnd.uniform(-2, 2) for _ in range(3)] + [x / nq for x in qv]
            v = [rnd.uniform(-2, 2) for _ in range(6)]
            a = [rnd.uniform(-5, 5) for _ in range(6)]
            if k % 2:  # a free flight: the efforts vanish
                R = quat_matrix(*q[3:7])
                RI = rpy(*FRPY)
                J = mat(R, mat(RI, mat(FJ, tr(mat(R, RI)))))
                c = mv(R, FC)
                w = v[3:6]
                al = solve3(J, [-x for x in cross(w, mv(J, w))])
                wc = cross(w, c)
                a = [[0.0, 0.0, -G][i] - cross(al, c)[i] - cross(w, wc)[i] for i in range(3)] + al
            f, n, R, _, _ = floater_wrench(q, v, a)
            rows.append(q + v + a)
            expect.append((f, n, R, k % 2))
        states = os.path.join(work, "floater_states%d.csv" % explicit)
        with open(states, "w") as fh:
            fh.write(",".join(cols) + "\n")
            for r in rows:
                fh.write(",".join(repr(x) for x in r) + "\n")
        args = ["inverse"] + ([] if explicit else ["--floating"]) + [urdf, states]
        r = run(vtdyn, *args)
        check(r.returncode == 0, "floating root (explicit %d): exit %d: %s" % (explicit, r.returncode, r.stderr))
        if r.returncode != 0:
            continue
        out = [{k: float(v) for k, v in row.items()} for row in csv.DictReader(r.stdout.splitlines())]
        check(len(out) == len(rows), "one output row per floating state")
        worst = 0.0
        for row, (f, n, R, flight) in zip(out, expect):
            got_f = [row["%s_effort_f%s" % (name, c)] for c in "xyz"]
            got_n = [row["%s_effort_n%s" % (name, c)] for c in "xyz"]
            got_fl = [row["%s_effort_f%s_link" % (name, c)] for c in "xyz"]
            got_nl = [row["%s_effort_n%s_link" % (name, c)] for c in "xyz"]
            scale = 1 + FM * G + max(abs(x) for x in f + n)
            fl, nl = mv(tr(R), f), mv(tr(R), n)
            for k in range(3):
                worst = max(worst, abs(got_f[k] - f[k]) / scale, abs(got_n[k] - n[k]) / scale,
                            abs(got_fl[k] - fl[k]) / scale, abs(got_nl[k] - nl[k]) / scale)
                if flight:
                    worst = max(worst, abs(got_f[k]) / scale, abs(got_n[k]) / scale)
        check(worst < 1e-12, "floating root (explicit %d): largest relative difference %.3g" % (explicit, worst))
        print("floating root (%s): %d rows, largest relative difference from Newton-Euler %.3g"
              % ("URDF floating joint" if explicit else "--floating", len(out), worst))
    # a quaternion off the unit sphere: the row and the columns named
    urdf = os.path.join(work, "floater1.urdf")
    states = os.path.join(work, "floater_states1.csv")
    lines = open(states).read().splitlines()
    cells = lines[2].split(",")
    cells[3] = repr(float(cells[3]) * 1.01 + 0.01)
    lines[2] = ",".join(cells)
    bad = os.path.join(work, "floater_bad.csv")
    with open(bad, "w") as fh:
        fh.write("\n".join(lines) + "\n")
    r = run(vtdyn, "inverse", urdf, bad)
    check(r.returncode == 1 and "floater_bad.csv:3" in r.stderr and "float_qw" in r.stderr,
          "a quaternion of norm not 1 named: %r" % r.stderr)
    r = run(vtdyn, "info", "--floating", os.path.join(work, "floater0.urdf"))
    check(r.returncode == 0 and "floating" in r.stdout, "info --floating shows the free joint: %r" % r.stdout)
    r = run(vtdyn, "inverse", "--help")
    check(r.returncode == 0 and "R_effort_fx" in r.stdout and "--floating" in r.stdout,
          "--help documents the floating root's columns")


# ---- a floating root given as samples ---------------------------------------------------------
def quat_mul(a, b):
    return [a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
            a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
            a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
            a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]]


Q0 = [0.8, 0.2, -0.4, 0.4]  # a fixed initial orientation (normalised below)
Q0 = [c / math.sqrt(sum(x * x for x in Q0)) for c in Q0]


def root_motion(t):
    """the link frame's pose and its exact rates at t: the origin r(t) = (0.3 sin 1.1t,
    0.2 cos 0.7t, 0.1 t^2 + 0.5), the orientation Rz(th1) Rx(th2) R0 with th1 = 1.2 sin 1.5t,
    th2 = 0.8 sin(2.3t + 0.4): w = th1' z + th2' Rz(th1) x, alpha = th1'' z + th2'' Rz(th1) x +
    th1' th2' (z x Rz(th1) x) (world axes); returns (q, v, a) as floater_wrench takes them"""
    th1, d1, dd1 = 1.2 * math.sin(1.5 * t), 1.8 * math.cos(1.5 * t), -2.7 * math.sin(1.5 * t)
    th2, d2, dd2 = (0.8 * math.sin(2.3 * t + 0.4), 1.84 * math.cos(2.3 * t + 0.4),
                    -4.232 * math.sin(2.3 * t + 0.4))
    qz = [math.cos(th1 / 2), 0.0, 0.0, math.sin(th1 / 2)]
    qx = [math.cos(th2 / 2), math.sin(th2 / 2), 0.0, 0.0]
    quat = quat_mul(qz, quat_mul(qx, Q0))
    r = [0.3 * math.sin(1.1 * t), 0.2 * math.cos(0.7 * t), 0.1 * t * t + 0.5]
    rv = [0.33 * math.cos(1.1 * t), -0.14 * math.sin(0.7 * t), 0.2 * t]
    ra = [-0.363 * math.sin(1.1 * t), -0.098 * math.cos(0.7 * t), 0.2]
    z, ex = [0.0, 0.0, 1.0], [math.cos(th1), math.sin(th1), 0.0]  # Rz(th1) x
    w = [d1 * z[k] + d2 * ex[k] for k in range(3)]
    zx = cross(z, ex)
    al = [dd1 * z[k] + dd2 * ex[k] + d1 * d2 * zx[k] for k in range(3)]
    return r + quat, rv + w, ra + al


def joint_motion(t):
    """two hinges' angles, rates and accelerations at t"""
    return ((0.7 * math.sin(1.7 * t), 1.19 * math.cos(1.7 * t), -2.023 * math.sin(1.7 * t)),
            (0.5 + 0.6 * math.cos(1.2 * t), -0.72 * math.sin(1.2 * t), -0.864 * math.cos(1.2 * t)))


def floater_samples_file(path, ts, flip=False, joints=False):
    cols = ["t"] + (["j1", "j2"] if joints else []) + ["float_%s" % s for s in FREE_COLS[:7]]
    with open(path, "w") as fh:
        fh.write(",".join(cols) + "\n")
        for k, t in enumerate(ts):
            q, _, _ = root_motion(t)
            if flip and k % 2:  # -q: the same orientation
                q = q[:3] + [-c for c in q[3:]]
            js = [m[0] for m in joint_motion(t)] if joints else []
            fh.write(",".join(repr(x) for x in [t] + js + q) + "\n")


def floater_sample_errors(vtdyn, urdf, work, n):
    """n samples over [0, 2] s: the largest difference of the efforts (world and link axes) from
    Newton-Euler at the exact motion, at the samples 10 or more from an end, and the largest
    effort"""
    ts = [2.0 * k / (n - 1) for k in range(n)]
    path = os.path.join(work, "floater_samples%d.csv" % n)
    floater_samples_file(path, ts)
    r = run(vtdyn, "inverse", urdf, path)
    if r.returncode != 0:
        return None, r.stderr
    out = [{k: float(v) for k, v in row.items()} for row in csv.DictReader(r.stdout.splitlines())]
    if len(out) != n:
        return None, "%d rows for %d samples" % (len(out), n)
    worst, big = 0.0, 0.0
    for k, (row, t) in enumerate(zip(out, ts)):
        f, m, R, _, _ = floater_wrench(*root_motion(t))
        fl, ml = mv(tr(R), f), mv(tr(R), m)
        want = f + m + fl + ml
        got = [row["float_effort_%s%s" % (a, c)] for a in "fn" for c in "xyz"]
        got += [row["float_effort_%s%s_link" % (a, c)] for a in "fn" for c in "xyz"]
        big = max(big, max(abs(x) for x in want))
        if 10 <= k < n - 10:
            worst = max(worst, max(abs(x - y) for x, y in zip(got, want)))
    return (worst, big), ""


FLOATING_ARM = """<robot name="floating_arm"><link name="world"/>
<joint name="float" type="floating"><parent link="world"/><child link="body"/></joint>
<link name="body"><inertial><origin xyz="0.1 -0.05 0.2" rpy="0.3 0.2 -0.1"/><mass value="2"/>
<inertia ixx="0.3" ixy="0.01" ixz="-0.02" iyy="0.4" iyz="0.03" izz="0.5"/></inertial></link>
<joint name="j1" type="revolute"><parent link="body"/><child link="l1"/><origin xyz="0.2 0.1 0.3" rpy="0.1 0 0.2"/>
<axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="100" velocity="10"/></joint>
<link name="l1"><inertial><origin xyz="0.25 0 0"/><mass value="1.5"/>
<inertia ixx="0.01" ixy="0" ixz="0" iyy="0.05" iyz="0" izz="0.05"/></inertial></link>
<joint name="j2" type="revolute"><parent link="l1"/><child link="l2"/><origin xyz="0.5 0 0"/>
<axis xyz="0 1 0"/><limit lower="-3" upper="3" effort="100" velocity="10"/></joint>
<link name="l2"><inertial><origin xyz="0.2 0 0.05"/><mass value="1"/>
<inertia ixx="0.01" ixy="0.001" ixz="0" iyy="0.03" iyz="0" izz="0.03"/></inertial></link>
</robot>
"""


def floating_samples(vtdyn, work, check):
    """A floating root given as samples (t, the positions, R_x ... R_qz): its velocities and
    accelerations from the splines through x, y, z and through the quaternion's components
    (normalised). The floater's efforts against Newton-Euler at the exact motion (a general
    rotation, its axis turning), and their second-order convergence (the spline's second
    derivative: O(h^2)); a floating arm's samples against the same rows given as states with the
    exact rates; a sign-flipped quaternion sequence as the plain one; refusals"""
    urdf = os.path.join(work, "floater1.urdf")
    floater_urdf(urdf, 1)
    # At an interior knot of evenly spaced samples the not-a-knot cubic's second derivative is
    # off by about h^2/12 times the fourth derivative (its first derivative by O(h^4)): with
    # h = 1e-3 s and a fourth derivative up to some 20 (th2 = 0.8 sin 2.3t: 0.8 x 2.3^4 = 22;
    # the quaternion's components, of half the angles, less) the accelerations are off by about
    # 2e-6 rad/s^2 and m/s^2, and the efforts (2 kg, inertia up to 0.5 kg m^2) by some 1e-6 N of
    # the largest 22: about 1e-7 of it. 1e-5 of the largest leaves a factor of 100 for the
    # constants and still catches a first-order error (h times the third derivative, ~1e-2).
    # The ten samples at each end are left out: the end pieces' error is larger. The order: the
    # largest error at 251 and 501 samples (h = 8e-3 and 4e-3, far above the round-off's
    # 1e-16 / h^2) falls by 4 (O(h^2)): between 3.5 and 4.6.
    res = {}
    for n in (251, 501, 2001):
        res[n], err = floater_sample_errors(vtdyn, urdf, work, n)
        check(res[n] is not None, "floating root as %d samples: %s" % (n, err))
        if res[n] is None:
            return
    worst, big = res[2001]
    check(worst < 1e-5 * big, "floating root as samples: largest difference %.3g of %.3g (tolerance 1e-5 of it)"
          % (worst, big))
    ratio = res[251][0] / res[501][0]
    check(3.5 < ratio < 4.6, "floating root as samples: error ratio %.3g for half the spacing (O(h^2): 4)" % ratio)
    print("floating root as samples: largest effort difference %.3g of %.3g at 2001 samples; %.3g at 251, %.3g at "
          "501 (ratio %.2f: second order)" % (worst, big, res[251][0], res[501][0], ratio))
    # a sign-flipped sequence (every other sample's quaternion negated): the same output
    ts = [2.0 * k / 500 for k in range(501)]
    plain, flipped = os.path.join(work, "floater_plain.csv"), os.path.join(work, "floater_flip.csv")
    floater_samples_file(plain, ts)
    floater_samples_file(flipped, ts, flip=True)
    a, b = run(vtdyn, "inverse", urdf, plain), run(vtdyn, "inverse", urdf, flipped)
    check(a.returncode == 0 and b.returncode == 0 and a.stdout == b.stdout,
          "a sign-flipped quaternion sequence gives the plain one's output: %s" % b.stderr)
    # a floating arm: samples against the same rows as states with the exact rates
    arm = os.path.join(work, "floating_arm.urdf")
    with open(arm, "w") as fh:
        fh.write(FLOATING_ARM)
    ts = [2.0 * k / 2000 for k in range(2001)]
    samples, states = os.path.join(work, "arm_samples.csv"), os.path.join(work, "arm_states.csv")
    floater_samples_file(samples, ts, joints=True)
    with open(states, "w") as fh:
        fh.write(",".join(["t", "j1", "j1_vel", "j1_acc", "j2", "j2_vel", "j2_acc"]
                          + ["float_%s" % s for s in FREE_COLS]) + "\n")
        for t in ts:
            q, v, acc = root_motion(t)
            js = [x for m in joint_motion(t) for x in m]
            fh.write(",".join(repr(x) for x in [t] + js + q + v + acc) + "\n")
    a, b = run(vtdyn, "inverse", arm, states), run(vtdyn, "inverse", arm, samples)
    check(a.returncode == 0 and b.returncode == 0, "a floating arm as states and as samples: %s %s"
          % (a.stderr, b.stderr))
    if a.returncode == 0 and b.returncode == 0:
        ra, rb = list(csv.reader(a.stdout.splitlines())), list(csv.reader(b.stdout.splitlines()))
        check(ra[0] == rb[0] and len(ra) == len(rb) == len(ts) + 1, "the same columns and rows")
        big = max(abs(float(c)) for row in ra[1:] for c in row[1:])
        worst = max(abs(float(x) - float(y)) for k in range(11, len(ts) - 9) for x, y in zip(ra[k], rb[k]))
        check(worst < 1e-5 * big, "a floating arm's samples against its states: largest difference %.3g of %.3g "
              "(tolerance 1e-5 of it)" % (worst, big))
        print("floating arm: %d samples against the states, %d columns: largest difference %.3g of %.3g"
              % (len(ts), len(ra[0]), worst, big))
    # refusals: a quaternion off the unit norm (its line named), a missing column, rates mixed in
    lines = open(plain).read().splitlines()
    cells = lines[5].split(",")
    cells[4] = repr(float(cells[4]) * 1.01)
    bad = os.path.join(work, "floater_bad_samples.csv")
    with open(bad, "w") as fh:
        fh.write("\n".join(lines[:5] + [",".join(cells)] + lines[6:]) + "\n")
    r = run(vtdyn, "inverse", urdf, bad)
    check(r.returncode == 1 and "floater_bad_samples.csv:6" in r.stderr and "float_qw" in r.stderr
          and "--normalize-quaternions" in r.stderr, "a non-unit quaternion sample named: %r" % r.stderr)
    r = run(vtdyn, "inverse", "--normalize-quaternions", "0.02", urdf, bad)
    check(r.returncode == 0, "a quaternion sample within --normalize-quaternions taken: %r" % r.stderr)
    with open(bad, "w") as fh:
        fh.write("\n".join(",".join(line.split(",")[:7]) for line in lines) + "\n")
    r = run(vtdyn, "inverse", urdf, bad)
    check(r.returncode == 1 and "'float_qz'" in r.stderr, "a missing float_qz named: %r" % r.stderr)
    with open(bad, "w") as fh:
        fh.write(lines[0] + ",float_vx\n" + "\n".join(line + ",0" for line in lines[1:]) + "\n")
    r = run(vtdyn, "inverse", urdf, bad)
    check(r.returncode == 1 and "'float_vy'" in r.stderr, "a floating root's rates in part refused: %r" % r.stderr)
    alines = open(samples).read().splitlines()
    with open(bad, "w") as fh:
        fh.write(alines[0] + ",float_vx\n" + "\n".join(line + ",0" for line in alines[1:]) + "\n")
    r = run(vtdyn, "inverse", arm, bad)
    check(r.returncode == 1 and "'float_vx'" in r.stderr and "samples" in r.stderr,
          "the root's rates with the joints' positions alone refused: %r" % r.stderr)
    slines = open(states).read().splitlines()
    keep = [k for k, c in enumerate(slines[0].split(",")) if not (c.startswith("float_") and c[6:] in FREE_COLS[7:])]
    with open(bad, "w") as fh:
        fh.write("\n".join(",".join(line.split(",")[k] for k in keep) for line in slines) + "\n")
    r = run(vtdyn, "inverse", arm, bad)
    check(r.returncode == 1 and "'float_vx'" in r.stderr and "samples" in r.stderr,
          "the joints' rates with the root's positions alone refused: %r" % r.stderr)


def strict(vtdyn, urdf, states, work, check):
    """Nothing ignored, nothing overwritten: an unknown column (a typo), a floating root's columns
    on a robot loaded fixed, a column twice (in a header of 110,000 names) each stop the run naming
    the file, the header's line and the column; -o naming an input (under its own or another name),
    a directory or a device is refused and leaves it as it was; a quoted header reads as the plain
    one; a header separated by ';' or tabs says so; --version; a one-link robot loaded fixed says
    how to float it"""
    lines = open(states).read().splitlines()
    bad = os.path.join(work, "strict.csv")

    def write(header, rows=lines[1:3]):
        with open(bad, "w") as f:
            f.write(header + "\n" + "\n".join(rows) + "\n")

    write(lines[0].replace("joint2_acc", "joint2_acc,joint3_vel"), [r + ",0" for r in lines[1:3]])
    r = run(vtdyn, "inverse", urdf, bad)
    check(r.returncode == 1 and "strict.csv:1: column 8 'joint3_vel' is none of the robot's" in r.stderr
          and r.stdout == "", "an unknown column stops the run, named: %r" % r.stderr)
    write(lines[0].replace("joint2_vel", "joint2_vell"))
    r = run(vtdyn, "inverse", urdf, bad)
    check(r.returncode == 1 and "joint2" in r.stderr and r.stdout == "", "a misspelt column stops the run: %r" % r.stderr)
    # the double link on a root link "base" (not "world": fixed to the world unless --floating),
    # its columns given as a floating root's
    based = os.path.join(work, "double_link_base.urdf")
    with open(based, "w") as f:
        f.write(open(urdf).read().replace('"world"', '"base"'))
    root = ",".join("base_" + c for c in "x y z qw qx qy qz vx vy vz wx wy wz ax ay az alx aly alz".split())
    write(lines[0] + "," + root, [r + "," + ",".join(["0"] * 3 + ["1"] + ["0"] * 15) for r in lines[1:3]])
    r = run(vtdyn, "inverse", based, bad)
    check(r.returncode == 1 and "'base_x'" in r.stderr and "run with --floating" in r.stderr,
          "a floating root's columns on a fixed robot say --floating: %r" % r.stderr)
    r = run(vtdyn, "inverse", "--floating", based, states)
    check(r.returncode == 1 and "'base_x'" in r.stderr and "without --floating" in r.stderr,
          "--floating without the root's columns says the way back: %r" % r.stderr)
    # a header of 110,000 names with one twice, far apart
    names = ["c%d" % k for k in range(110000)]
    names[109999] = "c17"
    write(",".join(names), [",".join(["0"] * 110000)])
    r = run(vtdyn, "inverse", urdf, bad)
    check(r.returncode == 1 and "column 'c17' twice (columns 18 and 110000)" in r.stderr,
          "a name twice in a wide header: %r" % r.stderr[:300])
    # quoted names (RFC 4180, one with a comma inside, unknown) and quoted numbers
    quoted = ",".join('"%s"' % n for n in lines[0].split(","))
    write(quoted, [",".join('"%s"' % c if k % 2 else c for k, c in enumerate(row.split(","))) for row in lines[1:3]])
    r = run(vtdyn, "inverse", urdf, bad)
    plain = run(vtdyn, "inverse", urdf, states)
    check(r.returncode == 0 and r.stdout.splitlines() == plain.stdout.splitlines()[:3],
          "a quoted header and quoted numbers read as plain ones: %r" % r.stderr)
    write(quoted + ',"a ""b"", c"', [row + ",0" for row in lines[1:3]])
    r = run(vtdyn, "inverse", urdf, bad)
    check(r.returncode == 1 and "column 8 'a \"b\", c'" in r.stderr, "a quoted name unquoted in the message: %r" % r.stderr)
    write(quoted + ',"open')
    r = run(vtdyn, "inverse", urdf, bad)
    check(r.returncode == 1 and "column 8: a quote not closed" in r.stderr, "an open quote named: %r" % r.stderr)
    # the same file exported with ';' (a comma-decimal locale's spreadsheet) or tabs between cells
    for sep, said in ((";", "separated by ';'"), ("\t", "separated by tabs")):
        write(lines[0].replace(",", sep), [row.replace(",", sep).replace(".", ",") for row in lines[1:3]])
        r = run(vtdyn, "inverse", urdf, bad, "-o", os.path.join(work, "sep_out.csv"))
        check(r.returncode == 1 and "strict.csv:1: the header is one column, its names %s (the first '%s')"
              % (said, lines[0].split(",")[0]) in r.stderr and "comma-separated" in r.stderr
              and not os.path.exists(os.path.join(work, "sep_out.csv")),
              "a header separated by %r named as such, no output: %r" % (sep, r.stderr))
    # -o: an input (the states, the URDF, a hard link to the states), a directory, a device
    before = {p: open(p, "rb").read() for p in (states, urdf)}
    link = os.path.join(work, "states_link.csv")
    if os.path.exists(link):
        os.remove(link)
    os.link(states, link)
    for target, what in ((states, "is the input"), (urdf, "is the input"), (link, "is the input"),
                         (work, "not a regular file"), ("/dev/null", "not a regular file")):
        r = run(vtdyn, "inverse", urdf, states, "-o", target)
        check(r.returncode == 1 and what in r.stderr, "-o %s refused: %r" % (target, r.stderr))
    check(all(open(p, "rb").read() == b for p, b in before.items()), "the inputs untouched by a refused -o")
    check(os.path.exists("/dev/null") and not os.path.isfile("/dev/null"), "/dev/null still a device")
    os.remove(link)
    r = run(vtdyn, "--version")
    check(r.returncode == 0 and r.stdout.startswith("vtdyn ") and r.stdout.count(".") == 2, "--version: %r" % r.stdout)
    floater_urdf(os.path.join(work, "one_link.urdf"), 0)
    r = run(vtdyn, "info", os.path.join(work, "one_link.urdf"))
    check(r.returncode == 1 and "with --floating the root link floats" in r.stderr,
          "a one-link robot loaded fixed says how to float it: %r" % r.stderr)


# ---- .npy files: the test's own reader and writer (struct and ast, not the command's code) ------
NPY_MAGIC = b"\x93NUMPY"


def npy_bytes(names, rows, version=(1, 0), descr=None, fortran=False, shape=None, extra="", typestr="<f8",
              endian="<", encoding=None):
    """a .npy file of the structured array (names, '<f8') of rows, as numpy writes it; the
    arguments other than names and rows make the layouts the command refuses"""
    if descr is None:
        descr = "[%s]" % ", ".join("(%r, %r)" % (n, typestr) for n in names)
    if shape is None:
        shape = "(%d,)" % len(rows)
    d = "{'descr': %s, 'fortran_order': %s, 'shape': %s, %s}" % (descr, fortran, shape, extra)
    enc = encoding or ("utf-8" if version[0] >= 3 else "latin-1")
    body = d.encode(enc)
    field = 2 if version[0] == 1 else 4
    total = (6 + 2 + field + len(body) + 1 + 63) // 64 * 64
    hlen = total - 6 - 2 - field
    head = NPY_MAGIC + bytes(version) + struct.pack("<H" if field == 2 else "<I", hlen)
    head += body + b" " * (hlen - len(body) - 1) + b"\n"
    fmt = struct.Struct(endian + "%dd" % len(names)) if names else None
    return head + b"".join(fmt.pack(*r) for r in rows)


def npy_write(path, names, rows, **kw):
    with open(path, "wb") as f:
        f.write(npy_bytes(names, rows, **kw))


def npy_read(path):
    """(names, rows, version, header length) of a .npy file of '<f8' fields, shape (N,), C order,
    the layout checked as NEP 1 says (magic, version, a header padded with spaces to a multiple of
    64 bytes and ended by a newline, the size)"""
    data = open(path, "rb").read()
    assert data[:6] == NPY_MAGIC, "magic"
    version = (data[6], data[7])
    assert version in ((1, 0), (2, 0), (3, 0)), "version %r" % (version,)
    field = 2 if version[0] == 1 else 4
    hlen = struct.unpack("<H" if field == 2 else "<I", data[8:8 + field])[0]
    start = 8 + field + hlen
    assert start % 64 == 0, "the data at %d, not a multiple of 64" % start
    text = data[8 + field:start].decode("utf-8" if version[0] >= 3 else "latin-1")
    assert text.endswith("\n"), "the header ends with a newline"
    d = ast.literal_eval(text)
    assert set(d) == {"descr", "fortran_order", "shape"}, "keys %r" % sorted(d)
    assert d["fortran_order"] is False and len(d["shape"]) == 1, "C order, shape (N,)"
    names = [n for n, t in d["descr"]]
    assert all(t == "<f8" for n, t in d["descr"]), "every field '<f8'"
    n = d["shape"][0]
    assert len(data) == start + 8 * len(names) * n, "size %d for %d rows" % (len(data), n)
    fmt = struct.Struct("<%dd" % len(names))
    rows = [fmt.unpack_from(data, start + k * fmt.size) for k in range(n)]
    return names, rows, version, hlen


def csv_table(text):
    """(names, rows of the cells' strings) of a CSV text"""
    lines = text.splitlines()
    return lines[0].split(","), [ln.split(",") for ln in lines[1:]]


def same_as_csv(npy_path, csv_text):
    """a .npy output holds exactly the doubles the CSV output's cells read back as"""
    names, rows, _, _ = npy_read(npy_path)
    cnames, crows = csv_table(csv_text)
    return names == cnames and len(rows) == len(crows) and all(
        struct.pack("<d", v) == struct.pack("<d", float(c)) for r, cr in zip(rows, crows) for v, c in zip(r, cr))


RSS_HELPER = """import os, sys
pid = os.fork()
if pid == 0:
    os.execv(sys.argv[1], sys.argv[1:])
_, status, usage = os.wait4(pid, 0)
print(os.waitstatus_to_exitcode(status), usage.ru_maxrss)
"""


def run_rss(vtdyn, *args):
    """the command's exit status and peak resident memory (kB), forked from a fresh interpreter
    (a child's peak counts the memory of the process it was forked from: not this script's)"""
    r = subprocess.run([sys.executable, "-c", RSS_HELPER, vtdyn, *args], capture_output=True, text=True)
    code, kb = r.stdout.split()
    return int(code), int(kb)


def double_link_rows(n, seed):
    rnd = random.Random(seed)
    return [[0.01 * k] + [rnd.uniform(-3, 3) for _ in range(6)] for k in range(n)]


DL_COLS = "t,joint1,joint1_vel,joint1_acc,joint2,joint2_vel,joint2_acc".split(",")


def write_csv(path, names, rows):
    with open(path, "w") as f:
        f.write(",".join(names) + "\n")
        for r in rows:
            f.write(",".join(repr(x) for x in r) + "\n")


def chunks_threads(vtdyn, urdf, work, check):
    """States read and solved in chunks on threads: the output's bytes the same for -j 1 and -j 3
    on 9,000 rows (18 chunks of 512 rows on one thread, three of 4,096 on more) and on a floating
    root's rows, and the same as each row's alone;
    the first failing row of a chunk named (a cell, a solve), for any -j, with no output left;
    the resident memory flat in the number of rows"""
    big = os.path.join(work, "many.csv")
    rows = double_link_rows(9000, 11)
    write_csv(big, DL_COLS, rows)
    outs = {}
    for j in ("1", "3"):
        out = os.path.join(work, "many_j%s.csv" % j)
        r = run(vtdyn, "inverse", "-j", j, urdf, big, "-o", out)
        check(r.returncode == 0, "9,000 rows with -j %s: %s" % (j, r.stderr))
        outs[j] = open(out, "rb").read() if r.returncode == 0 else b""
    check(outs["1"] == outs["3"] and outs["1"].count(b"\n") == 9001, "-j 1 and -j 3 write the same bytes")
    few = os.path.join(work, "few.csv")
    write_csv(few, DL_COLS, rows[4090:4100])  # across a chunk's end, on any number of threads
    r = run(vtdyn, "inverse", urdf, few)
    check(r.returncode == 0 and r.stdout.encode().splitlines()[1:] == outs["1"].splitlines()[4091:4101],
          "rows across a chunk's end as alone")
    for j in ("1", "3"):
        r1 = run(vtdyn, "inverse", "-j", j, urdf, big, "--format", "csv")
        check(r1.returncode == 0 and r1.stdout.encode() == outs["1"], "-j %s on standard output" % j)
    # a floating root: its quaternions normalised and its link axes, -j 1 and -j 3
    urdf_f = os.path.join(work, "floater1.urdf")
    floater_urdf(urdf_f, 1)
    rnd = random.Random(5)
    fcols = ["float_" + s for s in FREE_COLS]
    frows = []
    for _ in range(5000):
        qv = [rnd.uniform(-1, 1) for _ in range(4)]
        nq = math.sqrt(sum(x * x for x in qv))
        frows.append([rnd.uniform(-2, 2) for _ in range(3)] + [x / nq for x in qv] + [rnd.uniform(-5, 5) for _ in range(12)])
    fstates = os.path.join(work, "floater_many.csv")
    write_csv(fstates, fcols, frows)
    got = [run(vtdyn, "inverse", "-j", j, urdf_f, fstates) for j in ("1", "3")]
    check(all(g.returncode == 0 for g in got) and got[0].stdout == got[1].stdout and len(got[0].stdout.splitlines()) == 5001,
          "a floating root's rows: -j 1 and -j 3 the same")
    # the first failing row of a chunk: a cell (row 8200, in the last chunk), a state that fails its
    # solve (row 5000, joint velocities of 1e200) before a bad cell in the same chunk (row 5003),
    # and a bad cell (4999) before a failing state (5000) (one chunk for both, 4608-5119 or 4096-8191)
    def broken(changes):
        lines = [",".join(repr(x) for x in r) for r in rows]
        for k, col, text in changes:
            cells = lines[k].split(",")
            cells[col] = text
            lines[k] = ",".join(cells)
        with open(os.path.join(work, "broken.csv"), "w") as f:
            f.write(",".join(DL_COLS) + "\n" + "\n".join(lines) + "\n")
        return os.path.join(work, "broken.csv")

    never = os.path.join(work, "never_many.csv")
    for changes, line, what in (([(8200, 2, "x1")], 8202, "'joint1_vel': 'x1'"),
                                ([(5000, 2, "1e200"), (5000, 5, "1e200"), (5003, 3, "oops")], 5002, "overflow"),
                                ([(4999, 3, "oops"), (5000, 2, "1e200"), (5000, 5, "1e200")], 5001, "'oops'")):
        path = broken(changes)
        for j in ("1", "3"):
            r = run(vtdyn, "inverse", "-j", j, urdf, path, "-o", never)
            check(r.returncode == 1 and ("broken.csv:%d:" % line) in r.stderr and what in r.stderr
                  and not os.path.exists(never) and not os.path.exists(never + ".part"),
                  "the first failing row named (line %d, -j %s), no output left: %r" % (line, j, r.stderr))
    # the resident memory: flat in the rows (chunks of at most 4,096 rows), CSV and .npy in
    if "ASAN_OPTIONS" in os.environ or "TSAN_OPTIONS" in os.environ or "VALGRIND" in os.environ:
        print("resident memory: not measured under a sanitizer (its shadow memory grows with what is touched)")
        return
    rss = {}
    for n in (4000, 60000):
        src = os.path.join(work, "rss_%d.npy" % n)
        npy_write(src, DL_COLS, double_link_rows(n, 3))
        code, rss[("npy", n)] = run_rss(vtdyn, "inverse", urdf, src, "-o", os.path.join(work, "rss_out.npy"))
        check(code == 0, "%d rows from .npy" % n)
        src_csv = os.path.join(work, "rss_%d.csv" % n)
        write_csv(src_csv, DL_COLS, double_link_rows(n, 3))
        code, rss[("csv", n)] = run_rss(vtdyn, "inverse", urdf, src_csv, "-o", os.path.join(work, "rss_out.npy"))
        check(code == 0, "%d rows from CSV" % n)
    for kind in ("npy", "csv"):
        grow = rss[(kind, 60000)] - rss[(kind, 4000)]
        check(grow < 4096, "resident memory flat in the rows (%s): %d kB more for 15 times the rows" % (kind, grow))
        print("resident memory (%s in, .npy out): %d kB for 4,000 rows, %d kB for 60,000" % (kind, rss[(kind, 4000)],
                                                                                            rss[(kind, 60000)]))
    os.remove(os.path.join(work, "rss_out.npy"))


FREE_COLS = "x y z qw qx qy qz vx vy vz wx wy wz ax ay az alx aly alz".split()


def npy_files(vtdyn, urdf, states, work, check):
    """NumPy files in and out: npy->npy, csv->npy, npy->csv against csv->csv (the .npy doubles
    bitwise those the CSV's cells read back as), samples from .npy, the header (format 1.0, 2.0
    for a wide one, 3.0 for a name that is not ASCII; padded to 64 bytes; the row count rewritten
    after a CSV input), numpy.load when numpy is there, and every other layout refused, named"""
    ref = run(vtdyn, "inverse", urdf, states)
    check(ref.returncode == 0, "csv -> csv reference: %s" % ref.stderr)
    names, crows = csv_table(open(states).read())
    rows = [[float(c) for c in r] for r in crows]
    snpy = os.path.join(work, "states.npy")
    npy_write(snpy, names, rows)
    for src, what in ((snpy, "npy -> npy"), (states, "csv -> npy")):
        out = os.path.join(work, "out_%s.npy" % ("n" if src == snpy else "c"))
        r = run(vtdyn, "inverse", urdf, src, "-o", out)
        check(r.returncode == 0 and same_as_csv(out, ref.stdout), "%s: the CSV output's values, bitwise: %s"
              % (what, r.stderr))
        if r.returncode == 0:
            _, got, version, hlen = npy_read(out)
            check(version == (1, 0) and len(got) == len(rows), "%s: format 1.0, %d rows" % (what, len(got)))
    # the rows known, the output's size is reserved first: a file system without room for it
    # (here the process's file-size limit, SIGXFSZ ignored so that the call fails instead) stops
    # the run before any row is written, says so, and leaves no file
    if sys.platform.startswith("linux"):
        import resource
        import signal

        def small_files():
            signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
            resource.setrlimit(resource.RLIMIT_FSIZE, (65536, 65536))

        big = os.path.join(work, "rows_1000.npy")
        npy_write(big, DL_COLS, double_link_rows(1000, 5))
        full = os.path.join(work, "full.npy")
        r = subprocess.run([vtdyn, "inverse", urdf, big, "-o", full], capture_output=True, text=True,
                           preexec_fn=small_files)
        check(r.returncode == 1 and "full.npy.part: no room for the results' " in r.stderr
              and not os.path.exists(full) and not os.path.exists(full + ".part"),
              "no room for a .npy output: refused before its rows, no file left: %r" % r.stderr)
    r = run(vtdyn, "inverse", urdf, snpy)
    check(r.returncode == 0 and r.stdout == ref.stdout, "npy -> csv: the bytes of csv -> csv")
    r = subprocess.run([vtdyn, "inverse", urdf, snpy, "--format", "npy"], capture_output=True)
    check(r.returncode == 0 and open(os.path.join(work, "out_n.npy"), "rb").read() == r.stdout,
          "npy on standard output (a .npy input: the rows known ahead) as the file")
    # numpy itself, when it is there
    try:
        import numpy
    except ImportError:
        numpy = None
        print("numpy.load: skipped (numpy is not installed for %s)" % sys.executable)
    if numpy is not None:
        arr = numpy.load(os.path.join(work, "out_c.npy"))
        _, want, _, _ = npy_read(os.path.join(work, "out_c.npy"))
        check(arr.shape == (len(rows),) and arr.dtype.names[1] == "joint1_effort"
              and all(float(arr["joint1_effort"][k]) == want[k][1] for k in range(len(rows))),
              "numpy.load reads the output: arr['joint1_effort']")
        numpy.save(os.path.join(work, "by_numpy.npy"), numpy.rec.fromarrays([numpy.array(c) for c in zip(*rows)],
                                                                              names=",".join(names)))
        r = run(vtdyn, "inverse", urdf, os.path.join(work, "by_numpy.npy"))
        check(r.returncode == 0 and r.stdout == ref.stdout, "a file numpy.save wrote is read: %s" % r.stderr)
        print("numpy.load: the output read by numpy %s" % numpy.__version__)
    # samples from .npy as from CSV
    samples = os.path.join(work, "samples.csv")
    sn, srows = csv_table(open(samples).read())
    npy_write(os.path.join(work, "samples.npy"), sn, [[float(c) for c in r] for r in srows])
    a, b = run(vtdyn, "inverse", urdf, samples), run(vtdyn, "inverse", urdf, os.path.join(work, "samples.npy"))
    check(a.returncode == 0 and a.stdout == b.stdout, "samples from .npy as from CSV: %s" % b.stderr)
    r = subprocess.run([vtdyn, "inverse", urdf, samples, "--format", "npy"], capture_output=True)
    check(r.returncode == 0 and r.stdout.startswith(NPY_MAGIC),
          "samples to npy on standard output (the rows known): %s" % r.stderr)
    # format 2.0 in and out (a header past 65,535 bytes: a chain of 420 links, 5,461 output columns)
    chain = os.path.join(work, "chain.urdf")
    with open(chain, "w") as f:
        f.write('<robot name="chain"><link name="world"/>')
        for k in range(420):
            f.write('<link name="l%d"><inertial><origin xyz="0.05 0 0"/><mass value="1"/><inertia ixx="0.001" '
                    'ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/></inertial></link>' % k)
            f.write('<joint name="j%d" type="revolute"><parent link="%s"/><child link="l%d"/><origin xyz="0.1 0 0"/>'
                    '<axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>'
                    % (k, "world" if k == 0 else "l%d" % (k - 1), k))
        f.write("</robot>\n")
    cnames = sum(([j, j + "_vel", j + "_acc"] for j in ("j%d" % k for k in range(420))), [])
    crow = [0.001 * (k % 7) for k in range(len(cnames))]
    cin = os.path.join(work, "chain_in.npy")
    npy_write(cin, cnames, [crow, crow], version=(2, 0))
    cout = os.path.join(work, "chain_out.npy")
    r = run(vtdyn, "inverse", chain, cin, "-o", cout)
    ok = r.returncode == 0
    if ok:
        on, orows, version, hlen = npy_read(cout)
        ok = version == (2, 0) and hlen > 65535 and len(on) == 420 * 13 and len(orows) == 2
    check(ok, "format 2.0 read, and written for a header past 65,535 bytes: %s" % r.stderr[:300])
    # format 3.0: a joint named in UTF-8, read from 3.0 and from 1.0 (latin-1), written as 3.0
    uurdf = os.path.join(work, "double_link_utf8.urdf")
    with open(uurdf, "w", encoding="utf-8") as f:
        f.write(open(urdf).read().replace('"joint2"', '"jöint2"'))
    un = [n.replace("joint2", "jöint2") for n in names]
    for version in ((3, 0), (1, 0)):
        uin = os.path.join(work, "utf8_in.npy")
        npy_write(uin, un, rows, version=version)
        uout = os.path.join(work, "utf8_out.npy")
        r = run(vtdyn, "inverse", uurdf, uin, "-o", uout)
        ok = r.returncode == 0
        if ok:
            on, orows, v, _ = npy_read(uout)
            ok = v == (3, 0) and "jöint2_effort" in on and len(orows) == len(rows)
        check(ok, "a name in UTF-8 read from format %d.0, written as 3.0: %s" % (version[0], r.stderr))
    # a link frame turned from the body's axes (link 2's inertial frame turned about the rod):
    # the link axes' columns as the plain double link's
    turned = os.path.join(work, "double_link_turned.urdf")
    text = open(urdf).read()
    k = text.index('<link name="link2">')
    with open(turned, "w") as f:
        f.write(text[:k] + text[k:].replace('rpy="0 0 0"', 'rpy="0.7 0 0"', 1))
    r = run(vtdyn, "inverse", turned, states)
    ok = r.returncode == 0
    if ok:
        a_n, a_rows = csv_table(ref.stdout)
        b_n, b_rows = csv_table(r.stdout)
        worst = max(abs(float(x) - float(y)) / (1 + abs(float(x))) for ra, rb in zip(a_rows, b_rows)
                    for x, y in zip(ra, rb))
        ok = a_n == b_n and worst < 1e-12
    check(ok, "a link's axes turned from its body's: the same link-axes reactions: %s" % r.stderr)
    # the layouts refused, each named with what was found
    bad = os.path.join(work, "bad.npy")
    n = len(names)
    plain = npy_bytes(names, rows, descr="'<f8'", shape="(%d, %d)" % (len(rows), n))
    cases = [
        (plain, "a plain array of '<f8' of shape (12, 7)", "unstructured_to_structured"),
        (npy_bytes(names, rows, typestr=">f8", endian=">"), "field 't' is '>f8'", "little-endian"),
        (npy_bytes(names, rows, typestr="<f4"), "field 't' is '<f4'", "'<f8'"),
        (npy_bytes(names, rows, fortran=True), "fortran_order True", "C order"),
        (npy_bytes(names, rows[:6], shape="(3, 2)"), "shape (3, 2)", "(N,)"),
        (npy_bytes(names, rows)[:-8], "truncated", "12 rows of 7 float64 fields"),
        (npy_bytes(names, rows) + b"\0" * 8, "bytes after the data", "12 rows"),
        (b"PK\x03\x04" + b"\0" * 60, "not a .npy file", "x93NUMPY"),
        (NPY_MAGIC + b"\x04\x00" + b"\0" * 60, "format version 4.0", "1.0, 2.0 and 3.0"),
        (NPY_MAGIC + b"\x02\x00" + struct.pack("<I", 1 << 30), "1073741824 bytes", "bound"),
        (npy_bytes(names, rows, extra="'x': 1, "), "a key 'x'", "descr"),
        (npy_bytes(["t", "t"], [r[:2] for r in rows]), "field 't' twice", "fields 1 and 2"),
        (npy_bytes(names, rows, descr="[('t', '<f8'), ('j', [('a', '<f8')])]"), "field 'j' is a nested", "'<f8'"),
        (npy_bytes(names, rows, descr="[('t', '<f8', (2,))]"), "field 't' is a subarray", "'<f8'"),
        (npy_bytes(names, rows, descr="[('t', '<f8'), ('', '|V8')]"), "field '' has no name", "'<f8'"),
        (npy_bytes(names, rows, descr="[]"), "no fields", "structured"),
        (NPY_MAGIC + b"\x01\x00" + struct.pack("<H", 54) + b"{'descr': [('t', '<f8'" + b" " * 31 + b"\n",
         "not a dict", "unreadable"),
    ]
    for data, what, hint in cases:
        with open(bad, "wb") as f:
            f.write(data)
        r = run(vtdyn, "inverse", urdf, bad, "-o", os.path.join(work, "never.npy"))
        check(r.returncode == 1 and "bad.npy" in r.stderr and what in r.stderr and hint in r.stderr
              and not os.path.exists(os.path.join(work, "never.npy")),
              "a .npy layout refused, named (%s): %r" % (what, r.stderr))
    rows_nan = [list(r) for r in rows]
    rows_nan[3][5] = float("nan")
    npy_write(bad, names, rows_nan)
    r = run(vtdyn, "inverse", urdf, bad)
    check(r.returncode == 1 and "bad.npy[3]: column 'joint2_vel': nan is not a finite number" in r.stderr,
          "a NaN in a .npy file: its row (index) and column: %r" % r.stderr)
    npy_write(bad, names + ["joint3_vel"], [r + [0.0] for r in rows])
    r = run(vtdyn, "inverse", urdf, bad)
    check(r.returncode == 1 and "bad.npy: column 8 'joint3_vel' is none of the robot's" in r.stderr,
          "an unknown field stops the run, named: %r" % r.stderr)
    npy_write(bad, names, [])
    r = run(vtdyn, "inverse", urdf, bad)
    check(r.returncode == 1 and "no data rows" in r.stderr, "a .npy file of no rows: %r" % r.stderr)
    # npy on standard output needs the rows ahead; -o and --format agree; --precision is for CSV
    for args, what in ((["--format", "npy"], "-o OUT.npy"), (["-o", os.path.join(work, "x.csv"), "--format", "npy"],
                                                            "disagree"),
                       (["-o", os.path.join(work, "x.npy"), "--precision", "5"], "--precision")):
        r = run(vtdyn, "inverse", urdf, states, *args)
        check(r.returncode == 1 and what in r.stderr and r.stdout == "", "%s refused: %r" % (" ".join(args), r.stderr))


def significant(cell):
    """the significant digits of a number's text ('-1.250e+03' -> '125')"""
    m = cell.lstrip("+-").lower().split("e")[0].replace(".", "")
    return m.lstrip("0").rstrip("0") or "0"


def number_text(vtdyn, urdf, states, work, check):
    """cells as C's strtod reads them, the output's cells the shortest that read back (against
    Python's repr, David Gay's shortest), --precision P as printf's %.Pg (Python's %-format)"""
    lines = open(states).read().splitlines()
    plain = run(vtdyn, "inverse", urdf, states)
    names, rows = csv_table(plain.stdout)
    cells = [c for row in rows for c in row]
    check(plain.returncode == 0 and all(significant(c) == significant(repr(float(c))) for c in cells),
          "every output cell has the fewest digits that read back: %s" % next(
              (c for c in cells if significant(c) != significant(repr(float(c)))), plain.stderr))
    for p in (1, 6, 12, 17):
        r = run(vtdyn, "inverse", "--precision", str(p), urdf, states)
        n, prows = csv_table(r.stdout) if r.returncode == 0 else ([], [])
        check(r.returncode == 0 and n == names and len(prows) == len(rows)
              and all(c == "%.*g" % (p, float(fc)) for row, fr in zip(prows, rows) for c, fc in zip(row, fr)),
              "--precision %d: every number as %%.%dg: %s" % (p, p, r.stderr))
    # the same doubles in other spellings strtod reads: '+', blanks, a hexadecimal float, an
    # exponent, a point without digits after it
    values = [[float(c) for c in ln.split(",")] for ln in lines[1:4]]
    spell = (lambda v: repr(v) if repr(v)[0] == "-" else "+" + repr(v), lambda v: " %r\t" % v, lambda v: v.hex(),
             lambda v: "%.17e" % v, lambda v: "%.0f." % v if v == int(v) else repr(v))
    other = os.path.join(work, "spelled.csv")
    with open(other, "w") as fh:
        fh.write(lines[0] + "\n")
        for k, row in enumerate(values):
            fh.write(",".join(spell[(k + c) % len(spell)](v) for c, v in enumerate(row)) + "\n")
    r = run(vtdyn, "inverse", urdf, other)
    check(r.returncode == 0 and r.stdout.splitlines() == plain.stdout.splitlines()[:4],
          "'+', blanks, hexadecimal and exponents read as the same doubles: %r" % r.stderr)
    for cell in ("1e400", "-1e400", "1e", "--1", "0x", "nan", "inf", "1.5.2", "1x", "+", "."):
        with open(other, "w") as fh:
            row = [repr(v) for v in values[0]]
            row[2] = cell
            fh.write(lines[0] + "\n" + ",".join(row) + "\n")
        r = run(vtdyn, "inverse", urdf, other)
        check(r.returncode == 1 and "spelled.csv:2: column '%s'" % lines[0].split(",")[2] in r.stderr
              and "is not a finite number" in r.stderr, "the cell %r refused, named: %r" % (cell, r.stderr))


def options(vtdyn, urdf, states, work, check):
    """--columns, --precision, --normalize-quaternions, -j, --times, and info's lines"""
    full = run(vtdyn, "inverse", urdf, states)
    fn, frows = csv_table(full.stdout)
    for groups, want in (("effort", ["t", "joint1_effort", "joint2_effort"]),
                         ("link,world", ["t"] + sum(([j + s for s in ("_fx", "_fy", "_fz", "_nx", "_ny", "_nz")]
                                                     + [j + s + "_link" for s in ("_fx", "_fy", "_fz", "_nx", "_ny", "_nz")]
                                                     for j in ("joint1", "joint2")), []))):
        r = run(vtdyn, "inverse", "--columns", groups, urdf, states)
        n, rows = csv_table(r.stdout) if r.returncode == 0 else ([], [])
        check(n == want and all(row == [fr[fn.index(c)] for c in n] for row, fr in zip(rows, frows)) and len(rows) == len(frows),
              "--columns %s: the columns %s, the same cells: %s" % (groups, want[:4], r.stderr))
    for groups, what in (("effort,force", "'force' is none of effort, world, link"), ("effort,effort", "twice"),
                         ("", "none of")):
        r = run(vtdyn, "inverse", "--columns", groups, urdf, states)
        check(r.returncode == 1 and what in r.stderr, "--columns %r refused: %r" % (groups, r.stderr))
    r = run(vtdyn, "inverse", "--precision", "6", urdf, states)
    n, rows = csv_table(r.stdout) if r.returncode == 0 else ([], [])
    check(r.returncode == 0 and all(c == "%.6g" % float(fc) for row, fr in zip(rows, frows) for c, fc in zip(row, fr))
          and len(rows) == len(frows), "--precision 6: every number in 6 significant digits: %s" % r.stderr)
    for p in ("0", "18", "x"):
        r = run(vtdyn, "inverse", "--precision", p, urdf, states)
        check(r.returncode == 1 and "--precision" in r.stderr and "1 to 17" in r.stderr, "--precision %s refused" % p)
    for j in ("-1", "x", "2000"):
        r = run(vtdyn, "inverse", "-j", j, urdf, states)
        check(r.returncode == 1 and "-j" in r.stderr and "threads" in r.stderr, "-j %s refused: %r" % (j, r.stderr))
    r = run(vtdyn, "inverse", "-j2", "--times", urdf, states)
    check(r.returncode == 0 and r.stdout == full.stdout and "rows in" in r.stderr and "solve" in r.stderr,
          "-j2 and --times: %r" % r.stderr)
    r = run(vtdyn, "inverse", "-j", "2", "-j", "1", urdf, states)
    check(r.returncode == 1 and "given twice" in r.stderr, "an option twice refused")
    # --normalize-quaternions: a quaternion of norm 1 + 1e-4 refused by default (the option named),
    # taken with TOL 1e-3 as the unit one
    urdf_f = os.path.join(work, "floater1.urdf")
    floater_urdf(urdf_f, 1)
    unit = [0.1, 0.2, 0.3, 0.5, 0.5, -0.5, 0.5, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 1.0, 2.0, 3.0, 0.3, 0.2, 0.1]
    off = unit[:3] + [x * (1 + 1e-4) for x in unit[3:7]] + unit[7:]
    cols = ["float_" + s for s in FREE_COLS]
    for name, row in (("unit.csv", unit), ("off.csv", off)):
        write_csv(os.path.join(work, name), cols, [row])
    r = run(vtdyn, "inverse", urdf_f, os.path.join(work, "off.csv"))
    check(r.returncode == 1 and "off.csv:2" in r.stderr and "--normalize-quaternions" in r.stderr,
          "a quaternion off by 1e-4 refused, the option named: %r" % r.stderr)
    a = run(vtdyn, "inverse", "--normalize-quaternions", "1e-3", urdf_f, os.path.join(work, "off.csv"))
    b = run(vtdyn, "inverse", urdf_f, os.path.join(work, "unit.csv"))
    ok = a.returncode == 0 and b.returncode == 0
    if ok:
        (an, ar), (bn, br) = csv_table(a.stdout), csv_table(b.stdout)
        ok = an == bn and all(abs(float(x) - float(y)) <= 1e-14 * (1 + abs(float(y))) for x, y in zip(ar[0], br[0]))
    check(ok, "--normalize-quaternions 1e-3 takes it as the unit quaternion: %s" % a.stderr)
    for tol in ("1", "-1e-3", "x"):
        r = run(vtdyn, "inverse", "--normalize-quaternions", tol, urdf_f, os.path.join(work, "unit.csv"))
        check(r.returncode == 1 and "--normalize-quaternions" in r.stderr, "--normalize-quaternions %s refused" % tol)
    r = run(vtdyn, "inverse", "--columns", "world", urdf_f, os.path.join(work, "unit.csv"))
    check(r.returncode == 1 and "--columns" in r.stderr, "--columns with no column for the robot: %r" % r.stderr)
    with open(os.path.join(work, "unit.csv")) as f:
        unit = f.read().splitlines()
    with open(os.path.join(work, "unit_t.csv"), "w") as f:  # with t: t alone is no output either
        f.write("t," + unit[0] + "\n" + "".join("%d,%s\n" % (k, row) for k, row in enumerate(unit[1:]) if row))
    r = run(vtdyn, "inverse", "--columns", "world", urdf_f, os.path.join(work, "unit_t.csv"))
    check(r.returncode == 1 and "--columns" in r.stderr and not r.stdout,
          "--columns with no column for the robot, t given: %r" % r.stderr)
    # info: the states columns on one line (a header to paste) and the frames' names
    r = run(vtdyn, "info", urdf)
    lines = r.stdout.splitlines()
    k = next((i for i, ln in enumerate(lines) if ln.startswith("states columns")), -1)
    check(k >= 0 and lines[k + 1] == "joint1,joint1_vel,joint1_acc,joint2,joint2_vel,joint2_acc"
          and lines[k + 3] == "world,link1,link2" and lines[k + 4].startswith("a wrench at frame F (inverse --loads F)"),
          "info: the states header, the frames and the loads' columns: %r" % lines[-5:])
    if k >= 0:
        pasted = os.path.join(work, "pasted.csv")
        with open(pasted, "w") as f:
            f.write(lines[k + 1] + "\n" + ",".join(["0.5"] * 6) + "\n")
        r = run(vtdyn, "inverse", urdf, pasted)
        check(r.returncode == 0, "info's header line, pasted, is read: %s" % r.stderr)
    r = run(vtdyn, "info", "--floating", os.path.join(work, "floater0.urdf"))
    check(r.returncode == 0 and ",".join("body_" + s for s in FREE_COLS) in r.stdout, "info --floating: the root's columns")
    r = run(vtdyn, "info", "-j", "2", urdf)
    check(r.returncode == 1 and "--floating and --inertia-tol alone" in r.stderr, "info refuses inverse's options")


def payloads(vtdyn, urdf, states, work, check):
    """--payload against the same payloads written into the file as links fixed to theirs (the
    loader's merge): every output cell to 1e-15 of the table's largest; repeated; bad ones refused"""
    text = open(urdf).read()
    cut = text.rindex("</robot>")
    edited = os.path.join(work, "payload.urdf")
    with open(edited, "w") as f:
        f.write(text[:cut])
        f.write('  <link name="payload"><inertial><origin xyz="0.3 -0.1 0.2"/><mass value="5"/>'
                '<inertia ixx="0.1" iyy="0.2" izz="0.15" ixy="0.01" ixz="-0.02" iyz="0.03"/></inertial></link>\n'
                '  <joint name="grip" type="fixed"><parent link="link2"/><child link="payload"/></joint>\n'
                '  <link name="pebble"><inertial><origin xyz="-0.4 0.05 0"/><mass value="0.5"/>'
                '<inertia ixx="0" iyy="0" izz="0" ixy="0" ixz="0" iyz="0"/></inertial></link>\n'
                '  <joint name="pebble_joint" type="fixed"><parent link="link1"/><child link="pebble"/></joint>\n')
        f.write(text[cut:])
    want = run(vtdyn, "inverse", edited, states)
    got = run(vtdyn, "inverse", "--payload", "link2,5,0.3,-0.1,0.2,0.1,0.2,0.15,0.01,-0.02,0.03",
              "--payload=link1,0.5,-0.4,0.05,0", urdf, states)
    ok = want.returncode == 0 and got.returncode == 0
    worst = 1.0
    if ok:
        (wn, wr), (gn, gr) = csv_table(want.stdout), csv_table(got.stdout)
        big = max(abs(float(x)) for row in wr for x in row)
        worst = max(abs(float(x) - float(y)) for a, b in zip(gr, wr) for x, y in zip(a, b)) / big
        ok = wn == gn and len(wr) == len(gr) and worst <= 1e-15
    check(ok, "--payload equals the payloads written into the file: relative %.3g (%s%s)"
          % (worst, want.stderr, got.stderr))
    print("--payload against the edited file: largest relative difference %.3g" % worst)
    plain = run(vtdyn, "inverse", urdf, states)
    check(plain.returncode == 0 and plain.stdout != got.stdout, "a payload changes the efforts")
    for spec, what in (("link9,1,0,0,0", "'link9' is not a link"), ("link2,1,0,0", "3 numbers after the link"),
                       ("link2,1,0,0,0,1,1", "4 (mass, x, y, z) or 10"), ("link2,-1,0,0,0", "negative"),
                       ("link2,1,0,0,x", "finite numbers"), ("link2,1,0,0,0,1,1,5,0,0,0", "inertia_tol"),
                       ("nolink", "LINK,mass")):
        r = run(vtdyn, "inverse", "--payload", spec, urdf, states)
        check(r.returncode == 1 and what in r.stderr and spec in r.stderr,
              "--payload %s refused: %r" % (spec, r.stderr))


def joint_effects(vtdyn, urdf, states, work, check):
    """--joint-params, and the URDF's <dynamics> read by default: each effort is the ideal joints'
    (--ideal-joints) plus armature a + damping v + friction sign(v), to 1e-12 of the largest; the
    parts columns those three; a <dynamics> tag equals the same values in --joint-params; bad
    files refused"""
    def effort_table(*args):
        r = run(vtdyn, "inverse", "--columns", "effort,parts", *args, urdf, states)
        check(r.returncode == 0, "inverse %s: %s" % (" ".join(args), r.stderr))
        return csv_table(r.stdout) if r.returncode == 0 else ([], [])
    params = os.path.join(work, "joint_params.csv")
    p = {"joint1": (0.4, 2.5, 3.0), "joint2": (0.15, 0.7, 1.25)}
    with open(params, "w") as f:
        f.write("damping, joint ,friction,armature\n")  # any order, spaces around the names
        for j, (a, b, c) in p.items():
            f.write("%r,%s,%r,%r\n" % (b, j, c, a))
    ideal_n, ideal = effort_table("--ideal-joints")
    names, got = effort_table("--joint-params", params)
    inp = list(csv.DictReader(open(states)))
    ok = len(got) == len(ideal) == len(inp) > 0
    worst = 1.0
    if ok:
        big = max(abs(float(x)) for row in ideal for x in row)
        worst = 0.0
        for row, base, st in zip(got, ideal, inp):
            cell, ref = dict(zip(names, map(float, row))), dict(zip(ideal_n, map(float, base)))
            for j, (a, b, c) in p.items():
                v, acc = float(st[j + "_vel"]), float(st[j + "_acc"])
                parts = (a * acc, b * v, c * (1.0 if v > 0 else -1.0 if v < 0 else 0.0))
                worst = max(worst, abs(cell[j + "_effort"] - ref[j + "_effort"] - sum(parts)) / big,
                            abs(cell[j + "_effort_rigid"] - ref[j + "_effort"]) / big,
                            abs(cell[j + "_effort_armature"] - parts[0]) / big,
                            abs(cell[j + "_effort_damping"] - parts[1]) / big,
                            abs(cell[j + "_effort_friction"] - parts[2]) / big)
                worst = max(worst, abs(ref[j + "_effort_armature"]) + abs(ref[j + "_effort_friction"]))
    check(ok and worst <= 1e-12, "--joint-params: the ideal efforts plus the three parts: %.3g" % worst)
    print("--joint-params against the ideal joints plus armature, damping, friction: %.3g" % worst)
    # <dynamics damping friction> in the file: read by default, as --joint-params without armature
    text = open(urdf).read()
    dyn = os.path.join(work, "double_link_dynamics.urdf")
    with open(dyn, "w") as f:
        f.write(text.replace('<joint name="joint1" type="continuous">',
                             '<joint name="joint1" type="continuous"><dynamics damping="2.5" friction="3.0"/>'))
    only = os.path.join(work, "joint1_params.csv")
    with open(only, "w") as f:
        f.write("joint,armature,damping,friction\njoint1,0,2.5,3.0\n")
    r1 = run(vtdyn, "inverse", dyn, states)
    r2 = run(vtdyn, "inverse", "--joint-params", only, urdf, states)
    r3 = run(vtdyn, "inverse", "--ideal-joints", dyn, states)
    r4 = run(vtdyn, "inverse", urdf, states)
    quoted = os.path.join(work, "joint1_params_quoted.csv")
    with open(quoted, "w") as f:
        f.write('"joint","armature","damping","friction"\n"joint1",0,"2.5",3.0\n')
    r5 = run(vtdyn, "inverse", "--joint-params", quoted, urdf, states)
    check(r1.returncode == 0 and r1.stdout == r2.stdout and r1.stdout != r4.stdout and r5.stdout == r2.stdout,
          "<dynamics> read as --joint-params gives them (the file's cells quoted or not: %r)" % r5.stderr)
    check(r3.returncode == 0 and r3.stdout == r4.stdout, "--ideal-joints ignores <dynamics>")
    for body, what in (("joint,armature,damping\njoint1,0,1\n", "header"),
                       ("joint,armature,damping,friction\njoint9,0,1,1\n", "'joint9' is not a moving joint"),
                       ("joint,armature,damping,friction\njoint1,0,-1,1\n", "not a finite number >= 0"),
                       ("joint,armature,damping,friction\njoint1,0,1,1\njoint1,0,1,1\n", "twice"),
                       ("joint,armature,damping,friction\njoint1,0,1\n", "cells, not 4"),
                       ('joint,armature,damping,friction\n"joint1,0,1,1\n', "line 2: a double quote left open")):
        bad = os.path.join(work, "bad_params.csv")
        with open(bad, "w") as f:
            f.write(body)
        r = run(vtdyn, "inverse", "--joint-params", bad, urdf, states)
        check(r.returncode == 1 and what in r.stderr and not r.stdout, "--joint-params %r refused: %r" % (body, r.stderr))


def inertia_tolerance(vtdyn, urdf, states, work, check):
    """an inertia 0.18 % off the triangle inequality (izz > ixx + iyy): refused by default, the
    message naming --inertia-tol; accepted with --inertia-tol 2e-3 (inverse and info), and then
    the same efforts as the file with izz = iyy + ixx exactly, to 1e-2 of the difference made"""
    text = open(urdf).read()
    off = os.path.join(work, "double_link_off.urdf")
    with open(off, "w") as f:
        f.write(text.replace('iyz="0" izz="33.333333333333336"', 'iyz="0" izz="33.39333333333333"', 1))
    r = run(vtdyn, "inverse", off, states)
    check(r.returncode == 1 and "--inertia-tol" in r.stderr and "triangle" in r.stderr.lower() + "triangle",
          "an inertia off the triangle inequality refused, naming --inertia-tol: %r" % r.stderr)
    r = run(vtdyn, "inverse", "--inertia-tol", "2e-3", off, states)
    check(r.returncode == 0, "--inertia-tol 2e-3 accepts it: %r" % r.stderr)
    r = run(vtdyn, "info", "--inertia-tol=2e-3", off)
    check(r.returncode == 0, "info --inertia-tol accepts it: %r" % r.stderr)
    r = run(vtdyn, "inverse", "--inertia-tol", "1.5", off, states)
    check(r.returncode == 1 and "0 <= TOL < 1" in r.stderr, "--inertia-tol 1.5 refused: %r" % r.stderr)


def loads(vtdyn, urdf_dir, states, work, check):
    """--loads link2,link1 on the double link (planar: hinges about z, gravity along z): random
    wrenches at link 2's frame (joint 2's point, L along link 1) and link 1's (joint 1's point)
    against the arm's closed forms: each effort less the z moment of the loads beyond its joint
    (joint 1: both z moments and link 2's force's moment about the origin, L (c1 f_y - s1 f_x);
    joint 2: link 2's z moment), the ground's force on link 1 less the loads' forces; the same from
    .npy; a missing column, a frame of none, a frame fixed to the world and samples refused, named
    (with --contacts: contacts())"""
    urdf = os.path.join(urdf_dir, "double_link.urdf")
    lines = open(states).read().splitlines()
    rng = random.Random(5)
    names = [f + s for f in ("link2", "link1") for s in ("_fx", "_fy", "_fz", "_nx", "_ny", "_nz")]
    path, out = os.path.join(work, "loads.csv"), os.path.join(work, "loads_out.csv")
    W = []
    with open(path, "w") as f:
        f.write(lines[0] + "," + ",".join(names) + "\n")
        for line in lines[1:]:
            W.append([rng.uniform(-50, 50) for _ in names])
            f.write(line + "," + ",".join(repr(x) for x in W[-1]) + "\n")
    r = run(vtdyn, "inverse", "--loads", "link2,link1", urdf, path, "-o", out)
    check(r.returncode == 0, "--loads: exit %d: %s" % (r.returncode, r.stderr))
    if r.returncode != 0:
        return
    rows, worst = read(out), 0.0
    for row, w in zip(rows, W):
        q1, q2, v1, v2, a1, a2 = motion(row["t"])
        t1, t2, f = exact(q1, q2, v1, v2, a1, a2)
        c1, s1 = math.cos(q1), math.sin(q1)
        t1 -= L * (c1 * w[1] - s1 * w[0]) + w[5] + w[11]
        t2 -= w[5]
        scale = 1 + abs(t1) + abs(t2) + max(abs(x) for x in w)
        worst = max(worst, abs(row["joint1_effort"] - t1) / scale, abs(row["joint2_effort"] - t2) / scale)
        for k, c in enumerate("xyz"):
            worst = max(worst, abs(row["joint1_f" + c] - (f[k] - w[k] - w[6 + k])) / scale)
    check(len(rows) == len(W) and worst < 1e-12, "--loads against the closed forms: %.3g" % worst)
    print("--loads: %d rows, largest relative difference from the closed forms %.3g" % (len(rows), worst))
    rows_csv = rows
    npy_in, npy_out = os.path.join(work, "loads.npy"), os.path.join(work, "loads_out.npy")
    head, cells = csv_table(open(path).read())
    npy_write(npy_in, head, [[float(x) for x in row] for row in cells])
    r = run(vtdyn, "inverse", "--loads", "link2,link1", urdf, npy_in, "-o", npy_out)
    ok = r.returncode == 0
    if ok:
        n, vals, _, _ = npy_read(npy_out)
        ok = all(v == rc[k] for row, rc in zip(vals, rows_csv) for k, v in zip(n, row))
    check(ok, "--loads from .npy: the CSV's numbers: %s" % r.stderr)
    for args, what in ((["--loads", "link2,link3"], "'link3' is no frame"),
                       (["--loads", "world"], "fixed to the world"),
                       (["--loads", "link2,,link1"], "one empty"),
                       (["--loads", "link1", "--loads", "link2"], "given twice")):
        r = run(vtdyn, "inverse", *args, urdf, path)
        check(r.returncode == 1 and what in r.stderr, "--loads refused (%s): %r" % (what, r.stderr))
    with open(path, "w") as f:
        f.write(lines[0] + "," + ",".join(names[:11]) + "\n")
        for line, w in zip(lines[1:], W):
            f.write(line + "," + ",".join(repr(x) for x in w[:11]) + "\n")
    r = run(vtdyn, "inverse", "--loads", "link2,link1", urdf, path)
    check(r.returncode == 1 and "no column 'link1_nz'" in r.stderr, "--loads: a missing column named: %r" % r.stderr)
    r = run(vtdyn, "inverse", urdf, path)
    check(r.returncode == 1 and "'link2_fx' is none of the robot's" in r.stderr,
          "load columns without --loads stop the run: %r" % r.stderr)
    # samples (t and positions) with each sample's own wrenches, not splined: the efforts less
    # those of the same samples without loads are the loads' closed forms at the sample's q,
    # exactly (the splines' rates and accelerations are the same in both runs)
    samples, bare = os.path.join(work, "loads_samples.csv"), os.path.join(work, "loads_bare.csv")
    ts = [0.1 * k for k in range(len(W))]
    with open(samples, "w") as f, open(bare, "w") as g:
        f.write("t,joint1,joint2," + ",".join(names) + "\n")
        g.write("t,joint1,joint2\n")
        for t, w in zip(ts, W):
            q1, q2 = motion(t)[:2]
            f.write("%r,%r,%r,%s\n" % (t, q1, q2, ",".join(repr(x) for x in w)))
            g.write("%r,%r,%r\n" % (t, q1, q2))
    oa, ob = os.path.join(work, "loads_samples_out.csv"), os.path.join(work, "loads_bare_out.csv")
    a = run(vtdyn, "inverse", "--loads", "link2,link1", "-j", "2", urdf, samples, "-o", oa)
    b = run(vtdyn, "inverse", urdf, bare, "-o", ob)
    check(a.returncode == 0 and b.returncode == 0, "--loads on samples: %r %r" % (a.stderr, b.stderr))
    if a.returncode == 0 and b.returncode == 0:
        ra, rb, worst = read(oa), read(ob), 0.0
        for t, w, x, y in zip(ts, W, ra, rb):
            q1 = motion(t)[0]
            c1, s1 = math.cos(q1), math.sin(q1)
            d1, d2 = -(L * (c1 * w[1] - s1 * w[0]) + w[5] + w[11]), -w[5]
            scale = 1 + abs(x["joint1_effort"]) + max(abs(v) for v in w)
            worst = max(worst, abs(x["joint1_effort"] - y["joint1_effort"] - d1) / scale,
                        abs(x["joint2_effort"] - y["joint2_effort"] - d2) / scale)
        check(len(ra) == len(ts) and worst < 1e-12, "--loads on samples against the closed forms: %.3g" % worst)
        print("--loads on samples: %d rows, the loads' part against the closed forms %.3g" % (len(ra), worst))


def cubic_samples(vtdyn, urdf_dir, work, check):
    """samples of cubics in t: the not-a-knot spline through them is the cubic itself, so the
    samples form gives the rows of the states form with the exact rates, to round-off; on the
    fixed double link with a bilateral contact at link 2's frame (--contacts) and a wrench at
    link 1's (--loads), each sample's own, on two threads; every output column"""
    urdf = os.path.join(urdf_dir, "double_link.urdf")
    c1, c2 = (0.3, -0.8, 0.5, 0.2), (1.1, 0.4, -0.6, -0.1)

    def cubic(c, t):
        return (c[0] + c[1] * t + c[2] * t * t + c[3] * t ** 3, c[1] + 2 * c[2] * t + 3 * c[3] * t * t,
                2 * c[2] + 6 * c[3] * t)
    cfile = os.path.join(work, "tip_contact.csv")
    with open(cfile, "w") as f:
        f.write("frame,mu\nlink2,\n")
    rng = random.Random(11)
    wnames = ["link1" + s for s in ("_fx", "_fy", "_fz", "_nx", "_ny", "_nz")]
    ts = [0.07 * k for k in range(30)]
    W = [[rng.uniform(-20, 20) for _ in wnames] for _ in ts]
    sp, st = os.path.join(work, "cubic_samples.csv"), os.path.join(work, "cubic_states.csv")
    with open(sp, "w") as f, open(st, "w") as g:
        f.write("t,joint1,joint2," + ",".join(wnames) + "\n")
        g.write("t,joint1,joint1_vel,joint1_acc,joint2,joint2_vel,joint2_acc," + ",".join(wnames) + "\n")
        for t, w in zip(ts, W):
            a, b = cubic(c1, t), cubic(c2, t)
            lw = ",".join(repr(x) for x in w)
            f.write("%r,%r,%r,%s\n" % (t, a[0], b[0], lw))
            g.write("%r,%s,%s,%s\n" % (t, ",".join(repr(x) for x in a), ",".join(repr(x) for x in b), lw))
    outs = []
    for path in (sp, st):
        o = path.replace(".csv", "_out.csv")
        r = run(vtdyn, "inverse", "--contacts", cfile, "--loads", "link1", "-j", "2", urdf, path, "-o", o)
        check(r.returncode == 0, "cubic samples and states with --contacts and --loads: %s" % r.stderr)
        outs.append(read(o) if r.returncode == 0 else [])
    a, b = outs
    ok = len(a) == len(b) == len(ts) and a and list(a[0]) == list(b[0])
    worst = 0.0
    if ok:
        big = max(abs(v) for row in b for v in row.values())
        worst = max(abs(x[k] - y[k]) for x, y in zip(a, b) for k in x) / big
    check(ok and worst < 1e-11, "cubic samples against the states with exact rates: %.3g" % worst)
    print("cubic samples with a contact and a load: %d rows against the states, largest difference %.3g of the "
          "largest value" % (len(a), worst))


def help_is_documented(vtdyn, urdf_dir, check):
    """docs/command.md holds `vtdyn --help`'s text exactly"""
    doc = os.path.join(urdf_dir, "..", "..", "docs", "command.md")
    text = open(doc, encoding="utf-8").read()
    k = text.find("The full text of `vtdyn --help`")
    start = text.find("```text\n", k) + len("```text\n")
    block = text[start:text.find("```", start)]
    r = run(vtdyn, "--help")
    check(k >= 0 and r.stdout == block, "docs/command.md holds vtdyn --help's text exactly")


def bearing_and_limits(vtdyn, urdf, states, times, work, check):
    """--columns bearing against the closed forms (joint 1's axial force is the weight 2 m g, its
    radial force the planar momentum rate |f_xy|; a hinge's axial reaction moment is zero, its
    tilting moment the magnitude of the link-axes moment); --columns limits on a copy of the
    URDF with <limit> on joint 1: each excess is the input (or the effort column) less the limit
    it passes, 0 within or exactly at it (states: the rows of motion at the times)"""
    r = run(vtdyn, "inverse", "--columns", "link,bearing", urdf, states)
    names, rows = csv_table(r.stdout) if r.returncode == 0 else ([], [])
    want = ["t"] + sum(([j + s + "_link" for s in ("_fx", "_fy", "_fz", "_nx", "_ny", "_nz")] +
                        [j + s for s in ("_axial_force", "_radial_force", "_axial_moment", "_tilt_moment")]
                        for j in ("joint1", "joint2")), [])
    check(r.returncode == 0 and names == want, "--columns link,bearing: the columns: %s %s" % (names[:6], r.stderr))
    worst = 0.0
    for cells, t in zip(rows, times):
        row = {n: float(c) for n, c in zip(names, cells)}
        _, _, f = exact(*motion(t))
        fs = 1 + max(abs(x) for x in f)
        worst = max(worst, abs(row["joint1_axial_force"] - f[2]) / fs,
                    abs(row["joint1_radial_force"] - math.hypot(f[0], f[1])) / fs)
        for j in ("joint1", "joint2"):
            ms = 1 + abs(row[j + "_nx_link"]) + abs(row[j + "_ny_link"]) + abs(row[j + "_nz_link"])
            worst = max(worst, abs(row[j + "_axial_moment"]) / ms,
                        abs(row[j + "_tilt_moment"] - math.hypot(row[j + "_nx_link"], row[j + "_ny_link"])) / ms,
                        abs(row[j + "_axial_force"] - row[j + "_fz_link"]) / fs)
    check(len(rows) == len(times) and worst < 1e-9, "bearing: largest relative difference %.3g (1e-9)" % worst)
    # limits on joint 1: the position's upper bound at row 3's q1 exactly (not passed there), the
    # velocity's and the effort's at halves of the largest, so that some rows pass them
    q1s = [motion(t)[0] for t in times]
    v1s = [motion(t)[2] for t in times]
    full = run(vtdyn, "inverse", "--columns", "effort", urdf, states)
    fn, frows = csv_table(full.stdout) if full.returncode == 0 else ([], [])
    e1s = [float(fr[fn.index("joint1_effort")]) for fr in frows]
    lower, upper = -0.3, q1s[3]
    vmax, emax = 0.5 * max(abs(v) for v in v1s), 0.5 * max(abs(e) for e in e1s)
    with open(urdf) as f:
        text = f.read()
    k = text.index('<axis xyz="0 0 1"/>') + len('<axis xyz="0 0 1"/>')
    limited = os.path.join(work, "double_link_limits.urdf")
    with open(limited, "w") as f:
        f.write(text[:k] + '<limit lower="%r" upper="%r" velocity="%r" effort="%r"/>' % (lower, upper, vmax, emax)
                + text[k:])
    with open(limited) as f:
        text = f.read()
    with open(limited, "w") as f:  # position limits hold for a revolute joint, not a continuous one
        f.write(text.replace('<joint name="joint1" type="continuous">', '<joint name="joint1" type="revolute">'))
    r = run(vtdyn, "inverse", "--columns", "effort,limits", limited, states)
    names, rows = csv_table(r.stdout) if r.returncode == 0 else ([], [])
    check(r.returncode == 0 and names[:6] == ["t", "joint1_effort", "joint1_position_excess", "joint1_vel_excess",
                                              "joint1_effort_excess", "joint2_effort"],
          "--columns effort,limits: the columns: %s %s" % (names[:6], r.stderr))

    def beyond(x, lo, hi):
        return x - hi if x > hi else x - lo if x < lo else 0.0

    bad, flagged = [], 0
    for cells, q1, v1 in zip(rows, q1s, v1s):
        row = {n: float(c) for n, c in zip(names, cells)}
        e1 = row["joint1_effort"]
        want = (beyond(q1, lower, upper), beyond(v1, -vmax, vmax), beyond(e1, -emax, emax))
        got = (row["joint1_position_excess"], row["joint1_vel_excess"], row["joint1_effort_excess"])
        flagged += sum(1 for w in want if w != 0.0)
        if got != want or row["joint2_position_excess"] or row["joint2_vel_excess"] or row["joint2_effort_excess"]:
            bad.append((got, want))
    check(len(rows) == len(times) and not bad and flagged > 0 and rows and
          float(rows[3][names.index("joint1_position_excess")]) == 0.0,
          "limits: each excess the value less the limit passed (%d flagged), 0 at the limit: %s" % (flagged, bad[:2]))


QUAD_MASS = 17.2  # tests/urdf/quadruped.urdf: a 10 kg torso, four legs of 0.3 + 1 + 0.5 kg
QUAD_FEET = ("FL", "FR", "HL", "HR")


def quad_row(theta, root_acc=(0.0, 0.0, 0.0), rates=0.0, active=None):
    """a state of tests/urdf/quadruped.urdf in its stand (front legs flexed theta, knees -2 theta;
    hind legs mirrored: each foot under its hip, on the ground z = 0), the torso at rest with its
    centre accelerated by root_acc, the joints moving at rates (velocity and acceleration)"""
    row = {}
    for k, leg in enumerate(QUAD_FEET):
        th = theta if k < 2 else -theta
        for j, q in (("HAA", 0.0), ("HFE", th), ("KFE", -2 * th)):
            row["%s_%s" % (leg, j)] = q
            row["%s_%s_vel" % (leg, j)] = rates * math.sin(1.3 * k + len(j))
            row["%s_%s_acc" % (leg, j)] = rates * math.cos(0.7 * k + len(j))
    for c, v in zip(("x", "y", "z", "qw", "qx", "qy", "qz"), (0, 0, 0.4 * math.cos(theta), 1, 0, 0, 0)):
        row["torso_" + c] = float(v)
    for c in ("vx", "vy", "vz", "wx", "wy", "wz", "alx", "aly", "alz"):
        row["torso_" + c] = 0.0
    for c, v in zip(("ax", "ay", "az"), root_acc):
        row["torso_" + c] = v
    for leg, a in zip(QUAD_FEET, active or ()):
        row[leg + "_foot_active"] = float(a)
    return row


def contacts(vtdyn, urdf_dir, work, check):
    """--contacts on the quadruped of tests/urdf: the symmetric stand (M g / 4 a foot), the forces'
    balance against the root's wrench without contacts (the feet's places known in the stand), a
    push on the torso (--loads) taken off the feet's forces' sum, a
    lifted foot (the diagonal pair under the centre carries it all), slipping refused and named,
    bad contact files, C_active neither 0 nor 1"""
    urdf = os.path.join(urdf_dir, "quadruped.urdf")
    cfile = os.path.join(work, "feet.csv")
    with open(cfile, "w") as f:
        f.write("frame,mu\n" + "".join("%s_foot,0.5\n" % leg for leg in QUAD_FEET))
    W = QUAD_MASS * 9.81

    def run_rows(rows, *extra):
        path = os.path.join(work, "quad.csv")
        names = list(rows[0])
        with open(path, "w") as f:
            f.write(",".join(names) + "\n")
            for r in rows:
                f.write(",".join(repr(r[n]) for n in names) + "\n")
        r = run(vtdyn, "inverse", "--floating", *extra, urdf, path)
        out = [{k: float(v) for k, v in row.items()} for row in csv.DictReader(r.stdout.splitlines())] \
            if r.returncode == 0 else []
        return r, out

    theta = 0.6
    rows = [quad_row(theta), quad_row(theta, (0.8, -0.5, 1.2), 0.7)]
    r, out = run_rows(rows, "--contacts", cfile)
    check(r.returncode == 0 and len(out) == 2, "--contacts on the quadruped: %s" % r.stderr)
    r0, free = run_rows(rows)
    check(r0.returncode == 0 and len(free) == 2, "the quadruped without contacts: %s" % r0.stderr)
    if len(out) == 2 and len(free) == 2:
        stand = out[0]
        check(all(abs(stand[leg + "_foot_fz"] - W / 4) <= 1e-9 * W for leg in QUAD_FEET),
              "the symmetric stand: M g / 4 on each foot: %s" % [stand[leg + "_foot_fz"] for leg in QUAD_FEET])
        for k, row in enumerate(out):
            root = max(abs(row["torso_effort_" + c]) for c in ("fx", "fy", "fz", "nx", "ny", "nz"))
            check(root <= 1e-9 * W, "row %d: the floating root carries nothing (%.3g)" % (k, root))
            # the feet's forces are the root's wrench without them: force, and moment about the
            # root's point P = (0, 0, h), the feet at (±0.3, ±0.15, 0)
            h = 0.4 * math.cos(theta)
            force = [sum(row["%s_foot_f%s" % (leg, c)] for leg in QUAD_FEET) for c in "xyz"]
            moment = [0.0, 0.0, 0.0]
            for leg, (px, py) in zip(QUAD_FEET, ((0.3, 0.15), (0.3, -0.15), (-0.3, 0.15), (-0.3, -0.15))):
                f = [row["%s_foot_f%s" % (leg, c)] for c in "xyz"]
                d = (px, py, -h)
                for c, v in enumerate((d[1] * f[2] - d[2] * f[1], d[2] * f[0] - d[0] * f[2], d[0] * f[1] - d[1] * f[0])):
                    moment[c] += v
            want_f = [free[k]["torso_effort_f" + c] for c in "xyz"]
            want_n = [free[k]["torso_effort_n" + c] for c in "xyz"]
            worst = max(max(abs(a - b) for a, b in zip(force, want_f)), max(abs(a - b) for a, b in zip(moment, want_n)))
            check(worst <= 1e-9 * W, "row %d: the feet's forces give the root's wrench (%.3g)" % (k, worst))
            check(all(row["%s_foot_fz" % leg] >= 0 and abs(row["%s_foot_fx" % leg]) <= 0.5 * math.sqrt(0.5) * row["%s_foot_fz" % leg] + 1e-9 * W
                      for leg in QUAD_FEET), "row %d: the feet push, within friction" % k)
    # a push on the torso (--loads torso, world axes): the feet's forces sum to those without it
    # less the push's force (the unactuated root: the ground supplies the whole wrench), the root
    # still carries nothing
    push = (40.0, -25.0, -30.0, 3.0, -2.0, 5.0)
    lrows = [dict(row, **{"torso_" + c: v for c, v in zip(("fx", "fy", "fz", "nx", "ny", "nz"), push)}) for row in rows]
    r, pushed = run_rows(lrows, "--contacts", cfile, "--loads", "torso")
    check(r.returncode == 0 and len(pushed) == 2, "--loads with --contacts: %s" % r.stderr)
    for k in range(len(pushed) if len(out) == 2 else 0):
        for i, c in enumerate("xyz"):
            sums = [sum(o[leg + "_foot_f" + c] for leg in QUAD_FEET) for o in (out[k], pushed[k])]
            check(abs(sums[1] - (sums[0] - push[i])) <= 1e-9 * W,
                  "row %d: the feet's %s forces less the push's: %.17g, %.17g" % (k, c, sums[1], sums[0] - push[i]))
        root = max(abs(pushed[k]["torso_effort_" + c]) for c in ("fx", "fy", "fz", "nx", "ny", "nz"))
        check(root <= 1e-9 * W, "row %d with the push: the floating root carries nothing (%.3g)" % (k, root))
    # the front left foot lifted: FR and HL carry half each, HR nothing
    r, out = run_rows([quad_row(theta, active=(0, 1, 1, 1))], "--contacts", cfile)
    check(r.returncode == 0 and out and out[0]["FL_foot_fz"] == 0.0 and abs(out[0]["FR_foot_fz"] - W / 2) <= 1e-9 * W
          and abs(out[0]["HL_foot_fz"] - W / 2) <= 1e-9 * W and abs(out[0]["HR_foot_fz"]) <= 1e-9 * W,
          "FL lifted: FR and HL carry half the weight each: %s" % r.stderr)
    # 6 m/s² sideways on mu 0.5: slips; the row and the contact named, no output file
    path_out = os.path.join(work, "quad_out.csv")
    rows = [quad_row(theta), quad_row(theta, (6.0, 0.0, 0.0))]
    names = list(rows[0])
    with open(os.path.join(work, "quad.csv"), "w") as f:
        f.write(",".join(names) + "\n" + "".join(",".join(repr(r_[n]) for n in names) + "\n" for r_ in rows))
    r = run(vtdyn, "inverse", "--floating", "--contacts", cfile, urdf, os.path.join(work, "quad.csv"), "-o", path_out)
    check(r.returncode == 1 and "quad.csv:3" in r.stderr and "slip" in r.stderr and "_foot" in r.stderr
          and not os.path.exists(path_out), "a slipping row refused, named: %r" % r.stderr)
    # C_active neither 0 nor 1
    r, out = run_rows([quad_row(theta, active=(1, 2, 1, 1))], "--contacts", cfile)
    check(r.returncode == 1 and "FR_foot_active" in r.stderr and "neither 0 nor 1" in r.stderr,
          "C_active 2 refused, named: %r" % r.stderr)
    # C_active without --contacts: an unknown column
    r, out = run_rows([quad_row(theta, active=(1, 1, 1, 1))])
    check(r.returncode == 1 and "FL_foot_active" in r.stderr and "--contacts" in r.stderr,
          "C_active without --contacts refused: %r" % r.stderr)
    # bilateral feet (mu empty) hold a pull: the torso accelerated down at 1.5 g
    with open(cfile, "w") as f:
        f.write("mu,frame\n" + "".join(",%s_foot\n" % leg for leg in QUAD_FEET))
    r, out = run_rows([quad_row(theta, (0, 0, -1.5 * 9.81))], "--contacts", cfile)
    check(r.returncode == 0 and out and all(out[0][leg + "_foot_fz"] < 0 for leg in QUAD_FEET),
          "bilateral feet pull: %s" % r.stderr)
    # the optional columns: the defaults written out give the same bytes
    with open(cfile, "w") as f:
        f.write("frame,mu\n" + "".join("%s_foot,0.5\n" % leg for leg in QUAD_FEET))
    rows = [quad_row(theta), quad_row(theta, (0.8, -0.5, 1.2), 0.7)]
    r_plain, _ = run_rows(rows, "--contacts", cfile)
    with open(cfile, "w") as f:
        f.write("weight,frame,nz,mu,nx,faces,ny\n" + "".join("1e-4,%s_foot,1,0.5,0,4,0\n" % leg for leg in QUAD_FEET))
    r_full, _ = run_rows(rows, "--contacts", cfile)
    with open(cfile, "w") as f:
        f.write("frame,mu,faces,nx,ny,nz,weight\n" + "".join("%s_foot,0.5,,,,,\n" % leg for leg in QUAD_FEET))
    r_empty, _ = run_rows(rows, "--contacts", cfile)
    with open(cfile, "w") as f:  # quoted, as spreadsheets write them
        f.write('"frame", "mu"\n' + "".join('"%s_foot","0.5"\n' % leg for leg in QUAD_FEET))
    r_quoted, _ = run_rows(rows, "--contacts", cfile)
    check(r_plain.returncode == 0 and r_full.stdout == r_plain.stdout and r_empty.stdout == r_plain.stdout
          and r_quoted.stdout == r_plain.stdout,
          "faces, normal and weight at their defaults, written or empty, and the cells quoted: the same bytes "
          "(%r %r %r)" % (r_full.stderr, r_empty.stderr, r_quoted.stderr))
    # faces: 4 m/s² sideways on mu 0.5 needs |f_t| / f_n = 0.41 on the whole robot: beyond a 4-face
    # pyramid's mu cos(pi/4) = 0.35 along a face's direction (y), within an 8-face one's
    # mu cos(pi/8) = 0.46
    for faces, ok in ((4, False), (8, True)):
        with open(cfile, "w") as f:
            f.write("frame,mu,faces\n" + "".join("%s_foot,0.5,%d\n" % (leg, faces) for leg in QUAD_FEET))
        r, out = run_rows([quad_row(theta, (0.0, 4.0, 0.0))], "--contacts", cfile)
        check((r.returncode == 0) == ok and (ok or "slip" in r.stderr),
              "%d faces, 4 m/s^2 sideways on mu 0.5: %s (%r)" % (faces, "carried" if ok else "slips", r.stderr))
        if ok and out:
            fy = sum(out[0][leg + "_foot_fy"] for leg in QUAD_FEET)
            check(abs(fy - QUAD_MASS * 4.0) <= 1e-9 * W, "the feet's sideways forces accelerate the robot: %.12g" % fy)
    # the normal: the ground tilted by beta about y; at rest the forces hold the weight up, which
    # needs friction tan(beta) of the normal force: 0.2 within mu 0.5 cos(pi/4), 0.6 beyond mu
    for tan_b, ok in ((0.2, True), (0.6, False)):
        b = math.atan(tan_b)
        with open(cfile, "w") as f:
            f.write("frame,mu,nx,ny,nz\n" + "".join("%s_foot,0.5,%.17g,0,%.17g\n" % (leg, math.sin(b), math.cos(b))
                                                   for leg in QUAD_FEET))
        r, out = run_rows([quad_row(theta)], "--contacts", cfile)
        check((r.returncode == 0) == ok and (ok or "slip" in r.stderr),
              "the ground tilted, tan %.1f on mu 0.5: %s (%r)" % (tan_b, "stands" if ok else "slips", r.stderr))
        if ok and out:
            fz = sum(out[0][leg + "_foot_fz"] for leg in QUAD_FEET)
            fx = sum(out[0][leg + "_foot_fx"] for leg in QUAD_FEET)
            check(abs(fz - W) <= 1e-9 * W and abs(fx) <= 1e-9 * W, "on the tilted ground the weight held up")
            n = (math.sin(b), 0.0, math.cos(b))
            for leg in QUAD_FEET:
                f = [out[0]["%s_foot_f%s" % (leg, c)] for c in "xyz"]
                fn = sum(a * c for a, c in zip(f, n))
                ft = math.sqrt(sum((a - fn * c) ** 2 for a, c in zip(f, n)))
                check(fn > 0 and ft <= 0.5 * fn + 1e-9 * W, "%s pushes along the tilted normal within mu" % leg)
    # weight: FL's force costs 100 times the others': it carries less than FR
    with open(cfile, "w") as f:
        f.write("frame,mu,weight\n" + "".join("%s_foot,0.5,%s\n" % (leg, "1e-2" if leg == "FL" else "")
                                              for leg in QUAD_FEET))
    r, out = run_rows([quad_row(theta)], "--contacts", cfile)
    check(r.returncode == 0 and out and out[0]["FL_foot_fz"] < out[0]["FR_foot_fz"] - 1e-6 * W,
          "a heavier weight on FL: it carries less (%r)" % r.stderr)
    # samples of the floating robot (t and positions): each row solved as a state; the torso
    # rises as z = h + c t^2 / 2, which the not-a-knot spline through its samples reproduces, so
    # the feet carry M (g + c) / 4 each, and with FL inactive FR and HL half of it each
    with open(cfile, "w") as f:
        f.write("frame,mu\n" + "".join("%s_foot,0.5\n" % leg for leg in QUAD_FEET))
    acc = 0.8
    names = ["t"] + [k for k in quad_row(theta) if not k.endswith(("_vel", "_acc")) and
                     not any(k == "torso_" + c for c in ("vx", "vy", "vz", "wx", "wy", "wz", "ax", "ay", "az",
                                                          "alx", "aly", "alz"))] + ["FL_foot_active"]
    spath = os.path.join(work, "quad_samples.csv")
    with open(spath, "w") as f:
        f.write(",".join(names) + "\n")
        for i in range(6):
            t = 0.1 * i
            row = quad_row(theta)
            row["t"] = t
            row["torso_z"] += 0.5 * acc * t * t
            row["FL_foot_active"] = 0.0 if i == 3 else 1.0
            f.write(",".join(repr(float(row[n])) for n in names) + "\n")
    r = run(vtdyn, "inverse", "--floating", "--contacts", cfile, urdf, spath)
    out = [{k: float(v) for k, v in row.items()} for row in csv.DictReader(r.stdout.splitlines())] \
        if r.returncode == 0 else []
    Wc = QUAD_MASS * (9.81 + acc)
    check(r.returncode == 0 and len(out) == 6, "samples with --contacts: %r" % r.stderr)
    if len(out) == 6:
        for i, row in enumerate(out):
            want = {leg: Wc / 4 for leg in QUAD_FEET} if i != 3 else {"FL": 0.0, "FR": Wc / 2, "HL": Wc / 2, "HR": 0.0}
            worst = max(abs(row[leg + "_foot_fz"] - want[leg]) for leg in QUAD_FEET)
            check(worst <= 1e-8 * Wc, "sample %d: the feet carry M (g + c) as the rule shares it (%.3g)" % (i, worst))
    for text, says in (("frame,friction\nFL_foot,1\n", "'friction' unknown"),
                       ("frame,mu,mu\nFL_foot,1,1\n", "'mu' twice"),
                       ("frame,mu,nx\nFL_foot,1,0\n", "all of nx, ny, nz"),
                       ("frame,mu,faces\nFL_foot,1,2\n", "faces '2'"),
                       ("frame,mu,faces\nFL_foot,1,4.5\n", "faces '4.5'"),
                       ("frame,mu,nx,ny,nz\nFL_foot,1,0,0,0\n", "the normal (nx, ny, nz) is zero"),
                       ("frame,mu,nx,ny,nz\nFL_foot,1,0,up,1\n", "ny 'up'"),
                       ("frame,mu,weight\nFL_foot,1,0\n", "weight '0'"),
                       ("frame,mu,weight\nFL_foot,1\n", "2 cells, not 3"),
                       ("mu\nFL_foot\n", "the header is frame,mu"),
                       ("frame,mu\nnose,1\n", "'nose' is not a link"),
                       ("frame,mu\nFL_foot,-1\n", "not a finite number >= 0"),
                       ("frame,mu\nFL_foot,1\nFL_foot,1\n", "'FL_foot' twice (several points on one link"),
                       ("frame,mu,name\nFL_foot,1,a\nFR_foot,1,a\n", "the name 'a' twice"),
                       ("frame,mu,name\nFL_foot,1,a b\n", "the name 'a b'"),
                       ("frame,mu,name\nFL_foot,1,FL_HAA\n", "two output columns would be named 'FL_HAA_fx'"),
                       ("frame,mu,x,y\nFL_foot,1,0,0\n", "all of x, y, z"),
                       ('"frame,mu\nFL_foot,1\n', "line 1: a double quote left open"),
                       ('"frame"x,mu\nFL_foot,1\n', "line 1: a double quote left open, or text after"),
                       ("frame,mu,x,y,z\nFL_foot,1,0,zero,0\n", "y 'zero'"),
                       ("frame,mu\n", "no contact")):
        with open(cfile, "w") as f:
            f.write(text)
        r, out = run_rows([quad_row(theta)], "--contacts", cfile)
        check(r.returncode == 1 and says in r.stderr, "contacts file %r refused: %r" % (text, r.stderr))
    check(run(vtdyn, "inverse", "--contacts", os.path.join(work, "none.csv"), urdf,
              os.path.join(work, "quad.csv")).returncode == 1, "a missing contacts file refused")


def solve(a, b):
    """a x = b by Gaussian elimination with partial pivoting (a: n lists of n)"""
    n = len(b)
    m = [list(row) + [v] for row, v in zip(a, b)]
    for c in range(n):
        p = max(range(c, n), key=lambda r: abs(m[r][c]))
        m[c], m[p] = m[p], m[c]
        for r in range(c + 1, n):
            f = m[r][c] / m[c][c]
            m[r] = [x - f * y for x, y in zip(m[r], m[c])]
    x = [0.0] * n
    for r in reversed(range(n)):
        x[r] = (m[r][n] - sum(m[r][k] * x[k] for k in range(r + 1, n))) / m[r][r]
    return x


def sole_corners(vtdyn, work, check):
    """--contacts with points on a link's frame (x,y,z) and names: a floating box whose fixed link
    'sole' is 0.1 m under it, 0.03 m back, turned 40 degrees about z, on the sole's four corners
    given in the sole's axes (unevenly), at rest: the forces are the minimum-norm statics of the
    box at the corners o + R_z(40) p written here (1e-9 of the weight; uneven), each contact's
    columns under its name; HL_active 0 lifts that corner (its force exactly 0, the other three
    the statics on three points); without x,y,z every contact sits at the sole's origin, off the
    box's centre of mass: refused"""
    mass, yaw, o = 8.0, math.radians(40.0), (-0.03, 0.0, -0.1)
    urdf = os.path.join(work, "box.urdf")
    with open(urdf, "w") as f:
        f.write('<robot name="box"><link name="box"><inertial><mass value="%r"/><inertia ixx="0.13" ixy="0" '
                'ixz="0" iyy="0.27" iyz="0" izz="0.35"/></inertial></link><link name="sole"/>'
                '<joint name="sole_fixed" type="fixed"><parent link="box"/><child link="sole"/>'
                '<origin xyz="%r %r %r" rpy="0 0 %r"/></joint></robot>\n' % (mass, *o, yaw))
    corners = {"FL": (0.12, 0.07), "FR": (0.12, -0.06), "HL": (-0.09, 0.07), "HR": (-0.09, -0.06)}
    cfile = os.path.join(work, "sole.csv")
    with open(cfile, "w") as f:
        f.write("name,frame,mu,x,y,z\n" + "".join("%s,sole,1,%r,%r,0\n" % (k, x, y) for k, (x, y) in corners.items()))
    names = ["box_" + c for c in ("x", "y", "z", "qw", "qx", "qy", "qz", "vx", "vy", "vz", "wx", "wy", "wz",
                                  "ax", "ay", "az", "alx", "aly", "alz")]
    rest = [0, 0, 0.1, 1, 0, 0, 0] + [0] * 12
    states = os.path.join(work, "box_states.csv")
    with open(states, "w") as f:
        f.write(",".join(names + ["HL_active"]) + "\n" + ",".join(map(repr, rest + [1])) + "\n"
                + ",".join(map(repr, rest + [0])) + "\n")
    r = run(vtdyn, "inverse", "--floating", "--contacts", cfile, urdf, states)
    out = [{k: float(v) for k, v in row.items()} for row in csv.DictReader(r.stdout.splitlines())] \
        if r.returncode == 0 else []
    check(r.returncode == 0 and len(out) == 2, "a box on its sole's corners: %r" % r.stderr)
    W = mass * 9.81
    c, s_ = math.cos(yaw), math.sin(yaw)
    at = {k: (o[0] + c * x - s_ * y, o[1] + s_ * x + c * y, o[2]) for k, (x, y) in corners.items()}
    for row, on in zip(out, (("FL", "FR", "HL", "HR"), ("FL", "FR", "HR"))):
        # E f = (0, 0, W, 0, 0, 0): the forces' sum and their moments about the centre of mass
        E = [[0.0] * (3 * len(on)) for _ in range(6)]
        for k, name in enumerate(on):
            rx, ry, rz = at[name]
            for e in range(3):
                E[e][3 * k + e] = 1.0
            E[3][3 * k + 2], E[3][3 * k + 1] = ry, -rz
            E[4][3 * k + 0], E[4][3 * k + 2] = rz, -rx
            E[5][3 * k + 1], E[5][3 * k + 0] = rx, -ry
        if len(on) == 3:  # three points: the statics alone (six equations, three of them on fz)
            E, rhs = [E[2], E[3], E[4]], [W, 0.0, 0.0]
            Ez = [[E[i][3 * k + 2] for k in range(3)] for i in range(3)]
            fz = solve(Ez, rhs)
            want = {name: (0.0, 0.0, fz[k]) for k, name in enumerate(on)}
        else:
            EEt = [[sum(E[i][k] * E[j][k] for k in range(12)) for j in range(6)] for i in range(6)]
            y = solve(EEt, [0.0, 0.0, W, 0.0, 0.0, 0.0])
            f = [sum(E[i][k] * y[i] for i in range(6)) for k in range(12)]
            want = {name: tuple(f[3 * k:3 * k + 3]) for k, name in enumerate(on)}
        worst = max(abs(row["%s_f%s" % (name, e)] - want[name][i]) for name in on for i, e in enumerate("xyz"))
        check(worst <= 1e-9 * W and min(w[2] for w in want.values()) > 0.1 * W,
              "the sole's corners carry the box's statics on %s (%.3g; fz %s)"
              % (",".join(on), worst, [round(w[2], 3) for w in want.values()]))
        print("sole corners on %s: largest difference from the statics %.3g of the weight" % (",".join(on), worst / W))
        if len(on) == 3:
            check(all(row["HL_f" + e] == 0.0 for e in "xyz"), "HL lifted: its force exactly 0")
    with open(cfile, "w") as f:
        f.write("name,frame,mu\n" + "".join("%s,sole,1\n" % k for k in corners))
    r = run(vtdyn, "inverse", "--floating", "--contacts", cfile, urdf, states)
    check(r.returncode == 1 and "box_states.csv:2" in r.stderr, "four points at the sole's origin cannot carry the "
          "box: refused, the row named: %r" % r.stderr)


def main():
    vtdyn, urdf_dir, work = sys.argv[1], sys.argv[2], sys.argv[3]
    os.makedirs(work, exist_ok=True)
    urdf = os.path.join(urdf_dir, "double_link.urdf")
    failures = []

    def check(ok, what):
        if not ok:
            failures.append(what)
            print("FAIL:", what)

    # states given
    states = os.path.join(work, "states.csv")
    times = [0.1 * k for k in range(12)]
    with open(states, "w") as f:
        f.write("t,joint1,joint1_vel,joint1_acc,joint2,joint2_vel,joint2_acc\n")
        for t in times:
            q1, q2, v1, v2, a1, a2 = motion(t)
            f.write(",".join(repr(x) for x in (t, q1, v1, a1, q2, v2, a2)) + "\n")
    out = os.path.join(work, "out.csv")
    r = run(vtdyn, "inverse", urdf, states, "-o", out)
    check(r.returncode == 0, "inverse on states: exit %d: %s" % (r.returncode, r.stderr))
    if r.returncode == 0:
        rows = read(out)
        check(len(rows) == len(times), "one output row per state")
        worst = 0.0
        for row, t in zip(rows, times):
            q1, q2, v1, v2, a1, a2 = motion(t)
            t1, t2, f = exact(q1, q2, v1, v2, a1, a2)
            scale = 1 + abs(t1) + abs(t2)
            worst = max(worst, abs(row["joint1_effort"] - t1) / scale, abs(row["joint2_effort"] - t2) / scale)
            fs = 1 + max(abs(x) for x in f)
            for k, c in enumerate("xyz"):
                worst = max(worst, abs(row["joint1_f" + c] - f[k]) / fs)
            worst = max(worst, abs(row["joint1_nz"]) / scale)  # the hinge's torque is not reaction
            # in link 1's axes (turned q1 about z): the force's x and y components
            c, s = math.cos(q1), math.sin(q1)
            worst = max(worst, abs(row["joint1_fx_link"] - (c * f[0] + s * f[1])) / fs,
                        abs(row["joint1_fy_link"] - (-s * f[0] + c * f[1])) / fs,
                        abs(row["joint1_fz_link"] - f[2]) / fs)
            check(abs(row["t"] - t) == 0.0, "t copied")
        check(worst < 1e-9, "states: largest relative difference %.3g (tolerance 1e-9)" % worst)
        print("states: %d rows, largest relative difference from the closed forms %.3g" % (len(rows), worst))

    # samples of the same motion: the splines' derivatives
    samples = os.path.join(work, "samples.csv")
    ts = [0.01 * k for k in range(301)]
    with open(samples, "w") as f:
        f.write("t,joint1,joint2\n")
        for t in ts:
            q1, q2, *_ = motion(t)
            f.write("%r,%r,%r\n" % (t, q1, q2))
    out2 = os.path.join(work, "out_samples.csv")
    r = run(vtdyn, "inverse", urdf, samples, "-o", out2)
    check(r.returncode == 0, "inverse on samples: exit %d: %s" % (r.returncode, r.stderr))
    if r.returncode == 0:
        rows = read(out2)
        check(len(rows) == len(ts), "one output row per sample")
        worst, big = 0.0, 0.0
        for row, t in zip(rows, ts):
            t1, t2, _ = exact(*motion(t))
            big = max(big, abs(t1), abs(t2))
        for row, t in zip(rows[5:-5], ts[5:-5]):  # the spline's ends are less accurate
            t1, t2, _ = exact(*motion(t))
            worst = max(worst, abs(row["joint1_effort"] - t1), abs(row["joint2_effort"] - t2))
        check(worst < 1e-4 * big, "samples: largest difference %.3g of %.3g N m (tolerance 1e-4)" % (worst, big))
        print("samples: %d rows, largest torque difference %.3g of %.3g N m" % (len(rows), worst, big))

    # errors: named, exit 1, no output left under the name
    bad = os.path.join(work, "bad.csv")
    with open(bad, "w") as f:
        f.write("joint1,joint1_vel,joint1_acc,joint2,joint2_vel,joint2_acc\n0,0,0,0,0,0\n0,0,0,0.5,abc,0\n")
    out3 = os.path.join(work, "never.csv")
    r = run(vtdyn, "inverse", urdf, bad, "-o", out3)
    check(r.returncode == 1 and "bad.csv:3" in r.stderr and "joint2_vel" in r.stderr and "abc" in r.stderr,
          "a bad number names the file, row and column: %r" % r.stderr)
    check(not os.path.exists(out3) and not os.path.exists(out3 + ".part"), "no output file after a failure")
    with open(bad, "w") as f:
        f.write("joint1,joint1_vel,joint1_acc\n0,0,0\n")
    r = run(vtdyn, "inverse", urdf, bad)
    check(r.returncode == 1 and "'joint2'" in r.stderr, "a missing column is named: %r" % r.stderr)
    with open(bad, "w") as f:
        f.write("joint1,joint2\n0,0\n")
    r = run(vtdyn, "inverse", urdf, bad)
    check(r.returncode == 1 and "'t'" in r.stderr, "samples need t: %r" % r.stderr)
    # samples whose t does not increase (repeated, then going back): the row and the column named
    # in the file's terms (the line, as the other row errors), not the drive's spline samples
    for rows, line in (("0,0,0\n0.1,0.1,0.1\n0.1,0.2,0.2\n0.3,0.3,0.3\n", 4), ("0,0,0\n0.2,0.1,0.1\n0.1,0.2,0.2\n", 4)):
        with open(bad, "w") as f:
            f.write("t,joint1,joint2\n" + rows)
        r = run(vtdyn, "inverse", urdf, bad)
        check(r.returncode == 1 and "bad.csv:%d: column 't'" % line in r.stderr and "increasing" in r.stderr
              and "drive" not in r.stderr and "t[" not in r.stderr,
              "samples with t not increasing name the row and 't': %r" % r.stderr)
    r = run(vtdyn, "inverse", os.path.join(work, "missing.urdf"), states)
    check(r.returncode == 1 and "missing.urdf" in r.stderr, "a missing URDF is named: %r" % r.stderr)
    # a byte-order mark before the header, a subnormal number; an existing .part left alone
    with open(bad, "w", encoding="utf-8-sig") as f:
        f.write("t,joint1,joint1_vel,joint1_acc,joint2,joint2_vel,joint2_acc\n0.5,1e-320,0,0,0,0,0\n")
    r = run(vtdyn, "inverse", urdf, bad)
    check(r.returncode == 0 and r.stdout.startswith("t,joint1_effort"), "a BOM and a subnormal: %r" % r.stderr)
    part = out3 + ".part"
    with open(part, "w") as f:
        f.write("someone else's\n")
    r = run(vtdyn, "inverse", urdf, states, "-o", out3)
    check(r.returncode == 1 and ".part" in r.stderr, "an existing .part refused: %r" % r.stderr)
    check(open(part).read() == "someone else's\n" and not os.path.exists(out3), "an existing .part left as it was")
    os.remove(part)
    # the CSV line bound (1 MiB, docs/command.md): a row of exactly that many bytes (spaces
    # before a number) is read, one byte more is refused naming the file and the line, and so is
    # /dev/zero (a line that never ends: refused at the bound, not when memory runs out)
    limit = 1024 * 1024
    with open(bad, "w") as f:
        f.write("t,joint1,joint1_vel,joint1_acc,joint2,joint2_vel,joint2_acc\n0,0,0,0,0,0,0\n")
        f.write(" " * (limit - 13) + "1,0,0,0,0,0,0\r\n")
    r = run(vtdyn, "inverse", urdf, bad)
    check(r.returncode == 0 and len(r.stdout.splitlines()) == 3, "a line of the CSV bound is read: %r" % r.stderr[:300])
    with open(bad, "w") as f:
        f.write("t,joint1,joint1_vel,joint1_acc,joint2,joint2_vel,joint2_acc\n0,0,0,0,0,0,0\n")
        f.write(" " * (limit - 12) + "1,0,0,0,0,0,0\n0,0,0,0,0,0,0\n")
    r = run(vtdyn, "inverse", urdf, bad)
    check(r.returncode == 1 and "bad.csv:3" in r.stderr and "1048576 bytes" in r.stderr,
          "a line over the CSV bound names the file and line: %r" % r.stderr[:300])
    r = run(vtdyn, "inverse", urdf, "/dev/zero")
    check(r.returncode == 1 and "/dev/zero:1" in r.stderr and "1048576 bytes" in r.stderr,
          "/dev/zero as the CSV is refused at the line bound: %r" % r.stderr[:300])
    # the URDF's bound (VT_URDF_MAX_BYTES): /dev/zero as the robot is refused, named
    r = run(vtdyn, "info", "/dev/zero")
    check(r.returncode == 1 and "/dev/zero" in r.stderr and "VT_URDF_MAX_BYTES" in r.stderr,
          "/dev/zero as the URDF is refused at the bound: %r" % r.stderr[:300])
    strict(vtdyn, urdf, states, work, check)
    r = run(vtdyn, "--help")
    check(r.returncode == 0 and "J_effort" in r.stdout, "--help documents the columns")
    r = run(vtdyn, "info", urdf)
    check(r.returncode == 0 and "joint2" in r.stdout and "link2" in r.stdout, "info lists the joints")
    floating(vtdyn, work, check)
    floating_samples(vtdyn, work, check)
    chunks_threads(vtdyn, urdf, work, check)
    npy_files(vtdyn, urdf, states, work, check)
    options(vtdyn, urdf, states, work, check)
    number_text(vtdyn, urdf, states, work, check)
    payloads(vtdyn, urdf, states, work, check)
    joint_effects(vtdyn, urdf, states, work, check)
    inertia_tolerance(vtdyn, urdf, states, work, check)
    bearing_and_limits(vtdyn, urdf, states, times, work, check)
    help_is_documented(vtdyn, urdf_dir, check)
    loads(vtdyn, urdf_dir, states, work, check)
    cubic_samples(vtdyn, urdf_dir, work, check)
    contacts(vtdyn, urdf_dir, work, check)
    sole_corners(vtdyn, work, check)
    print("%d checks failed" % len(failures) if failures else "every check held")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
