#!/bin/sh
# Instructions per recursive instant of two trees of vtdyn (callgrind; see count.c).
# usage: count.sh <treeA> <treeB> [calls]   e.g. bash bench/ab/count.sh ../vtdyn-old .
# Builds both objects as run.sh does (build.sh: release, -march=native), then for each scene
# prints the instructions per call of A and B, per body (n), and B/A.
set -eu
[ $# -ge 2 ] || { echo "usage: $0 <treeA> <treeB> [calls]" >&2; exit 2; }
here=$(cd "$(dirname "$0")" && pwd)
cc=${CC:-cc}
calls=${3:-1000}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
command -v valgrind >/dev/null || { echo "count.sh: valgrind is needed" >&2; exit 1; }
echo "command: $0 $*"
sh "$here/build.sh" "$1" "$tmp/A.so"
sh "$here/build.sh" "$2" "$tmp/B.so"
$cc -std=c11 -O2 -Wall -Wextra -o "$tmp/count" "$here/count.c" -ldl
ir() { # instructions of `calls` instants of object $1 on scene $2, n $3
    valgrind --tool=callgrind --toggle-collect=ab_batch --callgrind-out-file=/dev/null \
        "$tmp/count" "$1" "$2" "$3" "$calls" 2>&1 | sed -n 's/.*Collected : *\([0-9]*\).*/\1/p'
}
printf "%-13s %4s %12s %12s %10s %10s %7s\n" scene n "A Ir/call" "B Ir/call" "A Ir/body" "B Ir/body" "B/A"
for s in "chain 2" "chain 5" "chain 10" "chain 50" "chain 200" "double_link 2" "fourbar 3" "fourbar_rusr 4" \
         "chain_tip 10" "chain_tip 20" "five_link 5" "delta 21" "stewart 24" "knee 4"; do
    set -- $s
    a=$(ir "$tmp/A.so" "$1" "$2"); b=$(ir "$tmp/B.so" "$1" "$2")
    if [ -z "$a" ] || [ -z "$b" ]; then echo "$1 $2: skipped (scene missing or failed)"; continue; fi
    awk -v s="$1" -v n="$2" -v a="$a" -v b="$b" -v c="$calls" \
        'BEGIN { printf "%-13s %4d %12.0f %12.0f %10.0f %10.0f %7.3f\n", s, n, a / c, b / c, a / c / n, b / c / n, b / a }'
done
