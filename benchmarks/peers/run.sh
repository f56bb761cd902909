#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Times gimlet's reference scene side by side with other MPM codes on the same problem
# (README.md in this folder says what each deck is and what differs between the codes).
#
# Every comparison runs the peer (A) and gimlet (B) in turn, A B A B ..., after one untimed
# warm-up run of each, and times each run as a whole process (start-up, set-up and output
# included) with the shell's clock. It prints each run's seconds, then min / median / max of
# A, of B and of the pair-by-pair ratio A/B, and the 1-minute load average before and after.
# Particle-updates per second = 64,000 x STEPS / wall seconds.
#
# Usage: benchmarks/peers/run.sh --gimlet PATH [--karamelo PATH] [--nairn PATH] [--cbgeo PATH]
#            [--runs N (5)] [--steps N (1000)] [--cbgeo-steps N (the same as --steps)]
#            [--work DIR (/tmp/gimlet-peers)] [--mpirun 'COMMAND' (mpirun -np 2)]
#   --gimlet    bench_throughput of a `cmake --preset bench` build (benchmarks/throughput)
#   --karamelo  Karamelo's `karamelo` executable (two comparisons: linear, quadratic B-spline)
#   --nairn     NairnMPM's executable (NairnMPM/input/NairnMPM after its makefile build)
#   --cbgeo     CB-Geo's `mpm` executable
# Peers not given are skipped. Two workers everywhere: 2 threads (gimlet, NairnMPM, CB-Geo),
# 2 MPI ranks (Karamelo). OMP_WAIT_POLICY=passive for the OpenMP codes.
set -euo pipefail
export LC_ALL=C  # printf and awk read and write numbers with a decimal point

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
gimlet="" karamelo="" nairn="" cbgeo=""
runs=5 steps=1000 cbgeo_steps="" work=/tmp/gimlet-peers
mpirun_cmd="mpirun -np 2"
[ "$(id -u)" = 0 ] && mpirun_cmd="mpirun --allow-run-as-root --oversubscribe -np 2"
while [ $# -gt 0 ]; do
    case "$1" in --gimlet|--karamelo|--nairn|--cbgeo|--runs|--steps|--cbgeo-steps|--work|--mpirun)
        [ $# -ge 2 ] || { echo "run.sh: $1 needs a value" >&2; exit 2; } ;;
    esac
    case "$1" in
        --gimlet) gimlet=$(realpath "$2"); shift 2 ;;
        --karamelo) karamelo=$(realpath "$2"); shift 2 ;;
        --nairn) nairn=$(realpath "$2"); shift 2 ;;
        --cbgeo) cbgeo=$(realpath "$2"); shift 2 ;;
        --runs) runs=$2; shift 2 ;;
        --steps) steps=$2; shift 2 ;;
        --cbgeo-steps) cbgeo_steps=$2; shift 2 ;;
        --work) work=$2; shift 2 ;;
        --mpirun) mpirun_cmd=$2; shift 2 ;;
        *) echo "run.sh: unknown argument '$1' (see the comment at the top)" >&2; exit 2 ;;
    esac
done
[ -n "$gimlet" ] || { echo "run.sh: --gimlet PATH is required" >&2; exit 2; }
for n in "$runs" "$steps" "${cbgeo_steps:-1}"; do
    [[ "$n" =~ ^[1-9][0-9]*$ ]] || { echo "run.sh: --runs, --steps and --cbgeo-steps take a whole number >= 1 (got '$n')" >&2; exit 2; }
done
cbgeo_steps=${cbgeo_steps:-$steps}
mkdir -p "$work"
work=$(realpath "$work")
export OMP_WAIT_POLICY=passive

load() { cut -d' ' -f1 /proc/loadavg; }
calc() { awk "BEGIN { printf \"%.6f\", $1 }"; }

# time_once LOG DIR CMD...: runs CMD in DIR, its output appended to LOG; prints wall seconds.
time_once() {
    local log=$1 dir=$2; shift 2
    local t0 t1
    t0=$(date +%s.%N)
    (cd "$dir" && "$@" >>"$log" 2>&1) || { echo "run.sh: '$*' failed, see $log" >&2; exit 1; }
    t1=$(date +%s.%N)
    calc "$t1 - $t0"
}

