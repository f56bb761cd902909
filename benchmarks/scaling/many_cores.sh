#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Strong scaling on a many-core machine (docs/performance.md, "Scaling to 16 threads"):
# what N threads give against one, and what the machine itself gives N independent
# one-thread processes. Run by scripts/bench.sh where there are 8 cores or more (or with
# --quick, at toy sizes, anywhere); by hand:
#
#   benchmarks/scaling/many_cores.sh BUILD_DIR [--quick]
#
# BUILD_DIR: a `bench` build with the flagship, as scripts/bench.sh makes it (`cmake --preset
# bench -DGIMLET_BUILD_EXAMPLES=ON -DGIMLET_EXAMPLES=cavity_collapse`). N is nproc, or
# GIMLET_CORES where set: on a machine with two hardware threads a core, set it to the cores.
#
# It prints, in order:
#   1. bench_ceilings on N threads (flops, triads, the synchronisation costs) under
#      OMP_WAIT_POLICY=passive, and the synchronisation line under active and unset;
#   2. bench_throughput at 1.02 M particles (0.125 mm, 15 steps, median of 3): one thread,
#      then N threads with OMP_WAIT_POLICY=passive and with active waiting and bound threads
#      (OMP_PROC_BIND=close OMP_PLACES=cores), each with its phases;
#   3. the machine's ceiling: one single-thread copy alone, then N at once, each pinned to a
#      core (taskset), with their rates and phases; their sum over the copy alone is what N
#      cores give perfectly parallel work of this kind;
#   4. the same as 2 at 64,000 particles (0.5 mm, 300 steps, median of 2);
#   5. the flagship, cavity_collapse at 0.25 mm (215,784 particles) to 12 us with the
#      quickstart's outputs (no figures), on 2 and N threads, with its summary line's split.
# Compare ratios within one run only: a machine's one-thread rate moves by 10-15 %. At 1.02 M
# particles the N copies need about N x 650 MB of memory.
set -euo pipefail

build="${1:?usage: many_cores.sh BUILD_DIR [--quick]}"
quick=0
[ "${2:-}" = "--quick" ] && quick=1
bench="$build/benchmarks/throughput/bench_throughput"
ceilings="$build/benchmarks/ceilings/bench_ceilings"
flagship="$build/examples/cavity_collapse/cavity_collapse"
n=${GIMLET_CORES:-$(nproc)}
for program in "$bench" "$ceilings" "$flagship"; do
    [ -x "$program" ] || { echo "many_cores.sh: $program is missing (see the header for the build)" >&2; exit 2; }
done
command -v taskset >/dev/null || echo "many_cores.sh: no taskset: the copies are not pinned to cores"
if [ "$quick" = 1 ]; then
    big=(--cell 2 --steps 3); small=(--cell 2 --steps 3); fine=(--cell 2 --end-us 2); ceil=(--quick 1)
    copies=$(( n < 2 ? n : 2 ))
else
    big=(--cell 0.125 --steps 15); small=(--cell 0.5 --steps 300); fine=(--cell 0.25 --end-us 12); ceil=()
    copies=$n
fi
passive=(env OMP_WAIT_POLICY=passive)
active=(env OMP_WAIT_POLICY=active OMP_PROC_BIND=close OMP_PLACES=cores)
pin() { if command -v taskset >/dev/null; then taskset -c "$1" "${@:2}"; else "${@:2}"; fi; }

echo "many-core scaling: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), $n cores"
echo "== 1. bench_ceilings on $n threads"
"${passive[@]}" "$ceilings" --threads "$n" "${ceil[@]}"
echo "synchronisation, OMP_WAIT_POLICY=active: $(env OMP_WAIT_POLICY=active "$ceilings" --threads "$n" --quick 1 | grep synchron)"
echo "synchronisation, OMP_WAIT_POLICY unset: $(env -u OMP_WAIT_POLICY "$ceilings" --threads "$n" --quick 1 | grep synchron)"

throughput() {  # throughput LABEL REPEATS ARGS...: 1 thread, N passive, N active and bound
    local label=$1 repeats=$2; shift 2
    echo "== $label (each run: its phases, P2G's parts, its CSV row: scene, scheme, cell_mm, particles, steps, threads, repeats, median_s, min_s, mups_median, mups_best, consistent_mass)"
    for scene in reference hmx; do
        echo "-- $scene, 1 thread";             "${passive[@]}" "$bench" --scene "$scene" "$@" --repeats "$repeats" --threads 1 --phases 1 2>&1
        echo "-- $scene, $n threads, passive";  "${passive[@]}" "$bench" --scene "$scene" "$@" --repeats "$repeats" --threads "$n" --phases 1 2>&1
        echo "-- $scene, $n threads, active, bound"; "${active[@]}" "$bench" --scene "$scene" "$@" --repeats "$repeats" --threads "$n" --phases 1 2>&1
    done
}
throughput "2. bench_throughput, ${big[*]}" 3 "${big[@]}"

echo "== 3. one-thread copies: one alone, then $copies at once, each pinned to a core"
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
for scene in reference hmx; do
    for k in 1 "$copies"; do
        pids=()
        for i in $(seq 0 $((k - 1))); do
            pin "$i" "${passive[@]}" "$bench" --scene "$scene" "${big[@]}" --repeats 2 --threads 1 --phases 1 \
                >"$scratch/copy_$i.txt" 2>&1 &
            pids+=($!)
        done
        for pid in "${pids[@]}"; do wait "$pid" || echo "many_cores.sh: a copy failed (its output below)"; done
        echo "-- $scene, $k at once (each copy: its phases, P2G's parts, its CSV row)"
        for i in $(seq 0 $((k - 1))); do echo "copy $i"; cat "$scratch/copy_$i.txt"; done
    done
done

throughput "4. bench_throughput, ${small[*]}" 2 "${small[@]}"

echo "== 5. the flagship, ${fine[*]}, the quickstart's outputs, no figures"
for t in 2 "$n"; do
    rm -rf "$scratch/flagship"
    start=$(date +%s.%N)
    "${passive[@]}" "$flagship" --velocity 300 --radius 10 "${fine[@]}" --snapshot-every-us 0 \
        --snapshots-after-contact-us 4,6,8,12,14,20,24,25,30 --no-figures --threads "$t" --quiet \
        --output "$scratch/flagship" >"$scratch/flagship.txt" 2>&1 || echo "many_cores.sh: the flagship failed:"
    grep "steps in" "$scratch/flagship.txt" | sed "s/^ */$t threads, passive: /" || cat "$scratch/flagship.txt"
    echo "$t threads, whole process: $(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.2f", b - a }') s"
done
