#!/usr/bin/env python3
"""vtdyn against Pinocchio on the robots of example-robot-data (run by run_peer.sh with the
venv's python, which has pin and example-robot-data).

    run_pinocchio.py COMPARE VTDYN WORKDIR IN_FLIGHT

1. UR5, Panda, Solo-12, Talos and ANYmal, each with its root welded to the world (Pinocchio's
   buildModelFromUrdf without a root joint; vtdyn's loader by default): at 20 random states
   (the last 4 at rest) Pinocchio's rnea and data.f (pinocchio_reference.py) against vtdyn's
   vt_inverse_dynamics_motion (compare_pinocchio): the torques and every joint reaction, in
   world axes and in the joint's axes, to 1e-12 of the largest of the state. Then Solo-12,
   Talos and ANYmal as free flyers (Pinocchio's JointModelFreeFlyer root; vtdyn's loader with
   floating = 1, a free joint at the root link's origin): the same at 20 random states, the base's
   six torques included (vtdyn's world wrench turned into the root frame) and its reaction (zero).
1b. The joints' own effects: UR5 and Panda welded, Solo-12 and Talos as free flyers, each
   one-velocity joint with an armature (Pinocchio's model.armature, in its rnea; the same values
   set on vtdyn's builder by vt_builder_set_joint_effects) and the URDF's <dynamics> as each
   reads them (Panda and Talos declare them; Pinocchio's model.damping v + model.friction
   sign(v) added to its torques): the torques and reactions to 1e-12, and the damping and
   friction vtdyn read equal to Pinocchio's.
2. The command vtdyn on UR5: the reference's states as a states file (the torques to 1e-12), and
   samples of a smooth motion q_j(t) = a_j sin(w_j t + phi_j) as a samples file: vtdyn's torques
   from the splines against Pinocchio's rnea with the exact derivatives, to 1e-4 of the largest
   torque at the interior samples. And `vtdyn inverse --floating` on Solo-12: the free-flyer
   reference's states, the base's six efforts (link axes) and the joints' torques to 1e-12, from
   a CSV file and from a NumPy .npy file to a .npy file (numpy.load, -j 2).
3. Every URDF the package ships through `vtdyn info`: accepted, or refused with its reason
   (a count, and the reasons; a crash fails the test).
4. Solo-12, Talos and ANYmal in flight (robots_in_flight): a free root, every joint driven, 20
   random states on the partly driven route: no warning and no failure from the robots' inertia
   spread, both paths' condition estimates equal, and the motion found needs no effort on the
   root and the same joint efforts when given to vt_inverse_dynamics_motion.
Exit 0 when every comparison holds, 1 otherwise.
"""
import csv
import math
import os
import subprocess
import sys
from importlib.metadata import distribution
from pathlib import Path

import numpy as np
import pinocchio as pin

HERE = Path(__file__).resolve().parent
ROBOTS = [
    ("UR5", "ur_description/urdf/ur5_robot.urdf", 1),
    ("Panda", "panda_description/urdf/panda.urdf", 2),
    ("Solo-12", "solo_description/robots/solo12.urdf", 3),
    ("Talos", "talos_data/robots/talos_reduced.urdf", 4),
    ("ANYmal", "anymal_b_simple_description/robots/anymal.urdf", 5),
]
FLOATING = ("Solo-12", "Talos", "ANYmal")


def robots_dir():
    dist = distribution("example-robot-data")
    urdfs = sorted(Path(dist.locate_file(f)) for f in dist.files or [] if str(f).endswith(".urdf"))
    parts = urdfs[0].parts
    return Path(*parts[: parts.index("robots") + 1]), urdfs


def run(*args):
    return subprocess.run([str(a) for a in args], capture_output=True, text=True)