# stats: min median max of the numbers on stdin
stats() { sort -g | awk '{v[NR]=$1} END {m=(NR%2)?v[(NR+1)/2]:(v[NR/2]+v[NR/2+1])/2; printf "%.3f %.3f %.3f\n", v[1], m, v[NR]}'; }

# expect LOG PATTERN: stop unless the peer's output holds PATTERN (a peer that exits 0 without
# running the scene would otherwise be timed as fast).
expect() {
    grep -q -- "$2" "$1" || { echo "run.sh: '$2' not found in $1: the peer did not run the scene" >&2; exit 1; }
}

# compare NAME DIR_A STEPS PATTERN -- CMD_A...: peer (A) against gimlet (B) at STEPS steps;
# PATTERN must appear in the peer's output.
compare() {
    local name=$1 dir=$2 n=$3 pattern=$4; shift 5
    local b=("$gimlet" --scene reference --threads 2 --cell 0.5 --steps "$n" --repeats 1)
    local la lb ta tb
    la="$work/$name.out" lb="$work/$name.gimlet.out"
    : >"$la"; : >"$lb"
    echo "== $name: A = $*  (in $dir)"
    echo "   B = ${b[*]}"
    local before; before=$(load)
    time_once "$la" "$dir" "$@" >/dev/null       # warm-up, not counted
    expect "$la" "$pattern"
    time_once "$lb" "$work" "${b[@]}" >/dev/null
    local sa=() sb=() r=()
    for ((k = 1; k <= runs; ++k)); do
        ta=$(time_once "$la" "$dir" "$@")
        tb=$(time_once "$lb" "$work" "${b[@]}")
        sa+=("$ta") sb+=("$tb") r+=("$(calc "$ta / $tb")")
        printf '   run %d: A %.3f s, B %.3f s, A/B %.3f\n' "$k" "$ta" "$tb" "${r[-1]}"
    done
    local after; after=$(load)
    read -r amin amed amax < <(printf '%s\n' "${sa[@]}" | stats)
    read -r bmin bmed bmax < <(printf '%s\n' "${sb[@]}" | stats)
    read -r rmin rmed rmax < <(printf '%s\n' "${r[@]}" | stats)
    printf '   A %s: wall s min %s median %s max %s = %.3f M particle-updates/s (median)\n' \
        "$name" "$amin" "$amed" "$amax" "$(calc "64000 * $n / $amed / 1e6")"
    printf '   B gimlet: wall s min %s median %s max %s = %.3f M particle-updates/s (median)\n' \
        "$bmin" "$bmed" "$bmax" "$(calc "64000 * $n / $bmed / 1e6")"
    printf '   A/B: min %s median %s max %s; load average (1 min) before %s after %s\n\n' \
        "$rmin" "$rmed" "$rmax" "$before" "$after"
}

# with_steps SRC DST STEPS: a Karamelo deck with its step count set to STEPS.
with_steps() { sed "s/^N = 1000$/N = $3/" "$1" >"$2"; }

if [ -n "$karamelo" ]; then
    for shape in linear quadratic_spline; do
        d="$work/karamelo_$shape"
        mkdir -p "$d"
        with_steps "$here/karamelo/reference_$shape.mpm" "$d/reference.mpm" "$steps"
        # shellcheck disable=SC2086
        compare "karamelo_$shape" "$d" "$steps" "^$steps[[:space:]]" -- $mpirun_cmd "$karamelo" -i reference.mpm
    done
fi

if [ -n "$nairn" ]; then
    d="$work/nairnmpm"
    mkdir -p "$d"
    # MaxTime = (STEPS - 0.5) dt gives STEPS steps (NairnMPM steps while t <= MaxTime)
    sed "s/\"1.3993e-5\"/\"$(awk "BEGIN { printf \"%.10g\", ($steps - 0.5) * 1.4e-8 }")\"/" \
        "$here/nairnmpm/reference.fmcmd" >"$d/reference.fmcmd"
    compare nairnmpm "$d" "$steps" "Calculation Steps: $steps\$" -- "$nairn" -np 2 -w reference.fmcmd
fi

if [ -n "$cbgeo" ]; then
    d="$work/cbgeo"
    python3 "$here/cbgeo/make_deck.py" "$d" "$cbgeo_steps"
    compare cbgeo "$d" "$cbgeo_steps" "Step: $((cbgeo_steps - 1)) of $cbgeo_steps\." -- "$cbgeo" -f "$d/" -i mpm.json -p 2
fi
