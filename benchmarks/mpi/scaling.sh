#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Time on many processes (docs/performance.md, "Many processes"): the two-disk example
# (examples/sulsky_disks, elastic, single field, MUSL) at a fine cell, on one process and on
# several, one thread each, and one process on as many threads; the median of REPEATS runs of
# each, and whether every run's energy.csv is byte-identical to the first's.
#
#   bash benchmarks/mpi/scaling.sh [BUILD] [CELL] [END_TIME] [REPEATS] [MAX_PROCESSES]
#
# BUILD: a configured and built release tree with MPI (default build/release); defaults 0.0025 m
# (160,000 particles), 0.3 s, 3 repeats, 2 processes.
set -euo pipefail
build=${1:-build/release}
cell=${2:-0.0025}
end=${3:-0.3}
repeats=${4:-3}
most=${5:-2}
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
exe="$build/examples/sulsky_disks/sulsky_disks"
[ -x "$exe" ] || cmake --build "$build" --target sulsky_disks
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_btl_vader_single_copy_mechanism=none
export OMP_WAIT_POLICY=passive
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# Runs "$@" REPEATS times; prints the median wall seconds; checks the output against the first run's.
median() {
    local label=$1
    shift
    local times=()
    for r in $(seq "$repeats"); do
        local t0 t1
        t0=$(date +%s.%N)
        "$@" --output "$out/run" >/dev/null
        t1=$(date +%s.%N)
        times+=("$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.3f", b - a }')")
        if [ -f "$out/reference.csv" ]; then
            cmp -s "$out/reference.csv" "$out/run/energy.csv" || { echo "scaling.sh: $label: energy.csv differs" >&2; exit 1; }
        else
            cp "$out/run/energy.csv" "$out/reference.csv"
        fi
    done
    printf '%s\n' "${times[@]}" | sort -n | awk -v n="$repeats" '{ a[NR] = $1 } END { print a[int((n + 1) / 2)] }'
}

echo "| run | median wall (s) | ratio to one process, one thread |"
echo "| --- | --- | --- |"
one=$(median "1 process" "$exe" --cell "$cell" --end-time "$end" --threads 1)
echo "| 1 process, 1 thread | $one | 1.00 |"
for p in $(seq 2 "$most"); do
    t=$(median "$p processes" mpirun -np "$p" --oversubscribe "$exe" --cell "$cell" --end-time "$end" --threads 1)
    echo "| $p processes, 1 thread each | $t | $(awk -v a="$t" -v b="$one" 'BEGIN { printf "%.2f", a / b }') |"
    t=$(median "$p threads" "$exe" --cell "$cell" --end-time "$end" --threads "$p")
    echo "| 1 process, $p threads | $t | $(awk -v a="$t" -v b="$one" 'BEGIN { printf "%.2f", a / b }') |"
done
echo "every run's energy.csv byte-identical to the first's"
