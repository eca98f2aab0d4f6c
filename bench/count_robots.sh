#!/bin/sh
# Instructions per call of every method of bench_inverse's robot rows (callgrind).
# usage: count_robots.sh <bench_inverse> <robots_dir> [calls]     (default 1000 calls)
#   e.g. sh bench/count_robots.sh build-bench/bench/bench_inverse "$robots_dir"
# Runs each robot's row alone (VT_BENCH_ONLY) with every method called `calls` times untimed
# (VT_BENCH_COUNT) under callgrind, and reads the inclusive instructions of the methods' entry
# points: run_motion (vtdyn_motion), Pinocchio's rnea (called by both of its methods: 2 calls
# times) and its robot_run (rnea_world = rnea + what robot_run adds over rnea, calls times),
# MuJoCo's robot_run. The few calls of the agreement check before the row (about 5 per method)
# are included: the figures are high by under 1 % at 1000 calls. Per body: divided by the
# number of joints (vtdyn's bodies; the free root counts as one).
set -eu
[ $# -ge 2 ] || { echo "usage: $0 <bench_inverse> <robots_dir> [calls]" >&2; exit 2; }
exe=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
dir=$2
calls=${3:-1000}
command -v valgrind >/dev/null || { echo "count_robots.sh: valgrind is needed" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "command: $0 $*"
printf "%-8s %6s %14s %14s %14s %14s   (instructions per call; per body in brackets)\n" robot bodies \
    vtdyn_motion pin_rnea pin_rnea_world mujoco_post
for row in "ur5 6" "panda 9" "solo12 13" "talos 33"; do
    set -- $row
    (cd "$tmp" && VT_BENCH_ONLY=$1 VT_BENCH_COUNT=$calls valgrind --tool=callgrind \
        --callgrind-out-file="$tmp/cg" "$exe" "$tmp" 1 "$dir" >/dev/null 2>&1) || { echo "$1: failed"; continue; }
    callgrind_annotate --inclusive=yes "$tmp/cg" >"$tmp/cg.txt" 2>/dev/null
    get() { grep -E "$1" "$tmp/cg.txt" | head -1 | awk '{gsub(",", "", $1); print $1 + 0}'; }
    mot=$(get ':run_motion ') # ???:run_motion, or bench_inverse.c:run_motion with debug information
    rnea=$(get 'pinocchio::rnea<')
    prun=$(get 'anonymous namespace[)]::robot_run')
    mrun=$(get '[^:]:robot_run ') # MuJoCo's (C): not Pinocchio's namespace::robot_run
    awk -v r="$1" -v b="$2" -v c="$calls" -v mot="$mot" -v rnea="$rnea" -v prun="$prun" -v mrun="$mrun" 'BEGIN {
        m = mot / c; p = rnea / (2 * c); w = p + (prun - rnea) / c; j = mrun / c
        printf "%-8s %6d %7.0f [%4.0f] %7.0f [%4.0f] %7.0f [%4.0f] %7.0f [%4.0f]\n", r, b, m, m / b, p, p / b, w, w / b, j, j / b
    }'
done
