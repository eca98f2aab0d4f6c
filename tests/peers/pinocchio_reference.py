#!/usr/bin/env python3
"""Reference inverse dynamics and joint reactions of a URDF robot, computed by Pinocchio.

    python pinocchio_reference.py URDF {fixed|free-flyer} N SEED OUT.csv [--static K] [--effects]

loads URDF with ``pin.buildModelFromUrdf`` (with ``pin.JointModelFreeFlyer()`` as root joint
for ``free-flyer``; mimic joints are not enabled, so a URDF mimic joint is an independent
joint), draws N random states with ``numpy.random.default_rng(SEED)``, runs ``pin.rnea`` on
each and writes OUT.csv (``-`` for stdout). Only pinocchio and numpy are used.

Random states
    q: for every coordinate of a one-coordinate joint (revolute, prismatic, helical...)
       uniform within the URDF limits when they are finite and lower < upper; otherwise
       uniform in [-pi, pi] (revolute-like) or [-1, 1] m (prismatic). Pinocchio stores "no
       limit" as +-DBL_MAX: any |limit| >= 1e300 counts as infinite. A continuous joint
       (Pinocchio's JointModelRUB*, nq = 2, nv = 1) gets theta uniform in [-pi, pi] and
       q = (cos theta, sin theta). A free flyer gets its position uniform in [-1, 1]^3 m and a
       uniform random unit quaternion; a spherical joint a uniform random unit quaternion.
    v, a: uniform in [-2, 2] for every velocity coordinate.
    With --static K the last K of the N states have v = a = 0 (q random as above): there the
    reactions carry only the weights, which tests/peers/check_reference.py checks.

Conventions (Pinocchio's)
    * Joints are Pinocchio's joints 1 .. njoints-1 in Pinocchio's order (depth first, as
      model.names; "universe", joint 0, is left out). URDF fixed joints are not joints: their
      child links are merged into the parent joint's body (for a fixed base the root link and
      everything fixed to it are merged into the universe, which no column reports).
    * A joint's frame (Pinocchio's "joint frame", the frame of the body that the joint moves)
      is oMi[j] = oMi[parent] * jointPlacements[j] * M_j(q_j): at q_j = 0 it coincides with the
      URDF joint's origin frame (the child link's frame for a URDF joint; the root link's
      frame for the free flyer).
    * Spatial vectors are [linear; angular]: a force is (f_x, f_y, f_z, m_x, m_y, m_z) and a
      motion (v_x, v_y, v_z, w_x, w_y, w_z).
    * Free flyer: q = (x, y, z, q_x, q_y, q_z, q_w), the position of the root link's origin in
      the world and the unit quaternion (scalar LAST) of the rotation R that takes root-frame
      coordinates to world coordinates (R = oMi[1].rotation). v and a are expressed in the ROOT
      frame (local): v = (R^T pdot, R^T omega); a = d/dt v, so a_linear is NOT R^T pddot:
      R^T pddot = a_linear + w x v_linear (the base_* columns give the world quantities).
    * Continuous joint: q = (cos theta, sin theta), one velocity theta_dot.
    * tau = pin.rnea(model, data, q, v, a): the generalized forces, in v's order, under
      model.gravity (URDF gives none: Pinocchio's default (0, 0, -9.81) m/s^2, world z up).
      The model's armature (zero from a URDF) is added to tau, not to f. With --effects every
      one-velocity joint gets armature 0.02 (1 + j mod 4) (j its Pinocchio index), and tau also
      takes model.damping * v + model.friction * sign(v), Pinocchio's reading of the URDF's
      <dynamics damping friction>; the columns armature:JOINT, damping:JOINT, friction:JOINT
      (one-velocity joints) give the three.
    * f[j] = data.f[j] after rnea: the spatial force that the parent body exerts ON body j
      THROUGH joint j (the net inertial-minus-gravity wrench of the whole subtree rooted at
      j), expressed in joint j's frame, the moment about joint j's origin. rnea's backward
      pass gives tau_j = S_j^T f[j] and adds liMi[j].act(f[j]) to the parent's f.
      S_j is the joint's motion subspace (data.joints[j].S, in joint j's frame, 6 x nv_j).
      f[j] includes the actuation: for a revolute joint S_j = (0, 0, 0, axis) and the moment
      along the axis is tau_j.
    * fr[j] = f[j] - S_j tau_j: the reaction without the actuation (what vtdyn reports as a
      joint reaction). For a revolute joint its moment has no component along the axis; for a
      prismatic one its force none along the axis; for the free flyer (S = I) it is zero.
      (For a joint whose S has orthonormal columns this is the projection of f off the
      motion subspace; the script stops on any joint whose S^T S is not I.)
    * World versions rotate both parts with R_j = oMi[j].rotation: f_world = (R_j f_lin,
      R_j f_ang). The moment stays about joint j's origin (oMi[j].translation), NOT about the
      world origin; the moment about a point P is m + (o_j - P) x f.

Columns (one header line of names, then one row per state; every value is a float written
with Python's repr, i.e. the shortest string that reads back to the same double, so strtod
recovers it exactly; integers are written as integers). Names have the form
QUANTITY:JOINT:COMPONENT, JOINT a Pinocchio joint name, with joints in Pinocchio's order
inside each group; the groups come in this order:

    state                     row index 0 .. N-1
    seed                      the SEED argument
    gravity_x gravity_y gravity_z       model.gravity.linear, m/s^2, world frame
    total_mass                sum of model.inertias[i].mass over i = 0 .. njoints-1, kg (for
                              a fixed base this includes the links merged into the universe)
    q:JOINT:k                 k = 0 .. nq_j-1 (the model's q vector, in order; see above)
    v:JOINT:k                 k = 0 .. nv_j-1 (the model's v vector, in order)
    a:JOINT:k                 k = 0 .. nv_j-1
    tau:JOINT:k               k = 0 .. nv_j-1, N or N m (free flyer: a force, in the root frame)
    base:pdot:x|y|z           free flyer only: root origin velocity, world axes, m/s
    base:omega:x|y|z          free flyer only: root angular velocity, world axes, rad/s
    base:pddot:x|y|z          free flyer only: root origin (classical) acceleration, world, m/s^2
    base:omegadot:x|y|z       free flyer only: root angular acceleration, world axes, rad/s^2
    then, for each joint JOINT in Pinocchio's order, the block:
    parent:JOINT              index of the parent joint (0 = universe; joint k is the k-th
                              joint block, counting from 1)
    mass:JOINT                model.inertias[j].mass, kg: the body of joint j with every link
                              merged into it through fixed joints
    com:JOINT:x|y|z           that body's centre of mass at q, world frame, m
    S:JOINT:r                 r = 0..5, the motion subspace S_j (joint frame) of a joint with
                              nv_j = 1; nothing for other joints
    p:JOINT:x|y|z             oMi[j].translation: joint j's origin in the world, m
    R:JOINT:rc                r, c = 0..2 (R:JOINT:00, 01, 02, 10, ... 22): oMi[j].rotation,
                              row-major; column c is joint j's axis c in world coordinates
    f:JOINT:fx|fy|fz|mx|my|mz       data.f[j], joint frame, about joint j's origin, N and N m
    fr:JOINT:fx|fy|fz|mx|my|mz      f[j] - S_j tau_j, joint frame, about joint j's origin
    fw:JOINT:fx|fy|fz|mx|my|mz      f[j] in world axes, moment about joint j's origin
    frw:JOINT:fx|fy|fz|mx|my|mz     fr[j] in world axes, moment about joint j's origin

Exit status 0 on success, 1 on a load failure or a bad argument, with a message on stderr.
"""
import argparse
import math
import sys

