#!/usr/bin/env bash
# examples/sweep.c under MPI: the MPI build run as a single process, and under mpirun with 1, 2
# and 3 ranks (3 does not divide the grid evenly), must write the byte-identical CSV of the
# build without MPI. Skips (exit 77, meson's "skipped") when vtdyn was built without MPI or
# mpirun is missing. Open MPI refuses root without --allow-run-as-root and more ranks than
# cores without --oversubscribe; both are passed to it (not to other MPIs' mpirun).
# Usage: sweep_mpi.sh <sweep built with MPI, or "none"> <sweep without MPI> <scratch directory>
set -euo pipefail
mpi_sweep=$1 serial_sweep=$2 dir=$3/sweep_mpi
if [ "$mpi_sweep" = none ]; then
    echo "sweep_mpi: skipped, vtdyn was configured without MPI (Debian: apt-get install libopenmpi-dev openmpi-bin, then reconfigure)"
    exit 77
fi
if ! command -v mpirun > /dev/null; then
    echo "sweep_mpi: skipped, no mpirun in PATH"
    exit 77
fi
mpirun=(mpirun)
if grep -q "Open MPI" <<< "$(mpirun --version 2>&1)"; then
    mpirun+=(--oversubscribe)
    [ "$(id -u)" -ne 0 ] || mpirun+=(--allow-run-as-root)
    # no ssh for a local run, and no cross-memory attach (refused in many containers)
    export OMPI_MCA_plm_rsh_agent="" OMPI_MCA_btl_vader_single_copy_mechanism=none
fi
mkdir -p "$dir"
grid=(-m 5 -M 2 -p 3 -t 0.5,2 -s 24)   # 15 grid points
"$serial_sweep" "${grid[@]}" -o "$dir/serial.csv" > /dev/null
"$mpi_sweep" "${grid[@]}" -o "$dir/mpi_singleton.csv" > /dev/null
for n in 1 2 3; do
    "${mpirun[@]}" -n "$n" "$mpi_sweep" "${grid[@]}" -o "$dir/mpi_$n.csv" > "$dir/mpi_$n.log" 2>&1 ||
        { cat "$dir/mpi_$n.log"; echo "sweep_mpi: mpirun -n $n failed"; exit 1; }
done
status=0
for f in mpi_singleton mpi_1 mpi_2 mpi_3; do
    if cmp "$dir/serial.csv" "$dir/$f.csv"; then
        echo "sweep_mpi: $f.csv identical to serial.csv ($(wc -l < "$dir/serial.csv") lines)"
    else
        echo "sweep_mpi: $f.csv differs from serial.csv"
        diff "$dir/serial.csv" "$dir/$f.csv" | head -5 || true
        status=1
    fi
done
grep -q "3 ranks" "$dir/mpi_3.log" || { echo "sweep_mpi: mpirun -n 3 did not run 3 ranks:"; cat "$dir/mpi_3.log"; status=1; }
exit $status
