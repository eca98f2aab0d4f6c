#!/bin/sh
# A/B speed of two trees of vtdyn in one process (see the comment at the top of ab.c).
# usage: run.sh <treeA> <treeB> [rounds]   e.g. bash bench/ab/run.sh ../vtdyn-old .
# Builds both shared objects (build.sh) and the driver into a temporary directory, then runs
# the driver pinned to CPU 1.
set -eu
[ $# -ge 2 ] || { echo "usage: $0 <treeA> <treeB> [rounds]" >&2; exit 2; }
here=$(cd "$(dirname "$0")" && pwd)
cc=${CC:-cc}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

echo "command: $0 $*"
for t in "$1" "$2"; do
    rev=$(git -C "$t" rev-parse --short HEAD 2>/dev/null || echo "?")
    dirty=$(git -C "$t" status --porcelain --untracked-files=no 2>/dev/null | wc -l)
    echo "tree $t: commit $rev, $dirty modified tracked file(s)"
done
echo "cc: $($cc --version | head -1)"
sh "$here/build.sh" "$1" "$tmp/A.so"
sh "$here/build.sh" "$2" "$tmp/B.so"
$cc -std=c11 -O2 -Wall -Wextra -o "$tmp/ab" "$here/ab.c" -ldl -lm
echo
taskset -c 1 "$tmp/ab" "$tmp/A.so" "$tmp/B.so" "${3:-41}" "$1" "$2"
