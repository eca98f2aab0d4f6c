#!/usr/bin/env python3
"""Speed of the Python package vtdyn on UR5 (a benchmark, not a test).

    python bench/bench_python.py [--rows 100000] [--pin-rows 2000] [--runs 3]
                                 [--bench-inverse build/bench/bench_inverse]
                                 [--command-lib build/bench/command_lib]

Run it with a Python that has vtdyn installed (`pip install .`), numpy, and for the peer rows pin
and example-robot-data (tests/peers/setup_venv.sh makes such a venv: install vtdyn into it).
Times, each the median of --runs runs, per row:

* vtdyn batch: Model.inverse(q, v, a, threads=1) on --rows random states (N x 6 arrays): every
  field of Result (efforts, reactions and totals in world, body and joint axes, the bearing
  split, the limits' excess, the effort's parts); again with outputs= the fields the C instant
  holds in its data (efforts, reactions and totals in world and body axes), the like-for-like
  row, into fresh arrays and into out= the arrays of an earlier call (fresh arrays cost the
  kernel's clearing of their pages); and threads=0 (every CPU);
* every field again into out= an earlier Result, against the C batch writing the same fields into
  arrays it reuses (bench/command_lib.c --all, on the same states saved as a .npy): what the
  Python layer adds to the C call it makes;
* vtdyn one state: Model.inverse on one state's 1-D arrays, in a Python loop (the call's overhead);
* the C library: bench_inverse's vtdyn_motion row for UR5 (vt_inverse_dynamics_motion on one
  state, the same outputs), when its executable is given or found in build/bench (its own median
  over rounds; the build's optimization, debugoptimized by default, not the wheel's release);
* Pinocchio from Python: a loop over --pin-rows states of pin.rnea and the joint wrenches
  turned into world axes (forwardKinematics, then f - S tau rotated by oMi for every joint: what
  Model.inverse's reaction holds), scaled per row.
Prints the CPU (lscpu's model name) first.
"""
import argparse
import csv
import os
import statistics
import subprocess
import sys
import tempfile
import time
from importlib.metadata import distribution
from pathlib import Path

import numpy as np

import vtdyn

HERE = Path(__file__).resolve().parent
# what vt_inverse_dynamics_motion leaves in its data: efforts, reactions and totals in both axes
SAME_AS_C = ("effort", "reaction", "reaction_body", "total", "total_body")


def robots_dir():
    dist = distribution("example-robot-data")
    urdf = next(Path(dist.locate_file(f)) for f in dist.files or [] if str(f).endswith(".urdf"))
    return Path(*urdf.parts[: urdf.parts.index("robots") + 1])


