#!/usr/bin/env bash
# The command's speed against the library's (not a timed test): ROWS random states of UR5 (its
# base fixed) and of Solo-12 (a quadruped, floating: --floating) (bench/command_states.py: the same numbers as CSV and as .npy), `vtdyn inverse` timed on
# csv->csv, npy->npy, npy to /dev/null (the command without the file system's writing), csv->npy
# and npy->csv with -j 1 and -j 2, and UR5's samples (t and positions) csv->csv and npy->npy (the
# median of ROUNDS runs, the process's wall time, the
# output's bytes checked equal for both), beside the library's own time per row on the same
# states (bench/command_lib.c: one vt_batch_inverse_dynamics_motion over every row with the
# outputs the command writes, the median of ROUNDS calls). Prints the date, the CPU, the load,
# the commit, then per case: µs per row, the ratio to the library at the same threads, the split
# of the median run (--times: reading, solving, writing), and -j 2's speed-up over -j 1. Each
# run starts after a sync (not timed), so that what the runs before wrote is on the disk.
#
#   bench/bench_command.sh [BUILD_DIR] [ROWS] [ROUNDS]     (build, 100000, 5)
#
# The URDF files: VT_BENCH_UR5 and VT_BENCH_SOLO12, else example-robot-data's in the virtual
# environment of the suite 'peers' (tests/peers/setup_venv.sh installs it; exit 77 when it cannot).
set -euo pipefail
src=$(cd "$(dirname "$0")/.." && pwd)
build=$(cd "${1:-$src/build}" && pwd)
rows=${2:-100000}
rounds=${3:-5}
vtdyn=$build/cmd/vtdyn
[ -x "$vtdyn" ] || { echo "bench_command.sh: no $vtdyn (build with URDF loading first)"; exit 1; }

ur5=${VT_BENCH_UR5:-}
solo=${VT_BENCH_SOLO12:-}
if [ -z "$ur5" ] || [ -z "$solo" ]; then
    py=$(bash "$src/tests/peers/setup_venv.sh") || { echo "bench_command.sh: no example-robot-data (set VT_BENCH_UR5 and VT_BENCH_SOLO12)"; exit 77; }
    robot() {
        "$py" - "$1" <<'PYEOF'
import sys
from importlib.metadata import distribution
d = distribution("example-robot-data")
print(next(str(d.locate_file(f)) for f in d.files if str(f).endswith(sys.argv[1])))
PYEOF
    }
    [ -n "$ur5" ] || ur5=$(robot ur_description/urdf/ur5_robot.urdf)
    [ -n "$solo" ] || solo=$(robot solo_description/robots/solo12.urdf)
fi

tmp=$(mktemp -d "${TMPDIR:-/tmp}/vtdyn-bench-command.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
${CC:-cc} -O2 -std=c11 -I"$src/include" -I"$build/include" "$src/bench/command_lib.c" -L"$build" -lvtdyn -lm \
    -Wl,-rpath,"$build" -o "$tmp/command_lib"

echo "date: $(date -u +%Y-%m-%d)"
echo "cpu: $(lscpu | sed -n 's/^Model name: *//p'), $(nproc) CPUs the process may use"
echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "commit: $(git -C "$src" rev-parse --short HEAD 2>/dev/null || echo '?')"
echo "command: bench/bench_command.sh $build $rows $rounds"

median() { sort -g | awk '{ a[NR] = $1 } END { print a[int((NR + 1) / 2)] }'; }

# one robot: bench <name> <urdf> [--floating]
bench() {
    local name=$1 urdf=$2 flag=${3:-}
    python3 "$src/bench/command_states.py" "$vtdyn" "$urdf" "$rows" "$tmp/states.csv" "$tmp/states.npy" $flag
    echo
    echo "== $name${flag:+ ($flag)}: $rows states, $(du -h "$tmp/states.csv" | cut -f1) CSV, $(du -h "$tmp/states.npy" | cut -f1) .npy"
    for j in 1 2; do
        lib[$j]=$(for r in $(seq "$rounds"); do "$tmp/command_lib" "$urdf" "$tmp/states.npy" "$j" 3 $flag; done | median)
        printf "library, -j %d: %.3f us/row (vt_batch_inverse_dynamics_motion, effort and reactions)\n" "$j" "${lib[$j]}"
    done

    cases "$urdf" states "csv:csv npy:npy npy:null csv:npy npy:csv" $flag
}

# the command timed on $tmp/<stem>.<in> for each in:out of the list, -j 1 and -j 2 (the median of
# ROUNDS runs), beside the library's time at the same threads (lib): cases <urdf> <stem> <list> [flag]
cases() {
    local urdf=$1 stem=$2 list=$3 flag=${4:-}
    printf "\n%-14s %3s %10s %9s %s\n" "case" "-j" "us/row" "x library" "split of the median run (--times)"
    TIMEFORMAT=%3R
    for case in $list; do
        in=${case%:*} out=${case#*:}
        declare -A per=()
        label="$in->$out"
        [ "$out" = null ] && label="npy->/dev/null"
        for j in 1 2; do
            : > "$tmp/runs"
            for r in $(seq "$rounds"); do
                rm -f "$tmp/out_$j.$out"
                # the runs before written back first: their dirty pages would throttle this one's
                sync
                if [ "$out" = null ]; then # the command alone: npy on standard output, to /dev/null
                    t=$({ time "$vtdyn" inverse $flag -j "$j" --times --format npy "$urdf" "$tmp/$stem.$in" > /dev/null 2> "$tmp/times"; } 2>&1)
                else
                    t=$({ time "$vtdyn" inverse $flag -j "$j" --times "$urdf" "$tmp/$stem.$in" -o "$tmp/out_$j.$out" 2> "$tmp/times"; } 2>&1)
                fi
                echo "$t $(sed -n 's/.*: read/read/p' "$tmp/times")" >> "$tmp/runs"
            done
            mid=$(sort -n "$tmp/runs" | awk -v n="$rounds" 'NR == int((n + 1) / 2)')
            us=$(awk -v t="${mid%% *}" -v n="$rows" 'BEGIN { printf "%.3f", 1e6 * t / n }')
            per[$j]=$us
            printf "%-14s %3d %10s %9.2f %s\n" "$label" "$j" "$us" "$(awk -v a="$us" -v b="${lib[$j]}" 'BEGIN { print a / b }')" \
                "${mid#* }"
        done
        if [ "$out" != null ]; then
            cmp -s "$tmp/out_1.$out" "$tmp/out_2.$out" || { echo "bench_command.sh: -j 1 and -j 2 wrote different bytes ($stem $case)"; exit 1; }
        fi
        printf "%-14s     -j 2 is %.2f times as fast as -j 1\n" "$label" "$(awk -v a="${per[1]}" -v b="${per[2]}" 'BEGIN { print a / b }')"
    done
}

# samples of UR5 (t and the joints' positions: the splines' rates and accelerations, then the
# states' batch), csv->csv and npy->npy, beside the library's time on states
samples() {
    local name=$1 urdf=$2
    python3 "$src/bench/command_states.py" "$vtdyn" "$urdf" "$rows" "$tmp/samples.csv" "$tmp/samples.npy" --samples
    echo
    echo "== $name samples (t and positions, 1 ms apart): $rows rows, $(du -h "$tmp/samples.csv" | cut -f1) CSV"
    cases "$urdf" samples "csv:csv npy:npy"
}

declare -A lib
bench UR5 "$ur5"
samples UR5 "$ur5"
bench Solo-12 "$solo" --floating
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
