#!/usr/bin/env python3
"""Random states of a URDF robot for `vtdyn inverse`, as a CSV file and a .npy file of the same
numbers (bench/bench_command.sh). The columns are those `vtdyn info` prints for the robot (a
floating root's with --floating); positions in [-pi, pi] (a floating root's origin in [-1, 1] m
and a unit quaternion), velocities in [-2, 2], accelerations in [-5, 5]; a fixed seed. The .npy
file is written with struct (no numpy needed): a structured array of '<f8' fields, shape (N,).
With --samples (a robot fixed to the world): samples instead, t = 0, 1 ms, ... and each joint's
position a sine, q_j = a_j sin(w_j t + p_j) (a_j in [0.2, 1.5] rad, w_j in [0.5, 3] rad/s).

    command_states.py VTDYN URDF N OUT.csv OUT.npy [--floating | --samples]
"""
import math
import random
import struct
import subprocess
import sys


def columns(vtdyn, urdf, floating):
    out = subprocess.run([vtdyn, "info"] + (["--floating"] if floating else []) + [urdf],
                         capture_output=True, text=True, check=True).stdout.splitlines()
    for k, line in enumerate(out):
        if line.startswith("states columns ("):
            return out[k + 1].split(",")
    sys.exit("command_states.py: no states columns in vtdyn info's output")


def npy_header(names, nrow):
    d = "{'descr': [%s], 'fortran_order': False, 'shape': (%d,), }" % (
        ", ".join("(%r, '<f8')" % n for n in names), nrow)
    total = (10 + len(d) + 1 + 63) // 64 * 64
    return b"\x93NUMPY\x01\x00" + struct.pack("<H", total - 10) + (d + " " * (total - 10 - len(d) - 1) + "\n").encode()


def main():
    vtdyn, urdf, n, out_csv, out_npy = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4], sys.argv[5]
    floating = "--floating" in sys.argv[6:]
    names = columns(vtdyn, urdf, floating)
    rnd = random.Random(2026)
    if "--samples" in sys.argv[6:]:
        joints = [c for c in names if not c.endswith(("_vel", "_acc"))]
        wave = [(rnd.uniform(0.2, 1.5), rnd.uniform(0.5, 3.0), rnd.uniform(0, 2 * math.pi)) for _ in joints]
        names = ["t"] + joints
        row_fmt = struct.Struct("<%dd" % len(names))
        with open(out_csv, "w") as fc, open(out_npy, "wb") as fn:
            fc.write(",".join(names) + "\n")
            fn.write(npy_header(names, n))
            for k in range(n):
                t = 1e-3 * k
                row = [t] + [a * math.sin(w * t + p) for a, w, p in wave]
                fc.write(",".join(repr(x) for x in row) + "\n")
                fn.write(row_fmt.pack(*row))
        return
    quat = [k for k, c in enumerate(names) if c.endswith("_qw")]
    row_fmt = struct.Struct("<%dd" % len(names))
    with open(out_csv, "w") as fc, open(out_npy, "wb") as fn:
        fc.write(",".join(names) + "\n")
        fn.write(npy_header(names, n))
        for _ in range(n):
            row = []
            for c in names:
                if c.endswith("_vel") or c[-3:] in ("_vx", "_vy", "_vz", "_wx", "_wy", "_wz"):
                    row.append(rnd.uniform(-2, 2))
                elif c.endswith("_acc") or c[-3:] in ("_ax", "_ay", "_az") or c[-4:] in ("_alx", "_aly", "_alz"):
                    row.append(rnd.uniform(-5, 5))
                elif c[-2:] in ("_x", "_y", "_z"):
                    row.append(rnd.uniform(-1, 1))
                else:
                    row.append(rnd.uniform(-math.pi, math.pi))
            for k in quat:  # a unit quaternion (the CSV's 17 digits read back as the .npy's doubles)
                q = [rnd.gauss(0, 1) for _ in range(4)]
                s = math.sqrt(sum(x * x for x in q))
                row[k:k + 4] = [x / s for x in q]
            fc.write(",".join(repr(x) for x in row) + "\n")
            fn.write(row_fmt.pack(*row))


if __name__ == "__main__":
    main()
