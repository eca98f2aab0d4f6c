#!/usr/bin/env python3
"""The joints' armature and damping against MuJoCo's mj_inverse (PyPI `mujoco`, in the venv of
setup_venv.sh): a spatial arm of four links on hinges about turned axes, written twice, as MJCF
and as URDF, each joint with an armature and a viscous damping (MJCF <joint armature damping>,
the command's --joint-params). At 40 random states MuJoCo's qfrc_inverse, (M + armature) q'' +
c(q, q') + damping q' (mj_inverse: its qfrc_passive holds -damping q'), against `vtdyn inverse`'s
J_effort, to 1e-10 of the largest; and the ideal joints' (--ideal-joints without the file,
MuJoCo's with armature and damping 0) to the same, so that the effects' part is held too.
Coulomb friction is left out: MuJoCo's frictionloss is a constraint of its solver, not a force
law. Exit 0 when both hold, 1 otherwise.

    mujoco_effects.py VTDYN WORKDIR
"""
import csv
import io
import math
import os
import random
import subprocess
import sys

import mujoco
import numpy as np

# link k: its frame from the parent's at (x, y, z) turned by rpy, its hinge's axis, the centre of
# mass, mass, principal inertias; armature and damping of its joint
LINKS = [
    ((0.0, 0.0, 0.2), (0.0, 0.0, 0.0), (0, 0, 1), (0.05, 0.0, 0.1), 3.0, (0.03, 0.025, 0.01), 0.4, 1.5),
    ((0.0, 0.1, 0.3), (0.3, 0.0, 0.0), (0, 1, 0), (0.2, 0.0, 0.0), 2.0, (0.004, 0.02, 0.021), 0.25, 0.8),
    ((0.4, 0.0, 0.0), (0.0, -0.2, 0.1), (0, 1, 0), (0.15, 0.02, 0.0), 1.2, (0.002, 0.01, 0.011), 0.1, 0.5),
    ((0.3, 0.0, 0.05), (0.0, 0.0, 0.5), (1, 0, 0), (0.03, 0.0, 0.0), 0.4, (0.0005, 0.0006, 0.0007), 0.05, 0.2),
]


def quat_rpy(r, p, y):
    """MJCF's quat (w x y z) of URDF's rpy: Rz(y) Ry(p) Rx(r)"""
    cr, sr, cp, sp, cy, sy = (math.cos(r / 2), math.sin(r / 2), math.cos(p / 2), math.sin(p / 2),
                              math.cos(y / 2), math.sin(y / 2))
    return (cr * cp * cy + sr * sp * sy, sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy,
            cr * cp * sy - sr * sp * cy)


def mjcf(effects):
    body, close = "", ""
    for k, (pos, rpy, axis, com, m, inert, arm, damp) in enumerate(LINKS):
        q = quat_rpy(*rpy)
        a, b = (arm, damp) if effects else (0.0, 0.0)
        body += ('<body name="l%d" pos="%r %r %r" quat="%r %r %r %r">'
                 '<joint name="j%d" type="hinge" axis="%d %d %d" armature="%r" damping="%r"/>'
                 '<inertial pos="%r %r %r" mass="%r" diaginertia="%r %r %r"/>'
                 % ((k,) + pos + q + (k,) + axis + (a, b) + com + (m,) + inert))
        close += "</body>"
    return ('<mujoco><compiler angle="radian"/><option gravity="0 0 -9.81"/><worldbody>'
            + body + close + "</worldbody></mujoco>")


def urdf():
    s = '<robot name="arm"><link name="world"/>'
    parent = "world"
    for k, (pos, rpy, axis, com, m, inert, arm, damp) in enumerate(LINKS):
        s += ('<link name="l%d"><inertial><origin xyz="%r %r %r"/><mass value="%r"/>'
              '<inertia ixx="%r" iyy="%r" izz="%r" ixy="0" ixz="0" iyz="0"/></inertial></link>'
              % ((k,) + com + (m,) + inert))
        s += ('<joint name="j%d" type="continuous"><parent link="%s"/><child link="l%d"/>'
              '<origin xyz="%r %r %r" rpy="%r %r %r"/><axis xyz="%d %d %d"/></joint>'
              % ((k, parent, k) + pos + rpy + axis))
        parent = "l%d" % k
    return s + "</robot>"


def mujoco_efforts(xml, states):
    model = mujoco.MjModel.from_xml_string(xml)
    data = mujoco.MjData(model)
    out = []
    for q, v, a in states:
        data.qpos[:], data.qvel[:], data.qacc[:] = q, v, a
        mujoco.mj_inverse(model, data)
        out.append(data.qfrc_inverse.copy())
    return np.array(out)


def vtdyn_efforts(vtdyn, work, states, params):
    path = os.path.join(work, "arm.urdf")
    with open(path, "w") as f:
        f.write(urdf())
    st = os.path.join(work, "arm_states.csv")
    n = len(LINKS)
    with open(st, "w") as f:
        f.write(",".join(sum((["j%d" % k, "j%d_vel" % k, "j%d_acc" % k] for k in range(n)), [])) + "\n")
        for q, v, a in states:
            f.write(",".join(repr(float(x)) for k in range(n) for x in (q[k], v[k], a[k])) + "\n")
    args = [vtdyn, "inverse", "--columns", "effort"]
    if params:
        pf = os.path.join(work, "arm_params.csv")
        with open(pf, "w") as f:
            f.write("joint,armature,damping,friction\n")
            for k, link in enumerate(LINKS):
                f.write("j%d,%r,%r,0\n" % (k, link[6], link[7]))
        args += ["--joint-params", pf]
    else:
        args += ["--ideal-joints"]
    r = subprocess.run(args + [path, st], capture_output=True, text=True)
    if r.returncode:
        raise RuntimeError(r.stderr)
    rows = list(csv.DictReader(io.StringIO(r.stdout)))
    return np.array([[float(row["j%d_effort" % k]) for k in range(n)] for row in rows])


def main():
    vtdyn, work = sys.argv[1], sys.argv[2]
    os.makedirs(work, exist_ok=True)
    rnd = random.Random(7)
    n = len(LINKS)
    states = [([rnd.uniform(-3, 3) for _ in range(n)], [rnd.uniform(-2, 2) for _ in range(n)],
               [rnd.uniform(-2, 2) for _ in range(n)]) for _ in range(40)]
    bad = 0
    for effects in (1, 0):
        ref = mujoco_efforts(mjcf(effects), states)
        mine = vtdyn_efforts(vtdyn, work, states, effects)
        worst = np.abs(mine - ref).max() / np.abs(ref).max()
        print("%s: 40 states, largest difference %.3g of the largest effort %.4g N m (tolerance 1e-10)"
              % ("armature and damping" if effects else "ideal joints", worst, np.abs(ref).max()))
        bad += not worst <= 1e-10
    if bad:
        print("FAIL: vtdyn and MuJoCo differ")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
