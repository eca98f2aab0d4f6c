#!/usr/bin/env bash
# The suite 'peers': a script of tests/peers (run_pinocchio.py: vtdyn against Pinocchio;
# mujoco_effects.py: against MuJoCo; check_qp.py: the distribution QP against quadprog) in the
# virtual environment of setup_venv.sh, which pip-installs pin, example-robot-data and mujoco
# (or, with VT_PEERS_SET=qp, quadprog alone); skipped (exit 77, with the reason) when that
# cannot be done here.
# VT_PEERS_OPTIONAL=qp also tries quadprog into the same venv and runs the script either way (it
# says what it skips without it).
#   [VT_PEERS_SET=qp] [VT_PEERS_OPTIONAL=qp] run_peer.sh SCRIPT.py ARGS...
set -u
here=$(cd "$(dirname "$0")" && pwd)
py=$(bash "$here/setup_venv.sh" "${VT_PEERS_SET:-robots}") || exit 77
if [ -n "${VT_PEERS_OPTIONAL:-}" ]; then
    bash "$here/setup_venv.sh" "$VT_PEERS_OPTIONAL" >/dev/null || echo "run_peer.sh: without $VT_PEERS_OPTIONAL" >&2
fi
script=$1
shift
exec "$py" "$here/$script" "$@"
