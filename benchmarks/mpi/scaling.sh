#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Time on many processes (docs/performance.md, "Many processes"), the median of REPEATS runs of
# each, one thread a process, against one process on as many threads; every run's output must be
# byte-identical to the first run's of its table.
#  - strong scaling, the flagship: examples/cavity_collapse, the plane run (HMX, self-contact,
#    the distance contact, four consistent-mass iterations) at CELL_MM to END_US (series.csv);
#  - strong scaling, the two-disk example (examples/sulsky_disks, elastic, single field, MUSL) at
#    DISK_CELL to 0.3 s (energy.csv);
#  - weak scaling, the two disks: P processes on about P times the particles, the cell 1 / N
#    with N the nearest whole number to sqrt(P) / DISK_CELL (the unit square holds whole cells;
#    energy.csv differs with the cell: each size against its own first run).
#
#   bash benchmarks/mpi/scaling.sh [BUILD] [REPEATS] [MAX_PROCESSES] [CELL_MM] [END_US] [DISK_CELL]
#
# BUILD: a configured and built release tree with MPI (default build/release); defaults 3
# repeats, 2 processes, the flagship at 0.5 mm to 10 us, the disks at 0.0025 m (160,000 particles).
set -euo pipefail
shopt -s inherit_errexit
build=${1:-build/release}
repeats=${2:-3}
most=${3:-2}
cell_mm=${4:-0.5}
end_us=${5:-10}
disk_cell=${6:-0.0025}
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
flagship="$build/examples/cavity_collapse/cavity_collapse"
disks="$build/examples/sulsky_disks/sulsky_disks"
[ -x "$flagship" ] && [ -x "$disks" ] || cmake --build "$build" --target cavity_collapse sulsky_disks
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl_vader_single_copy_mechanism=none
export OMP_WAIT_POLICY=passive
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# median LABEL FILE COMMAND...: runs COMMAND --output DIR REPEATS times; prints the median wall
# seconds; FILE (in DIR) must be byte-identical to the reference named by LABEL's table ($table).
median() {
    local label=$1 file=$2
    shift 2
    local times=()
    for r in $(seq "$repeats"); do
        local t0 t1
        rm -rf "$out/run"
        t0=$(date +%s.%N)
        "$@" --output "$out/run" >/dev/null
        t1=$(date +%s.%N)
        times+=("$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.3f", b - a }')")
        if [ -f "$out/$table.ref" ]; then
            cmp -s "$out/$table.ref" "$out/run/$file" || { echo "scaling.sh: $label: $file differs" >&2; exit 1; }
        else
            cp "$out/run/$file" "$out/$table.ref"
        fi
    done
    printf '%s\n' "${times[@]}" | sort -n | awk -v n="$repeats" '{ a[NR] = $1 } END { print a[int((n + 1) / 2)] }'
}
ratio() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", a / b }'; }

# strong TITLE FILE EXE ARG...: one process on one thread, then P processes and P threads.
strong() {
    local title=$1 file=$2 exe=$3
    shift 3
    table=$title
    echo "$title"
    echo "| run | median wall (s) | ratio to one process, one thread |"
    echo "| --- | --- | --- |"
    local one t
    one=$(median "$title, 1 process" "$file" "$exe" "$@" --threads 1)
    echo "| 1 process, 1 thread | $one | 1.00 |"
    for p in $(seq 2 "$most"); do
        t=$(median "$title, $p processes" "$file" mpirun -np "$p" --oversubscribe "$exe" "$@" --threads 1)
        echo "| $p processes, 1 thread each | $t | $(ratio "$t" "$one") |"
        t=$(median "$title, $p threads" "$file" "$exe" "$@" --threads "$p")
        echo "| 1 process, $p threads | $t | $(ratio "$t" "$one") |"
    done
    echo
}

strong "flagship, plane, ${cell_mm} mm to ${end_us} us" series.csv "$flagship" --cell "$cell_mm" --end-us "$end_us" \
    --snapshot-every-us 0 --quiet --no-figures
strong "two disks, ${disk_cell} m to 0.3 s" energy.csv "$disks" --cell "$disk_cell" --end-time 0.3

echo "two disks, weak: about P times the particles on P processes (cell 1 / round(sqrt(P) / ${disk_cell}))"
echo "| run | cell (m) | median wall (s) | ratio to one process |"
echo "| --- | --- | --- | --- |"
base=""
for p in $(seq 1 "$most"); do
    cell=$(awk -v c="$disk_cell" -v p="$p" 'BEGIN { printf "%.17g", 1 / int(sqrt(p) / c + 0.5) }')
    table="weak-$p"
    # P processes against one process on P threads, the same size.
    if [ "$p" = 1 ]; then
        t=$(median "weak, 1 process" energy.csv "$disks" --cell "$cell" --end-time 0.3 --threads 1)
        base=$t
        echo "| 1 process, 1 thread | $cell | $t | 1.00 |"
    else
        t=$(median "weak, $p processes" energy.csv mpirun -np "$p" --oversubscribe "$disks" --cell "$cell" --end-time 0.3 --threads 1)
        echo "| $p processes, 1 thread each | $cell | $t | $(ratio "$t" "$base") |"
        t=$(median "weak, $p threads" energy.csv "$disks" --cell "$cell" --end-time 0.3 --threads "$p")
        echo "| 1 process, $p threads | $cell | $t | $(ratio "$t" "$base") |"
    fi
done
echo
echo "every run's output byte-identical to the first of its table"
