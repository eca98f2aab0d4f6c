#!/usr/bin/env bash
# Installs the benchmark peers (MuJoCo, Pinocchio) from PyPI into a Python virtual environment
# and prints the settings the Meson build and the benchmark need:
#   mujoco_dir=<dir with include/mujoco/mujoco.h and libmujoco.so.*>
#   pinocchio_prefix=<site-packages/cmeel.prefix: Pinocchio, Eigen and Boost headers>
#   robots_dir=<example-robot-data's robots directory: the URDFs of the robot rows>
#
#   bash bench/peers/install.sh
#   eval "$(bash bench/peers/install.sh | grep '=')"    # to get all three as shell variables
#   meson setup build-bench -Dbuildtype=release -Dmujoco_dir="$mujoco_dir" -Dpinocchio_prefix="$pinocchio_prefix"
#
# Environment:
#   VT_PEERS_VENV      the virtual environment (default $HOME/.cache/vtdyn-peers/venv)
#   VT_PEERS_PYTHON    the Python that creates it (default python3; needs the venv module)
#   VT_PEERS_PACKAGES  the pip requirement list (default: the versions the peers were written and
#                      checked against; "mujoco pin cmeel-eigen example-robot-data" takes the newest)
#
# The wheels: mujoco puts its headers in site-packages/mujoco/include/mujoco/ and libmujoco.so.*
# beside them in site-packages/mujoco/; pin (Pinocchio) puts its headers in
# site-packages/cmeel.prefix/include, with Eigen (cmeel-eigen) and Boost (cmeel-boost, a
# dependency of pin) under the same prefix. Only headers of Pinocchio are used, no library.
# example-robot-data puts the robots' URDFs (and meshes, unused) in
# site-packages/cmeel.prefix/share/example-robot-data/robots/; found through the distribution's
# file list, as tests/peers/*.py do. The benchmark reads them at run time (VT_BENCH_ROBOTS).
set -euo pipefail

venv="${VT_PEERS_VENV:-$HOME/.cache/vtdyn-peers/venv}"
python="${VT_PEERS_PYTHON:-python3}"
packages="${VT_PEERS_PACKAGES:-mujoco==4.0.0 pin==4.1.0 cmeel-eigen==3.4.1 example-robot-data==6.0.0}"

if [ ! -x "$venv/bin/python" ]; then
    mkdir -p "$(dirname "$venv")"
    "$python" -m venv "$venv"
fi
# shellcheck disable=SC2086  # the package list is meant to split
"$venv/bin/python" -m pip install --disable-pip-version-check $packages >&2

site="$("$venv/bin/python" -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')"

mujoco_dir="$site/mujoco"
if [ ! -f "$mujoco_dir/include/mujoco/mujoco.h" ] || ! compgen -G "$mujoco_dir/libmujoco.so*" >/dev/null; then
    echo "install.sh: no include/mujoco/mujoco.h and libmujoco.so* in $mujoco_dir" >&2
    exit 1
fi
pinocchio_prefix="$site/cmeel.prefix"
for f in include/pinocchio/algorithm/rnea.hpp include/eigen3/Eigen/Core include/boost/variant.hpp; do
    if [ ! -f "$pinocchio_prefix/$f" ]; then
        echo "install.sh: no $f in $pinocchio_prefix" >&2
        exit 1
    fi
done

robots_dir="$("$venv/bin/python" - <<'PYEOF'
from importlib.metadata import PackageNotFoundError, distribution
from pathlib import Path
try:
    dist = distribution("example-robot-data")
except PackageNotFoundError:
    raise SystemExit(0)
urdfs = [Path(dist.locate_file(f)) for f in dist.files or [] if str(f).endswith(".urdf")]
if urdfs:
    parts = urdfs[0].parts
    print(Path(*parts[: parts.index("robots") + 1]), end="")
PYEOF
)"
[ -n "$robots_dir" ] || echo "install.sh: no example-robot-data URDFs: the robot rows will be skipped" >&2

echo "mujoco_dir=$mujoco_dir"
echo "pinocchio_prefix=$pinocchio_prefix"
echo "robots_dir=$robots_dir"
