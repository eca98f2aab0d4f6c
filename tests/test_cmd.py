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
flight; samples and a non-unit quaternion refused.

    test_cmd.py VTDYN URDF_DIR WORKDIR
"""
import csv
import math
import os
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
    # samples with a floating root: refused, named
    urdf = os.path.join(work, "floater1.urdf")
    samples = os.path.join(work, "floater_samples.csv")
    with open(samples, "w") as fh:
        fh.write("t,float_x,float_y,float_z,float_qw,float_qx,float_qy,float_qz\n0,0,0,0,1,0,0,0\n1,0,0,0,1,0,0,0\n")
    r = run(vtdyn, "inverse", urdf, samples)
    check(r.returncode == 1 and "floating root 'float'" in r.stderr and "samples" in r.stderr,
          "samples with a floating root refused: %r" % r.stderr)
    # a quaternion off the unit sphere: the row and the columns named
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


def strict(vtdyn, urdf, states, work, check):
    """Nothing ignored, nothing overwritten: an unknown column (a typo), a floating root's columns
    on a robot loaded fixed, a column twice (in a header of 110,000 names) each stop the run naming
    the file, the header's line and the column; -o naming an input (under its own or another name),
    a directory or a device is refused and leaves it as it was; a quoted header reads as the plain
    one; --version; a one-link robot loaded fixed says how to float it"""
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
    print("%d checks failed" % len(failures) if failures else "every check held")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
