#!/bin/sh
# meson benchmark driver: runs a benchmark executable into outdir, then draws its chart.
# usage: run_bench.sh <bench executable> <outdir> <gnuplot script>
set -e
"$1" "$2"
if command -v gnuplot >/dev/null 2>&1; then
    gnuplot -e "csv='$2/inverse_speed.csv'; out='$2/inverse_speed.png'" "$3"
    echo "wrote $2/inverse_speed.png"
else
    echo "gnuplot not found: no chart"
fi