import numpy as np
import pinocchio as pin

INF_LIMIT = 1e300
FORCE_COMPONENTS = ("fx", "fy", "fz", "mx", "my", "mz")
XYZ = ("x", "y", "z")


def load_model(urdf, root):
    if root == "free-flyer":
        return pin.buildModelFromUrdf(urdf, pin.JointModelFreeFlyer())
    return pin.buildModelFromUrdf(urdf)


def random_unit_quaternion(rng):
    while True:
        x = rng.normal(size=4)
        n = np.linalg.norm(x)
        if n > 1e-6:
            return x / n  # (x, y, z, w): a uniform rotation either way


def random_q(model, rng):
    q = pin.neutral(model)
    lo_all, hi_all = model.lowerPositionLimit, model.upperPositionLimit
    for j in range(1, model.njoints):
        jm = model.joints[j]
        kind = jm.shortname()
        iq, nq, nv = jm.idx_q, jm.nq, jm.nv
        if kind == "JointModelFreeFlyer":
            q[iq:iq + 3] = rng.uniform(-1.0, 1.0, 3)
            q[iq + 3:iq + 7] = random_unit_quaternion(rng)
        elif kind == "JointModelSpherical":
            q[iq:iq + 4] = random_unit_quaternion(rng)
        elif kind.startswith("JointModelRUB") or kind == "JointModelRevoluteUnboundedUnaligned":
            th = rng.uniform(-math.pi, math.pi)
            q[iq:iq + 2] = (math.cos(th), math.sin(th))
        elif nq == nv:
            prismatic = kind.startswith("JointModelP") and kind != "JointModelPlanar"
            default = (-1.0, 1.0) if prismatic else (-math.pi, math.pi)
            for k in range(iq, iq + nq):
                lo, hi = lo_all[k], hi_all[k]
                finite = abs(lo) < INF_LIMIT and abs(hi) < INF_LIMIT and lo < hi
                q[k] = rng.uniform(lo, hi) if finite else rng.uniform(*default)
        else:
            raise ValueError(f"joint {model.names[j]}: no sampling rule for {kind}")
    return q


