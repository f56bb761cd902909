#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Build the benchmarks (`bench` preset) and run them all: the machine's ceilings, the material
# update with two particles per vector, throughput (the reference scene and the 2-D HMX step,
# 1 and 2 threads, scaling with particle count), the per-phase roofline, strong scaling to the
# machine's cores where it has 8 or more (benchmarks/scaling/many_cores.sh), the cost of each
# effect, accuracy against time, the flagship's outputs against outputs off, and its serial
# share on 2 threads (benchmarks/scaling/serial_share.py, where perf may sample). CSVs and
# Markdown tables go to results/bench/, plots to docs/perf_*.png (drawn with Debian's
# /usr/bin/python3, which has matplotlib).
#
#   scripts/bench.sh            the full run (20-40 minutes on a 2-core machine)
#   scripts/bench.sh --quick    a smoke run of every benchmark (a minute)
#
# The machine's load average is recorded before and after each benchmark: timings on a busy
# machine are not comparable, so check results/bench/load.txt before trusting a table.
set -euo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"
quick=0
[ "${1:-}" = "--quick" ] && quick=1

# What the run needs (the compiler, Eigen, matplotlib for the plots, valgrind and objdump for
# the per-phase roofline): installed where missing. Where that is not possible (no apt, not
# root and no sudo) the run goes on with what is there, and says what it skips.
bash scripts/setup.sh --bench >/dev/null || echo "bench.sh: scripts/setup.sh --bench failed (above); going on with what is installed" >&2
build="${GIMLET_BENCH_BUILD:-build/bench}"
out="${GIMLET_BENCH_OUTPUT:-results/bench}"
# The flagship too (and no other example): its outputs are timed against outputs off below.
cmake --preset bench -B "$build" -DGIMLET_BUILD_EXAMPLES=ON -DGIMLET_EXAMPLES=cavity_collapse >/dev/null
cmake --build "$build" -j2
mkdir -p "$out"
bin="$build/benchmarks"

{
    echo "date: $(date -u +%Y-%m-%dT%H:%MZ)"
    echo "cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs), $(nproc) cores"
    echo "memory: $(free -g | awk '/Mem:/ {print $2}') GiB"
    echo "compiler: $(c++ --version | head -1)"
    echo "flags: bench preset (-O3 -DNDEBUG, no -march=native), OpenMP"
    echo "commit: $(git rev-parse --short HEAD)$(git diff --quiet HEAD -- include benchmarks || echo ' (modified)')"
} > "$out/machine.txt"
: > "$out/load.txt"
load() { echo "$1: $(cut -d' ' -f1-3 /proc/loadavg)" >> "$out/load.txt"; }

# OMP_WAIT_POLICY=passive: a waiting thread sleeps instead of spinning, which costs little on
# an idle machine and avoids long stalls when another process holds a core.
export OMP_WAIT_POLICY="${OMP_WAIT_POLICY:-passive}"

if [ "$quick" = 1 ]; then
    ref_args=(--cell 2 --steps 10 --repeats 1)
    sizes=(2 1)
    eff_args=(--cell 4 --steps 5 --repeats 1)
    acc_args=(--quick 1)
    ceil_args=(--quick 1)
    lanes_args=(--repeats 1 --cell 2)
    roof_args=(--runs 1 --steps 5 --short 1 --long 2 --cell 2 --quick)
else
    ref_args=(--cell 0.5 --steps 1000 --repeats 3)
    sizes=(2 1 0.5 0.25 0.125)
    eff_args=(--cell 1 --steps 300 --repeats 5)
    acc_args=()
    ceil_args=()
    lanes_args=()
    roof_args=()
fi

# The machine's ceilings (floating-point throughput and bandwidth) that docs/performance.md's
# per-phase table compares the step with.
load "ceilings start"
"$bin/ceilings/bench_ceilings" "${ceil_args[@]}" | tee "$out/ceilings.md"
load "ceilings end / lanes start"
# The elastic material update with two particles per vector, against the library's (a lever's
# measure: docs/performance.md, "Two particles per vector").
"$bin/lanes/bench_lanes" "${lanes_args[@]}" | tee "$out/lanes.md"
load "lanes end / throughput start"
{
    "$bin/throughput/bench_throughput" --header 1 --scene reference --threads 1 "${ref_args[@]}"
    for scene in reference hmx; do
        for t in 1 2; do
            [ "$scene $t" = "reference 1" ] && continue
            "$bin/throughput/bench_throughput" --scene "$scene" --threads "$t" "${ref_args[@]}"
        done
    done
} | tee "$out/throughput.csv"
for t in 1 2; do
    "$bin/throughput/bench_throughput" --scene reference --threads "$t" --cell 0.5 --steps "${ref_args[3]}" \
        --repeats 1 --phases 1 2>&1 >/dev/null | sed "s/^/reference, $t threads: /"
    "$bin/throughput/bench_throughput" --scene hmx --threads "$t" --cell 0.5 --steps "${ref_args[3]}" \
        --repeats 1 --phases 1 2>&1 >/dev/null | sed "s/^/hmx, $t threads: /"
done | tee "$out/phases.txt"
load "throughput end / roofline start"
# The per-phase roofline (docs/performance.md, "What bounds each phase"): each phase's time
# (solver::timings()) against its work (callgrind's counts) and this run's ceilings.
if command -v valgrind >/dev/null && command -v objdump >/dev/null; then
    python3 benchmarks/roofline/roofline.py "$bin/throughput/bench_throughput" "$bin/ceilings/bench_ceilings" \
        "${roof_args[@]}" | tee "$out/roofline.md"
else
    echo "bench.sh: no valgrind or objdump: the per-phase roofline is skipped (scripts/setup.sh --bench installs them)" \
        | tee "$out/roofline.md"