def main():
    compare, vtdyn, work, in_flight = sys.argv[1], sys.argv[2], Path(sys.argv[3]), sys.argv[4]
    work.mkdir(parents=True, exist_ok=True)
    root, urdfs = robots_dir()
    failures = []

    # 1. the five robots
    for name, rel, seed in ROBOTS:
        urdf = root / rel
        ref = work / ("%s.csv" % name)
        r = run(sys.executable, HERE / "pinocchio_reference.py", urdf, "fixed", 20, seed, ref, "--static", 4)
        if r.returncode:
            failures.append("%s: pinocchio_reference.py: %s" % (name, r.stderr.strip()))
            continue
        r = run(compare, urdf, ref, "1e-12")
        print("%s: %s" % (name, (r.stdout + r.stderr).strip()))
        if r.returncode:
            failures.append("%s: vtdyn and Pinocchio differ" % name)
        if name not in FLOATING:
            continue
        ref = work / ("%s_free_flyer.csv" % name)
        r = run(sys.executable, HERE / "pinocchio_reference.py", urdf, "free-flyer", 20, seed + 10, ref, "--static", 4)
        if r.returncode:
            failures.append("%s (free flyer): pinocchio_reference.py: %s" % (name, r.stderr.strip()))
            continue
        r = run(compare, "--floating", urdf, ref, "1e-12")
        print("%s (free flyer): %s" % (name, (r.stdout + r.stderr).strip()))
        if r.returncode:
            failures.append("%s (free flyer): vtdyn and Pinocchio differ" % name)

    # 1b. the joints' own effects: Pinocchio's rnea with model.armature set, plus its reading of
    # <dynamics> (damping v + friction sign(v)), against vtdyn with the same armature and its
    # own reading (Panda and Talos declare <dynamics>; UR5 and Solo-12 do not)
    for name, root_kind, seed in (("UR5", "fixed", 21), ("Panda", "fixed", 22), ("Solo-12", "free-flyer", 23),
                                  ("Talos", "free-flyer", 24)):
        urdf = root / dict((n, r) for n, r, _ in ROBOTS)[name]
        ref = work / ("%s_effects_%s.csv" % (name, root_kind))
        r = run(sys.executable, HERE / "pinocchio_reference.py", urdf, root_kind, 20, seed, ref, "--static", 4,
                "--effects")
        if r.returncode:
            failures.append("%s (effects): pinocchio_reference.py: %s" % (name, r.stderr.strip()))
            continue
        flags = ["--floating"] if root_kind == "free-flyer" else []
        r = run(compare, *flags, "--effects", urdf, ref, "1e-12")
        print("%s (%s, armature, damping, friction): %s" % (name, root_kind, (r.stdout + r.stderr).strip()))
        if r.returncode:
            failures.append("%s (effects): vtdyn and Pinocchio differ" % name)

    # 2. the command on UR5
    urdf = root / ROBOTS[0][1]
    with open(work / "UR5.csv") as f:
        ref = list(csv.DictReader(f))
    joints = [c.split(":")[1] for c in ref[0] if c.startswith("q:")]
    states = work / "ur5_states.csv"
    with open(states, "w") as f:
        f.write(",".join(sum(([j, j + "_vel", j + "_acc"] for j in joints), [])) + "\n")
        for row in ref:
            f.write(",".join(sum(([row["q:%s:0" % j], row["v:%s:0" % j], row["a:%s:0" % j]] for j in joints), []))
                    + "\n")
    out = work / "ur5_states_out.csv"
    r = run(vtdyn, "inverse", urdf, states, "-o", out)
    if r.returncode:
        failures.append("vtdyn inverse (UR5 states): %s" % r.stderr.strip())
    else:
        with open(out) as f:
            got = list(csv.DictReader(f))
        worst = 0.0
        for g, row in zip(got, ref):
            tau = [float(row["tau:%s:0" % j]) for j in joints]
            scale = max(1.0, max(abs(t) for t in tau))
            worst = max(worst, max(abs(float(g[j + "_effort"]) - t) / scale for j, t in zip(joints, tau)))
        print("vtdyn inverse, UR5 states file: %d rows, largest relative torque difference %.2g" % (len(got), worst))
        if len(got) != len(ref) or worst > 1e-12:
            failures.append("vtdyn inverse (UR5 states): %.3g" % worst)
    model = pin.buildModelFromUrdf(str(urdf))
    data = model.createData()
    rng = np.random.default_rng(7)
    amp, w, ph = rng.uniform(0.3, 1.0, model.nv), rng.uniform(0.5, 2.0, model.nv), rng.uniform(0, 2 * math.pi, model.nv)
    times = np.linspace(0.0, 3.0, 601)
    names = [model.names[j] for j in range(1, model.njoints)]
    samples = work / "ur5_samples.csv"
    expected = []
    with open(samples, "w") as f:
        f.write("t," + ",".join(names) + "\n")
        for t in times:
            q = amp * np.sin(w * t + ph)
            v = amp * w * np.cos(w * t + ph)
            a = -amp * w * w * np.sin(w * t + ph)
            expected.append(pin.rnea(model, data, q, v, a).copy())
            f.write(repr(float(t)) + "," + ",".join(repr(float(x)) for x in q) + "\n")
    out = work / "ur5_samples_out.csv"
    r = run(vtdyn, "inverse", urdf, samples, "-o", out)
    if r.returncode:
        failures.append("vtdyn inverse (UR5 samples): %s" % r.stderr.strip())
    else:
        with open(out) as f:
            got = list(csv.DictReader(f))
        big = max(abs(x) for e in expected for x in e)
        worst = max(abs(float(g[n + "_effort"]) - e[k]) for g, e in zip(got[5:-5], expected[5:-5])
                    for k, n in enumerate(names))
        print("vtdyn inverse, UR5 samples file: %d samples, largest torque difference %.2g of %.3g N m"
              % (len(got), worst, big))
        if len(got) != len(times) or worst > 1e-4 * big:
            failures.append("vtdyn inverse (UR5 samples): %.3g of %.3g" % (worst, big))

    # the command on Solo-12 floating: the free-flyer reference's states with the root's columns
    # (base_link_x ... base_link_alz, world axes) and its efforts in the root link's axes against
    # Pinocchio's free-flyer tau
    urdf = root / ROBOTS[2][1]
    with open(work / "Solo-12_free_flyer.csv") as f:
        ref = list(csv.DictReader(f))
    joints = [c.split(":")[1] for c in ref[0] if c.startswith("q:") and c.endswith(":0")]
    joints = [j for j in joints if j != "root_joint"]
    rootcols = ["base_link_" + c for c in "x y z qw qx qy qz vx vy vz wx wy wz ax ay az alx aly alz".split()]
    states = work / "solo_floating_states.csv"
    with open(states, "w") as f:
        f.write(",".join(rootcols + sum(([j, j + "_vel", j + "_acc"] for j in joints), [])) + "\n")
        for row in ref:
            q = [row["q:root_joint:%d" % k] for k in (0, 1, 2, 6, 3, 4, 5)]
            base = [row["base:%s:%s" % (w, c)] for w in ("pdot", "omega", "pddot", "omegadot") for c in "xyz"]
            f.write(",".join(q + base + sum(([row["q:%s:0" % j], row["v:%s:0" % j], row["a:%s:0" % j]]
                                             for j in joints), [])) + "\n")
    out = work / "solo_floating_out.csv"
    r = run(vtdyn, "inverse", "--floating", urdf, states, "-o", out)
    if r.returncode:
        failures.append("vtdyn inverse --floating (Solo-12 states): %s" % r.stderr.strip())
    else:
        with open(out) as f:
            got = list(csv.DictReader(f))
        worst = 0.0
        names = ["base_link_effort_%s_link" % c for c in ("fx", "fy", "fz", "nx", "ny", "nz")]
        for g, row in zip(got, ref):
            tau = [float(row["tau:root_joint:%d" % k]) for k in range(6)] + [float(row["tau:%s:0" % j]) for j in joints]
            mine = [float(g[n]) for n in names] + [float(g[j + "_effort"]) for j in joints]
            scale = max(1.0, max(abs(t) for t in tau))
            worst = max(worst, max(abs(a - b) / scale for a, b in zip(mine, tau)))
        print("vtdyn inverse --floating, Solo-12 states file: %d rows, largest relative torque difference %.2g"
              % (len(got), worst))
        if len(got) != len(ref) or worst > 1e-12:
            failures.append("vtdyn inverse --floating (Solo-12 states): %.3g" % worst)
    # the same states as a NumPy structured array (.npy in, -j 2) and the efforts as one (.npy
    # out, numpy.load): the same to 1e-12
    with open(states) as f:
        rows = list(csv.reader(f))
    arr = np.rec.fromarrays([np.array([float(r[k]) for r in rows[1:]]) for k in range(len(rows[0]))],
                            names=",".join(rows[0]))
    np.save(work / "solo_floating_states.npy", arr)
    out = work / "solo_floating_out.npy"
    r = run(vtdyn, "inverse", "--floating", "-j", "2", urdf, work / "solo_floating_states.npy", "-o", out)
    if r.returncode:
        failures.append("vtdyn inverse --floating (Solo-12 states, .npy): %s" % r.stderr.strip())
    else:
        got = np.load(out)
        names = ["base_link_effort_%s_link" % c for c in ("fx", "fy", "fz", "nx", "ny", "nz")]
        worst = 0.0
        for k, row in enumerate(ref):
            tau = [float(row["tau:root_joint:%d" % i]) for i in range(6)] + [float(row["tau:%s:0" % j]) for j in joints]
            mine = [float(got[n][k]) for n in names] + [float(got[j + "_effort"][k]) for j in joints]
            scale = max(1.0, max(abs(t) for t in tau))
            worst = max(worst, max(abs(a - b) / scale for a, b in zip(mine, tau)))
        print("vtdyn inverse --floating, Solo-12 states .npy -> .npy: %d rows, largest relative torque difference %.2g"
              % (got.shape[0], worst))
        if got.shape != (len(ref),) or worst > 1e-12:
            failures.append("vtdyn inverse --floating (Solo-12 states, .npy): %.3g" % worst)

    # 3. every URDF of the package
    accepted, refused = 0, {}
    for u in urdfs:
        r = run(vtdyn, "info", u)
        if r.returncode == 0:
            accepted += 1
        elif r.returncode == 1:
            reason = r.stderr.strip().splitlines()[-1] if r.stderr.strip() else "?"
            refused[str(u.relative_to(root))] = reason.split(": ", 2)[-1]
        else:
            failures.append("vtdyn info %s: exit %d (%s)" % (u, r.returncode, r.stderr.strip()))
    print("example-robot-data: %d URDFs, %d accepted, %d refused" % (len(urdfs), accepted, len(refused)))
    for path, reason in sorted(refused.items()):
        print("  refused %s: %s" % (path, reason))

    # 4. the floating robots in flight
    for name, rel, _ in ROBOTS:
        if name in FLOATING:
            r = run(in_flight, root / rel)
            print("%s: %s" % (name, (r.stdout + r.stderr).strip().replace(str(root / rel) + " ", "")))
            if r.returncode:
                failures.append("%s in flight: the estimate warned or failed, or the motion disagrees" % name)

    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
