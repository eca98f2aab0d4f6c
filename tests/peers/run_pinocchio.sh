#!/usr/bin/env bash
# The suite 'peers': vtdyn against Pinocchio (tests/peers/run_pinocchio.py) in the virtual
# environment of setup_venv.sh, which pip-installs pin and example-robot-data; skipped (exit
# 77, with the reason) when that cannot be done here.
#   run_pinocchio.sh COMPARE VTDYN WORKDIR
set -u
here=$(cd "$(dirname "$0")" && pwd)
py=$(bash "$here/setup_venv.sh") || exit 77
exec "$py" "$here/run_pinocchio.py" "$@"