def columns_and_checks(model, effects=False):
    """The header, in the order described in the docstring."""
    names = list(model.names)
    cols = ["state", "seed", "gravity_x", "gravity_y", "gravity_z", "total_mass"]
    for qty, size in (("q", "nq"), ("v", "nv"), ("a", "nv"), ("tau", "nv")):
        for j in range(1, model.njoints):
            n = getattr(model.joints[j], size)
            cols += [f"{qty}:{names[j]}:{k}" for k in range(n)]
    free = model.njoints > 1 and model.joints[1].shortname() == "JointModelFreeFlyer"
    if free:
        for qty in ("pdot", "omega", "pddot", "omegadot"):
            cols += [f"base:{qty}:{c}" for c in XYZ]
    for j in range(1, model.njoints):
        n = names[j]
        cols += [f"parent:{n}", f"mass:{n}"] + [f"com:{n}:{c}" for c in XYZ]
        if model.joints[j].nv == 1:
            cols += [f"S:{n}:{r}" for r in range(6)]
        cols += [f"p:{n}:{c}" for c in XYZ]
        cols += [f"R:{n}:{r}{c}" for r in range(3) for c in range(3)]
        for qty in ("f", "fr", "fw", "frw"):
            cols += [f"{qty}:{n}:{c}" for c in FORCE_COMPONENTS]
    if effects:
        for j in range(1, model.njoints):
            if model.joints[j].nv == 1:
                cols += [f"{qty}:{names[j]}" for qty in ("armature", "damping", "friction")]
    if len(set(cols)) != len(cols):
        raise ValueError("joint names make duplicate column names")
    return cols, free


def fmt(x):
    if isinstance(x, (int, np.integer)):
        return str(int(x))
    return repr(float(x))


def set_armature(model):
    """--effects: every one-velocity joint's armature 0.02 (1 + j mod 4) kg m^2 (or kg)"""
    arm = np.zeros(model.nv)
    for j in range(1, model.njoints):
        jm = model.joints[j]
        if jm.nv == 1:
            arm[jm.idx_v] = 0.02 * (1 + j % 4)
    model.armature = arm