fi
load "roofline end / many cores start"
# Strong scaling to this machine's cores and the machine's own ceiling (docs/performance.md,
# "Scaling to 16 threads"): where it has 8 cores or more, or at toy sizes with --quick.
if [ "$quick" = 1 ] || [ "$(nproc)" -ge 8 ]; then
    bash benchmarks/scaling/many_cores.sh "$build" $([ "$quick" = 1 ] && echo --quick) | tee "$out/many_cores.txt" \
        || echo "bench.sh: benchmarks/scaling/many_cores.sh failed (above); going on" >&2
else
    echo "bench.sh: $(nproc) cores: the many-core scaling is skipped (it needs 8 or more)" | tee "$out/many_cores.txt"
fi
load "many cores end / scaling start"

# Scaling: the same number of particle-updates at each size (250 steps at 64,000 particles),
# but no more simulated time than the reference run's 14 us (coarse grids take long steps and
# the blocks would leave the grid).
{
    echo "scene,scheme,cell_mm,particles,steps,threads,repeats,median_s,min_s,mups_median,mups_best,consistent_mass"
    for cell in "${sizes[@]}"; do
        steps=$(awk -v c="$cell" -v q="$quick" 'BEGIN { s = int(250 * (c / 0.5) ^ 2); m = int(1000 * 0.5 / c);
                                                          if (s > m) s = m; if (s < 10) s = 10; if (q) s = 3; print s }')
        for scene in reference hmx; do
            for t in 1 2; do
                "$bin/throughput/bench_throughput" --scene "$scene" --threads "$t" --cell "$cell" --steps "$steps" \
                    --repeats "$([ "$quick" = 1 ] && echo 1 || echo 3)"
            done
        done
    done
} | tee "$out/scaling.csv"
load "scaling end / effects start"

"$bin/effects/bench_effects" "${eff_args[@]}" | tee "$out/effects.csv"
load "effects end / accuracy start"

"$bin/accuracy/bench_accuracy" "${acc_args[@]}" | tee "$out/accuracy.csv"
load "accuracy end"

python=python3
[ -x /usr/bin/python3 ] && python=/usr/bin/python3

# The flagship's outputs (the aim: within 15 % of the same run with outputs off): the
# quickstart's run (scripts/quickstart.sh's flags) on 2 threads, whole process, with
#   off       no snapshots, one sample per 100 us (the least the flags allow), no figures;
#   written   the quickstart's samples (every 0.1 us) and nine snapshots, no figures;
#   default   the same with the figures (plot.py), as a user runs it.
# The three are interleaved, repeated, and the median of each is compared.
flagship="$build/examples/cavity_collapse/cavity_collapse"
if [ "$quick" = 1 ]; then
    fl_args=(--velocity 300 --radius 10 --cell 2 --end-us 40); fl_repeats=1
else
    fl_args=(--velocity 300 --radius 10 --cell 0.5 --end-us 40); fl_repeats=5
fi
fl_out=$(mktemp -d)
load "outputs start"
{
    echo "outputs,repeat,wall_s"
    for r in $(seq 1 "$fl_repeats"); do
        for kind in off written default; do
            case "$kind" in
                off) extra=(--snapshot-every-us 0 --sample-every-us 100 --no-figures) ;;
                written) extra=(--snapshot-every-us 0 --snapshots-after-contact-us 4,6,8,12,14,20,24,25,30 --no-figures) ;;
                default) extra=(--snapshot-every-us 0 --snapshots-after-contact-us 4,6,8,12,14,20,24,25,30) ;;
            esac
            rm -rf "$fl_out/run"
            t0=$(date +%s.%N)
            "$flagship" "${fl_args[@]}" "${extra[@]}" --threads 2 --quiet \
                --output "$fl_out/run" >/dev/null
            echo "$kind,$r,$(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf "%.3f", b - a }')"
        done
    done
} | tee "$out/outputs.csv"
rm -rf "$fl_out"
load "outputs end / serial share start"
# The flagship's serial share on 2 threads (docs/performance.md, "What limits scaling to 16
# threads"): the samples of its first thread while the other slept, which cap what more
# threads can give (Amdahl). It needs perf, and permission to sample.
perf_works() {
    local data
    data=$(mktemp)
    perf record -q -F 15000 -o "$data" -- true >/dev/null 2>&1
    local rc=$?
    rm -f "$data"
    return $rc
}
if command -v perf >/dev/null && perf_works; then
    ss_out=$(mktemp -d)
    # 12 us: past the first contact (6.7 us) and the snapshot 4 us after it. The quick run at 1 mm
    # (13,472 particles: enough for the loops to use both threads).
    if [ "$quick" = 1 ]; then ss_cell=1; else ss_cell=0.25; fi
    # The report on standard output; the flagship's own lines on standard error.
    python3 benchmarks/scaling/serial_share.py -- "$flagship" --velocity 300 --radius 10 --cell "$ss_cell" \
        --end-us 12 --snapshot-every-us 0 --snapshots-after-contact-us 4 --no-figures --threads 2 --quiet \
        --output "$ss_out/run" | tee "$out/serial_share.txt" \
        || echo "bench.sh: benchmarks/scaling/serial_share.py failed (its message is above)" | tee -a "$out/serial_share.txt" >&2
    rm -rf "$ss_out"
else
    echo "bench.sh: no perf, or no permission to sample: the serial share is skipped (scripts/setup.sh --bench installs perf)" \
        | tee "$out/serial_share.txt"
fi
load "serial share end"
plots="docs"
[ "$quick" = 1 ] && plots="$out"
"$python" benchmarks/report.py "$out" "$plots"
cat "$out/load.txt"
