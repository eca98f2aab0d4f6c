#!/usr/bin/env python3
"""Which URDF features a robot file uses: a scan of the XML (numpy and the standard library).

    python urdf_features.py FILE.urdf [FILE.urdf ...]

For each file prints: joints by type; mimic joints; joints with a rotated origin (rpy != 0);
axes that are not a unit coordinate axis (and not of unit length); limits (missing, infinite-
like, lower == upper); <dynamics> damping/friction; links without <inertial>; links with
zero mass; inertial origins with rpy != 0 and with xyz != 0; inertia matrices that are not
positive definite or that break the triangle inequality (principal moments a + b >= c) with
the worst margin; links attached by fixed joints (Pinocchio merges them into the parent
body) and of those the massive ones; the root link and whether it is "world"; the elements
other than link/joint at the top level (transmission, gazebo, material...); mesh file types.
"""
import collections
import sys
import xml.etree.ElementTree as ET

import numpy as np


def floats(text, n=3, default=0.0):
    if text is None:
        return [default] * n
    v = [float(x) for x in text.split()]
    return v if len(v) == n else v + [default] * (n - len(v))


def scan(path):
    root = ET.parse(path).getroot()
    out = collections.OrderedDict()
    joints = list(root.findall("joint"))
    links = list(root.findall("link"))
    types = collections.Counter(j.get("type") for j in joints)
    out["joints by type"] = dict(types)
    out["mimic joints (type)"] = [f'{j.get("name")} ({j.get("type")})' for j in joints
                                  if j.find("mimic") is not None]
    rot = [j.get("name") for j in joints
           if j.find("origin") is not None and any(floats(j.find("origin").get("rpy")))]
    out["joint origins with rpy != 0"] = f"{len(rot)} of {len(joints)}"
    odd_axes, nonunit = [], []
    for j in joints:
        if j.get("type") in ("fixed", "floating"):
            continue
        ax = np.array(floats(j.find("axis").get("xyz")) if j.find("axis") is not None
                      else [1.0, 0.0, 0.0])
        if abs(np.linalg.norm(ax) - 1.0) > 1e-12:
            nonunit.append((j.get("name"), ax.tolist()))
        if np.count_nonzero(np.abs(ax) > 1e-12) != 1:
            odd_axes.append((j.get("name"), ax.tolist()))
    missing_axis = [j.get("name") for j in joints
                    if j.get("type") not in ("fixed", "floating") and j.find("axis") is None]
    out["movable joints without <axis> (default 1 0 0)"] = missing_axis
    out["axes not along a coordinate axis"] = odd_axes
    out["axes not of unit length"] = nonunit
    lim = {"no <limit>": [], "lower == upper": [], "|limit| > 1e6": []}
    out["axes with a negative component"] = [
        j.get("name") for j in joints if j.find("axis") is not None
        and j.get("type") not in ("fixed", "floating") and min(floats(j.find("axis").get("xyz"))) < 0]
    for j in joints:
        t = j.get("type")
        if t in ("fixed", "floating", "planar"):
            continue
        L = j.find("limit")
        if L is None:
            if t != "continuous":
                lim["no <limit>"].append(j.get("name"))
            continue
        if t == "continuous":
            continue
        lo, hi = float(L.get("lower", 0)), float(L.get("upper", 0))
        if lo == hi:
            lim["lower == upper"].append(j.get("name"))
        if max(abs(lo), abs(hi)) > 1e6:
            lim["|limit| > 1e6"].append(j.get("name"))
    out["limits"] = {k: v for k, v in lim.items() if v}
    dyn = [j.get("name") for j in joints if j.find("dynamics") is not None
           and any(float(j.find("dynamics").get(k, 0)) for k in ("damping", "friction"))]
    out["joints with damping/friction != 0"] = len(dyn)
    parent_joint = {j.find("child").get("link"): j for j in joints}
    no_inertial, zero_mass, rpy, xyz, notpd, triangle = [], [], [], [], [], []
    worst = (np.inf, None)
    masses = {}
    for l in links:
        name = l.get("name")
        I = l.find("inertial")
        if I is None:
            no_inertial.append(name)
            masses[name] = 0.0
            continue
        m = float(I.find("mass").get("value")) if I.find("mass") is not None else 0.0
        masses[name] = m
        if m == 0.0:
            zero_mass.append(name)
        o = I.find("origin")
        if o is not None and any(floats(o.get("rpy"))):
            rpy.append(name)
        if o is not None and any(floats(o.get("xyz"))):
            xyz.append(name)
        it = I.find("inertia")
        if it is None:
            continue
        g = {k: float(it.get(k, 0)) for k in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")}
        J = np.array([[g["ixx"], g["ixy"], g["ixz"]], [g["ixy"], g["iyy"], g["iyz"]],
                      [g["ixz"], g["iyz"], g["izz"]]])
        if not J.any():
            continue
        e = np.linalg.eigvalsh(J)
        if e[0] <= 0:
            notpd.append((name, e.tolist()))
        margin = (e[0] + e[1] - e[2]) / max(e[2], 1e-300)  # >= 0 when the inequality holds
        if margin < worst[0]:
            worst = (margin, name)
        if margin < 0:
            triangle.append((name, float(margin)))
    out["links"] = len(links)
    out["links without <inertial>"] = no_inertial
    out["links with mass 0"] = zero_mass
    out["inertial origins with rpy != 0"] = f"{len(rpy)} of {len(links)}"
    out["inertial origins with xyz != 0"] = f"{len(xyz)} of {len(links)}"
    out["inertias not positive definite"] = notpd
    out["inertias off the triangle inequality (relative margin)"] = triangle
    out["worst triangle margin (a+b-c)/c"] = (f"{worst[0]:.3g} at {worst[1]}"
                                            if worst[1] else "no inertia")
    fixed_children = [c for c, j in parent_joint.items() if j.get("type") == "fixed"]
    out["links on fixed joints (merged by Pinocchio)"] = len(fixed_children)
    out["  of which with mass > 0"] = sum(masses.get(c, 0) > 0 for c in fixed_children)
    leaves_massless = [l.get("name") for l in links
                       if l.get("name") not in {j.find("parent").get("link") for j in joints}
                       and masses.get(l.get("name"), 0) == 0]
    out["massless leaf links (frames)"] = len(leaves_massless)
    movable_massless = [c for c, j in parent_joint.items()
                        if j.get("type") not in ("fixed",) and masses.get(c, 0) == 0]
    out["massless links on movable joints"] = movable_massless
    roots = [l.get("name") for l in links if l.get("name") not in parent_joint]
    out["root link"] = roots
    out["root link mass"] = [masses.get(r) for r in roots]
    out["other top-level elements"] = dict(collections.Counter(
        e.tag for e in root if e.tag not in ("link", "joint")))
    meshes = collections.Counter(
        m.get("filename", "").rsplit(".", 1)[-1].lower() for m in root.iter("mesh"))
    out["mesh types"] = dict(meshes)
    out["package:// URIs"] = sum(m.get("filename", "").startswith("package://")
                                 for m in root.iter("mesh"))
    out["total mass (all links)"] = round(sum(masses.values()), 9)
    return out


def main(argv):
    for path in argv:
        print(f"== {path}")
        for k, v in scan(path).items():
            print(f"  {k}: {v}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
