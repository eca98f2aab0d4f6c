#!/usr/bin/env bash
# The meson test 'python': `pip install .` of this source tree into the virtual environment of
# tests/peers (Pinocchio and example-robot-data, made or checked by tests/peers/setup_venv.sh),
# then pytest on tests/python. Skipped (exit 77, one line saying why) only where the venv or
# the packages the test needs cannot be had from the package index.
#
#   run.sh SOURCE_DIR WORK_DIR
#
# The package is built with --no-build-isolation by the venv's meson-python (installed here
# beside pytest, once) in WORK_DIR/pybuild, kept between runs: a rerun rebuilds only what changed.
set -u
src=$1
work=$2
mkdir -p "$work"
py=$(bash "$src/tests/peers/setup_venv.sh") || exit $?   # 77: skipped, the reason on stderr

skip() { echo "tests/python/run.sh: skipped: $*" >&2; exit 77; }
if ! "$py" -c 'import pytest, mesonpy' >/dev/null 2>&1; then
    log=$("$py" -m pip install --disable-pip-version-check --no-input --quiet --retries 1 --timeout 30 \
            pytest meson-python meson ninja 2>&1) || {
        last=$(printf '%s\n' "$log" | grep -v '^\s*$' | tail -n 1)
        if printf '%s' "$log" | grep -qiE 'connection|network|resolve|timed out|proxy|ssl|No matching distribution'; then
            skip "pip cannot reach the package index for pytest and meson-python: $last"
        fi
        echo "tests/python/run.sh: pip install pytest meson-python meson ninja failed: $last" >&2
        exit 1
    }
fi

echo "pip install $src (build directory $work/pybuild)"
if ! "$py" -m pip install --disable-pip-version-check --no-input --quiet --no-build-isolation --no-deps \
        --config-settings=build-dir="$work/pybuild" "$src" > "$work/pip.log" 2>&1; then
    tail -n 40 "$work/pip.log"
    echo "tests/python/run.sh: pip install of $src failed (log: $work/pip.log)" >&2
    exit 1
fi
cd "$work" || exit 1   # not the source tree: vtdyn is imported from the venv, not from python/
exec "$py" -m pytest -q -p no:cacheprovider "$src/tests/python"
