#!/bin/sh
# meson benchmark driver: runs a benchmark executable with outdir, then draws its charts.
# usage: run_bench.sh <bench executable> <outdir> <gnuplot script>
set -e
"$1" "$2"
if command -v gnuplot >/dev/null 2>&1; then
    gnuplot -e "dir='$2'" "$3"
    echo "charts written to $2"
else
    echo "gnuplot not found: no chart"
fi