def one_state(model, data, kin, q, v, a, free, state, seed, effects=False):
    tau = pin.rnea(model, data, q, v, a).copy()  # with model.armature a
    if effects:  # <dynamics>, as Pinocchio reads them: its rnea leaves them out
        tau += model.damping * v + model.friction * np.sign(v)
    pin.forwardKinematics(model, kin, q)  # rnea sets liMi, not oMi: a second data for these
    row = [state, seed] + list(model.gravity.linear)
    row.append(sum(model.inertias[i].mass for i in range(model.njoints)))
    row += list(q) + list(v) + list(a) + list(tau)
    if free:
        R = kin.oMi[1].rotation
        vl, wl = v[0:3], v[3:6]
        al, dwl = a[0:3], a[3:6]
        row += list(R @ vl) + list(R @ wl) + list(R @ (al + np.cross(wl, vl))) + list(R @ dwl)
    for j in range(1, model.njoints):
        jm = model.joints[j]
        M = kin.oMi[j]
        R = M.rotation
        S = np.asarray(data.joints[j].S).reshape(6, jm.nv)
        if not np.allclose(S.T @ S, np.eye(jm.nv), atol=1e-12, rtol=0):
            raise ValueError(f"joint {model.names[j]}: S^T S is not I, f - S tau is no reaction")
        f = data.f[j].vector.copy()
        fr = f - S @ (S.T @ f)  # S^T f: the torque without the joint's armature, damping, friction
        row += [int(model.parents[j]), model.inertias[j].mass]
        row += list(M.act(model.inertias[j].lever))
        if jm.nv == 1:
            row += list(S[:, 0])
        row += list(M.translation) + list(R.reshape(9))
        row += list(f) + list(fr)
        row += list(R @ f[:3]) + list(R @ f[3:]) + list(R @ fr[:3]) + list(R @ fr[3:])
    if effects:
        for j in range(1, model.njoints):
            jm = model.joints[j]
            if jm.nv == 1:
                k = jm.idx_v
                row += [model.armature[k], model.damping[k], model.friction[k]]
    return row


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("urdf")
    ap.add_argument("root", choices=("fixed", "free-flyer"))
    ap.add_argument("states", type=int)
    ap.add_argument("seed", type=int)
    ap.add_argument("out", help="the CSV to write, - for stdout")
    ap.add_argument("--static", type=int, default=0, metavar="K",
                    help="the last K states have v = a = 0")
    ap.add_argument("--effects", action="store_true",
                    help="armature on every one-velocity joint, and tau with the URDF's <dynamics>")
    args = ap.parse_args(argv)
    if args.states < 1 or not 0 <= args.static <= args.states:
        ap.error("need N >= 1 and 0 <= K <= N")
    try:
        model = load_model(args.urdf, args.root)
        if args.effects:
            set_armature(model)
        cols, free = columns_and_checks(model, args.effects)
        data, kin = model.createData(), model.createData()
        rng = np.random.default_rng(args.seed)
        rows = []
        for s in range(args.states):
            q = random_q(model, rng)
            v = rng.uniform(-2.0, 2.0, model.nv)
            a = rng.uniform(-2.0, 2.0, model.nv)
            if s >= args.states - args.static:
                v[:] = 0.0
                a[:] = 0.0
            rows.append(one_state(model, data, kin, q, v, a, free, s, args.seed, args.effects))
    except (ValueError, RuntimeError) as e:
        print(f"pinocchio_reference.py: {args.urdf}: {e}", file=sys.stderr)
        return 1
    for r in rows:
        assert len(r) == len(cols)
    out = sys.stdout if args.out == "-" else open(args.out, "w", encoding="utf-8")
    try:
        out.write(",".join(cols) + "\n")
        for r in rows:
            out.write(",".join(fmt(x) for x in r) + "\n")
    finally:
        if out is not sys.stdout:
            out.close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
