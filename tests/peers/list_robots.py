#!/usr/bin/env python3
"""List every URDF that example-robot-data ships and whether Pinocchio loads it.

    python list_robots.py [OUT.csv]       (default: stdout)

Finds the URDFs through the installed distribution's file list
(importlib.metadata.distribution("example-robot-data")): with the PyPI wheel they lie under
site-packages/cmeel.prefix/share/example-robot-data/robots/. Prints that directory on stderr.

Columns of OUT.csv (one header line, one row per URDF, sorted by path):
    path              relative to the robots directory, e.g. ur_description/urdf/ur5_robot.urdf
    root_link         the URDF's root link (the one link that is no joint's child)
    floating_base     1 when the root link is not a "world" link (Pinocchio's notion: a model
                      loaded without a root joint then has the root link welded to the
                      universe, so such a robot is meant to get a free flyer), 0 when the root
                      link is named "world" (the robot is bolted to the world in the URDF)
    urdf_joints       number of <joint> elements, all types (fixed ones included)
    fixed_ok          1 when pin.buildModelFromUrdf(path) succeeds, else 0
    fixed_njoints, fixed_nq, fixed_nv   model.njoints (universe included), nq, nv; empty on failure
    ff_ok             1 when pin.buildModelFromUrdf(path, pin.JointModelFreeFlyer()) succeeds
    ff_njoints, ff_nq, ff_nv            the same for that model
    error             the first failure's message (commas and newlines replaced), else empty
"""
import sys
import xml.etree.ElementTree as ET
from importlib.metadata import distribution
from pathlib import Path

import pinocchio as pin


def robots_dir_and_urdfs():
    dist = distribution("example-robot-data")
    urdfs = [Path(dist.locate_file(f)) for f in dist.files or [] if str(f).endswith(".urdf")]
    if not urdfs:
        raise SystemExit("list_robots.py: example-robot-data lists no .urdf file")
    parts = urdfs[0].parts
    root = Path(*parts[:parts.index("robots") + 1])
    return root, sorted(urdfs)


def root_link(path):
    tree = ET.parse(path).getroot()
    links = [l.get("name") for l in tree.iter("link")]
    children = {j.find("child").get("link") for j in tree.iter("joint")
                if j.find("child") is not None}
    roots = [l for l in links if l not in children]
    return (roots[0] if len(roots) == 1 else "|".join(roots)), len(list(tree.iter("joint")))


def try_load(path, ff):
    try:
        m = (pin.buildModelFromUrdf(str(path), pin.JointModelFreeFlyer()) if ff
             else pin.buildModelFromUrdf(str(path)))
        return (1, m.njoints, m.nq, m.nv), ""
    except Exception as e:  # Pinocchio raises ValueError or RuntimeError
        return (0, "", "", ""), f"{type(e).__name__}: {e}"


def clean(text):
    return " ".join(str(text).replace(",", ";").split())


def main(argv):
    robots, urdfs = robots_dir_and_urdfs()
    print(f"list_robots.py: robots directory {robots}", file=sys.stderr)
    rows = []
    for path in urdfs:
        try:
            rl, nj = root_link(path)
        except ET.ParseError as e:
            rl, nj = "", ""
            xml_error = f"XML: {e}"
        else:
            xml_error = ""
        floating = "" if not rl else int(rl != "world")
        fixed, err_f = try_load(path, False)
        free, err_ff = try_load(path, True)
        error = xml_error or err_f or err_ff
        rows.append([path.relative_to(robots).as_posix(), rl, floating, nj, *fixed, *free,
                     clean(error)])
    header = ["path", "root_link", "floating_base", "urdf_joints", "fixed_ok", "fixed_njoints",
              "fixed_nq", "fixed_nv", "ff_ok", "ff_njoints", "ff_nq", "ff_nv", "error"]
    out = open(argv[0], "w", encoding="utf-8") if argv else sys.stdout
    out.write(",".join(header) + "\n")
    for r in rows:
        out.write(",".join(str(x) for x in r) + "\n")
    if out is not sys.stdout:
        out.close()
    n = len(rows)
    print(f"list_robots.py: {n} URDFs; {sum(r[2] == 1 for r in rows)} with a floating base; "
          f"Pinocchio loads {sum(r[4] for r in rows)} without a root joint and "
          f"{sum(r[8] for r in rows)} with a free flyer", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
