#!/usr/bin/env bash
# Creates (if missing) the virtual environment of the Pinocchio reference scripts in
# tests/peers/ and installs pinned versions of Pinocchio (PyPI package `pin`),
# example-robot-data (the robots' URDFs and meshes) and MuJoCo (`mujoco`) into it; with the
# argument qp, only quadprog (`quadprog`, the distribution QP's peer, check_qp.py) into the
# same venv, so that either set is fetched, checked or skipped without the other.
#
#   tests/peers/setup_venv.sh            # prints the venv's python path on success
#   tests/peers/setup_venv.sh qp         # the same for quadprog
#
# Environment:
#   VT_PEERS_TEST_VENV   the venv's directory (default $HOME/.cache/vtdyn-peers/venv-test)
#   VT_PEERS_PYTHON      the interpreter that creates it (default python3, needs >= 3.9)
#
# Exit status: 0 and the python path on stdout when the venv has the pinned versions;
# 77 (meson's "skipped") with one line on stderr when the venv cannot be created, pip cannot
# reach the index or the install fails. When the pinned versions are already there it
# only checks them (no network, well under a second).
set -u

PIN_VERSION=4.1.0
ERD_VERSION=6.0.0
MUJOCO_VERSION=4.0.1
QUADPROG_VERSION=0.1.14  # wheels for CPython >= 3.11
SET=${1:-robots}
VENV=${VT_PEERS_TEST_VENV:-$HOME/.cache/vtdyn-peers/venv-test}
BASE_PYTHON=${VT_PEERS_PYTHON:-python3}
PY="$VENV/bin/python"

skip() { echo "setup_venv.sh: skipped: $*" >&2; exit 77; }

# The check: the distributions at the pinned versions, pinocchio and mujoco importable.
have_pinned() {
    [ -x "$PY" ] || return 1
    "$PY" - "$PIN_VERSION" "$ERD_VERSION" "$MUJOCO_VERSION" <<'PYEOF' >/dev/null 2>&1
import sys
from importlib.metadata import version
if (version("pin") != sys.argv[1] or version("example-robot-data") != sys.argv[2]
        or version("mujoco") != sys.argv[3]):
    sys.exit(1)
import pinocchio, mujoco, numpy  # noqa: F401
PYEOF
}

# quadprog alone (numpy comes with it, or is kept as the venv has it)
have_quadprog() {
    [ -x "$PY" ] || return 1
    "$PY" - "$QUADPROG_VERSION" <<'PYEOF' >/dev/null 2>&1
import sys
from importlib.metadata import version
if version("quadprog") != sys.argv[1]:
    sys.exit(1)
import quadprog, numpy  # noqa: F401
PYEOF
}

case "$SET" in
    robots) have_pinned && { echo "$PY"; exit 0; } ;;
    qp) have_quadprog && { echo "$PY"; exit 0; } ;;
    *) echo "setup_venv.sh: unknown set '$SET' (robots or qp)" >&2; exit 2 ;;
esac

# The peers' tests run at once (meson's processes) and may both install into the one venv:
# one at a time from here, the check repeated once the lock is held (flock, where there is one)
mkdir -p "$(dirname "$VENV")" 2>/dev/null || skip "cannot create $(dirname "$VENV")"
if command -v flock >/dev/null 2>&1 && exec 9>"$(dirname "$VENV")/.setup_venv.lock"; then
    flock 9
    case "$SET" in
        robots) have_pinned && { echo "$PY"; exit 0; } ;;
        qp) have_quadprog && { echo "$PY"; exit 0; } ;;
    esac
fi

if [ ! -x "$PY" ]; then
    command -v "$BASE_PYTHON" >/dev/null 2>&1 || skip "no $BASE_PYTHON to create $VENV"
    mkdir -p "$(dirname "$VENV")" 2>/dev/null || skip "cannot create $(dirname "$VENV")"
    log=$("$BASE_PYTHON" -m venv "$VENV" 2>&1) \
        || skip "cannot create the venv $VENV: $(printf '%s' "$log" | tail -n 1)"
fi

if [ "$SET" = qp ]; then
    log=$("$PY" -m pip install --disable-pip-version-check --no-input --quiet \
            --retries 1 --timeout 30 "quadprog==$QUADPROG_VERSION" 2>&1)
    if [ $? -ne 0 ]; then
        last=$(printf '%s\n' "$log" | grep -v '^\s*$' | tail -n 1)
        if printf '%s' "$log" | grep -qiE 'connection|network|resolve|timed out|proxy|ssl|No matching distribution'; then
            skip "pip cannot reach the package index or find quadprog==$QUADPROG_VERSION: $last"
        fi
        skip "pip install of quadprog==$QUADPROG_VERSION failed: $last"
    fi
    have_quadprog || skip "installed, but quadprog==$QUADPROG_VERSION does not import in $VENV"
    echo "$PY"
    exit 0
fi

log=$("$PY" -m pip install --disable-pip-version-check --no-input --quiet \
        --retries 1 --timeout 30 \
        "pin==$PIN_VERSION" "example-robot-data==$ERD_VERSION" "mujoco==$MUJOCO_VERSION" 2>&1)
status=$?
if [ $status -ne 0 ]; then
    last=$(printf '%s\n' "$log" | grep -v '^\s*$' | tail -n 1)
    if printf '%s' "$log" | grep -qiE 'connection|network|resolve|timed out|proxy|ssl|No matching distribution'; then
        skip "pip cannot reach the package index or find pin==$PIN_VERSION, mujoco==$MUJOCO_VERSION: $last"
    fi
    skip "pip install of pin==$PIN_VERSION example-robot-data==$ERD_VERSION mujoco==$MUJOCO_VERSION failed: $last"
fi

have_pinned || skip "installed, but pin==$PIN_VERSION / example-robot-data==$ERD_VERSION / mujoco==$MUJOCO_VERSION do not import in $VENV"
echo "$PY"