def cpu():
    try:
        out = subprocess.run(["lscpu"], capture_output=True, text=True).stdout
        for line in out.splitlines():
            if line.startswith("Model name:"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return "unknown CPU"


def states(m, n, seed=1):
    rng = np.random.default_rng(seed)
    lim = m.limits
    q = rng.uniform(np.maximum(lim[:, 0], -np.pi), np.minimum(lim[:, 1], np.pi), (n, m.nq))
    return q, rng.uniform(-2, 2, (n, m.nv)), rng.uniform(-2, 2, (n, m.nv))


def median_of(runs, f):
    return statistics.median(f() for _ in range(runs))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--rows", type=int, default=100000)
    ap.add_argument("--pin-rows", type=int, default=2000)
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--bench-inverse", default=None, help="build/bench/bench_inverse (the C instant's row)")
    ap.add_argument("--command-lib", default=None, help="build/bench/command_lib (the C batch's row)")
    args = ap.parse_args()
    root = robots_dir()
    urdf = root / "ur_description/urdf/ur5_robot.urdf"
    m = vtdyn.load_urdf(str(urdf))
    q, v, a = states(m, args.rows)
    print("CPU: %s; vtdyn %s, Python %s, NumPy %s" % (cpu(), vtdyn.__version__, sys.version.split()[0],
                                                       np.__version__))
    print("UR5, medians of %d runs, per row:" % args.runs)

    def batch(threads, outputs=None):
        def run():
            t = time.perf_counter()
            m.inverse(q, v, a, threads=threads, outputs=outputs)
            return (time.perf_counter() - t) / args.rows
        return run

    m.inverse(q[:10], v[:10], a[:10], threads=1)  # the batch made before timing
    m.inverse(q[:10], v[:10], a[:10], threads=0)
    t1 = median_of(args.runs, batch(1))
    print("  vtdyn Model.inverse, %d states, threads=1: %8.0f ns" % (args.rows, 1e9 * t1))
    ts = median_of(args.runs, batch(1, SAME_AS_C))
    print("  vtdyn Model.inverse, %d states, threads=1, outputs= what the C instant holds: %8.0f ns"
          % (args.rows, 1e9 * ts))
    reuse = m.inverse(q, v, a, threads=1, outputs=SAME_AS_C)

    def again():
        t = time.perf_counter()
        m.inverse(q, v, a, threads=1, outputs=SAME_AS_C, out=reuse)
        return (time.perf_counter() - t) / args.rows
    tr = median_of(args.runs, again)
    print("  the same into out= an earlier Result (no new pages for the kernel to clear): %8.0f ns" % (1e9 * tr))
    every = m.inverse(q, v, a, threads=1)

    def again_all():
        t = time.perf_counter()
        m.inverse(q, v, a, threads=1, out=every)
        return (time.perf_counter() - t) / args.rows
    ta = median_of(args.runs, again_all)
    print("  vtdyn Model.inverse, every field, into out=: %8.0f ns" % (1e9 * ta))
    lib = args.command_lib or next((str(p) for p in (HERE.parent / "build/bench/command_lib",) if p.exists()), None)
    if lib:  # the C batch writing the same every field, its arrays reused as out= reuses them
        with tempfile.TemporaryDirectory() as d:
            cols = [(n + sfx, "<f8") for n in m.joint_names for sfx in ("", "_vel", "_acc")]
            st = np.zeros(args.rows, dtype=cols)
            for k, n in enumerate(m.joint_names):
                st[n], st[n + "_vel"], st[n + "_acc"] = q[:, k], v[:, k], a[:, k]
            np.save(Path(d) / "states.npy", st)

            def c_batch():
                r = subprocess.run([lib, str(urdf), str(Path(d) / "states.npy"), "1", "11", "--all"],
                                   capture_output=True, text=True)
                if r.returncode:
                    raise RuntimeError("%s: %s" % (lib, r.stderr.strip()))
                return 1e-6 * float(r.stdout.strip())
            tb = median_of(args.runs, c_batch)
        print("  C vt_batch_inverse_dynamics_motion, every field, arrays reused (command_lib --all): %8.0f ns   "
              "(Python into out= / C batch: %.2f)" % (1e9 * tb, ta / tb))
    else:
        print("  C batch row skipped: no build/bench/command_lib (give --command-lib)")
    t0 = median_of(args.runs, batch(0))
    print("  vtdyn Model.inverse, %d states, threads=0 (%d CPUs): %8.0f ns" % (args.rows, os.cpu_count() or 0, 1e9 * t0))
    n1 = min(args.rows, 20000)

    def one():
        t = time.perf_counter()
        for i in range(n1):
            m.inverse(q[i], v[i], a[i], threads=1)
        return (time.perf_counter() - t) / n1
    print("  vtdyn Model.inverse, one state a call (%d calls): %8.0f ns" % (n1, 1e9 * median_of(args.runs, one)))

    exe = args.bench_inverse or next((str(p) for p in (HERE.parent / "build/bench/bench_inverse",) if p.exists()), None)
    tc = None
    if exe:
        def c_run():
            with tempfile.TemporaryDirectory() as d:
                env = dict(os.environ, VT_BENCH_ONLY="ur5")
                r = subprocess.run([exe, d, "21", str(root)], capture_output=True, text=True, env=env)
                if r.returncode:
                    raise RuntimeError("%s: %s" % (exe, r.stderr.strip()))
                with open(Path(d) / "inverse_speed.csv") as f:
                    rows = [x for x in csv.DictReader(f) if x["scene"] == "ur5" and x["method"] == "vtdyn_motion"]
                return 1e-6 * float(rows[0]["median_us"])
        tc = median_of(args.runs, c_run)
        print("  C vt_inverse_dynamics_motion (bench_inverse, one state): %8.0f ns   (Python batch / C: %.2f; "
              "with the C instant's outputs: %.2f; into out=: %.2f)" % (1e9 * tc, t1 / tc, ts / tc, tr / tc))
    else:
        print("  C row skipped: no build/bench/bench_inverse (give --bench-inverse)")

    try:
        import pinocchio as pin
    except ImportError:
        print("  Pinocchio row skipped: no pinocchio in this Python")
        return 0
    pm = pin.buildModelFromUrdf(str(urdf))
    pd = pm.createData()
    ids = [pm.getJointId(n) for n in m.joint_names]
    order = [pm.joints[j].idx_q for j in ids]
    S = [np.asarray(pd.joints[j].S).reshape(6, 1) for j in ids]
    n2 = min(args.pin_rows, args.rows)
    qp, vp, ap2 = np.empty_like(q[:n2]), np.empty_like(v[:n2]), np.empty_like(a[:n2])
    qp[:, order], vp[:, order], ap2[:, order] = q[:n2], v[:n2], a[:n2]

    def pin_run():
        out = np.empty((n2, len(ids), 6))
        t = time.perf_counter()
        for s in range(n2):
            tau = pin.rnea(pm, pd, qp[s], vp[s], ap2[s])
            pin.forwardKinematics(pm, pd, qp[s])
            for k, j in enumerate(ids):
                fr = pd.f[j].vector - S[k][:, 0] * tau[pm.joints[j].idx_v]
                R = pd.oMi[j].rotation
                out[s, k, :3], out[s, k, 3:] = R @ fr[:3], R @ fr[3:]
        return (time.perf_counter() - t) / n2
    tp = median_of(args.runs, pin_run)
    print("  Pinocchio from Python: rnea + world joint wrenches, loop over %d states: %8.0f ns   (/ vtdyn batch: %.0f)"
          % (n2, 1e9 * tp, tp / t1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
