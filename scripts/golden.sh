#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Golden outputs: the examples' files for a fixed set of runs, recorded once and compared after a
# change that must not change a result (a refactor), byte for byte.
#
#   bash scripts/golden.sh record DIR [BUILD]   run every case into DIR
#   bash scripts/golden.sh compare DIR [BUILD]  run every case again and compare with DIR
#
# BUILD is a configured and built release tree (default build/release; the three examples are
# built there if they are missing). The cases: cavity_collapse in 13 configurations (every
# numerical option the example exposes, one at a time, 1 and 2 threads, a checkpoint and the run
# resumed from it), impact_1d at 300, 500 and 700 m/s under USF and at 500 m/s under MUSL and
# USL, and contact_validation. The comparison covers every file a run writes except figures
# (PNG) and ignores the wall-clock columns of summary.csv (wall_s); the printed progress, which
# holds timings, is not compared. Exit status 1 names every file that differs.
set -euo pipefail

mode=${1:-}
dir=${2:-}
build=${3:-build/release}
if { [ "$mode" != record ] && [ "$mode" != compare ]; } || [ -z "$dir" ]; then
    echo "usage: golden.sh record|compare DIR [BUILD]" >&2
    exit 2
fi
cd "$(dirname "${BASH_SOURCE[0]}")/.."
ex="$build/examples"
need=()
for e in cavity_collapse impact_1d contact_validation; do [ -x "$ex/$e/$e" ] || need+=("$e"); done
if [ "${#need[@]}" -gt 0 ]; then cmake --build "$build" --target "${need[@]}"; fi
export OMP_WAIT_POLICY=passive

if [ "$mode" = record ]; then
    [ -e "$dir" ] && { echo "golden.sh: $dir exists; record into a new directory" >&2; exit 2; }
    out=$dir
else
    [ -d "$dir" ] || { echo "golden.sh: no recorded outputs in $dir" >&2; exit 2; }
    out=$(mktemp -d)
    trap 'rm -rf "$out"' EXIT
fi
mkdir -p "$out"

# The flagship at 1 mm cells to 30 us: contact at 6.6 us, both cavities closed (jets landed) by
# 30 us. One configuration, the quickstart's cell (0.5 mm), runs to 26 us.
cc() {
    local name=$1
    shift
    "$ex/cavity_collapse/cavity_collapse" --no-figures --quiet --output "$out/cc_$name" "$@" >"$out/cc_$name.log"
}
base=(--cell 1 --end-us 30 --threads 1)
cc default "${base[@]}"
cc threads2 --cell 1 --end-us 30 --threads 2
cc single "${base[@]}" --contact single
cc bardenhagen "${base[@]}" --contact bardenhagen
cc no_self_contact "${base[@]}" --self-contact off
cc volumetric_average "${base[@]}" --volumetric-average on
cc pic "${base[@]}" --pic-fraction 0.05
cc lumped "${base[@]}" --consistent-mass 0
cc volume_filter "${base[@]}" --volume-filter on
cc paper_temperature "${base[@]}" --temperature paper
cc no_viscosity "${base[@]}" --viscosity-linear 0 --viscosity-quadratic 0
cc strong "${base[@]}" --velocity 700 --radius 6
cc fine --cell 0.5 --end-us 26 --threads 2
cc checkpoint "${base[@]}" --checkpoint "$out/checkpoint.bin" --checkpoint-at-us 20
# A checkpoint at 20 us, and the run resumed from it in a copy of its folder (a restart continues
# the series of the run that wrote the checkpoint).
cp -r "$out/cc_checkpoint" "$out/cc_restart"
cc restart "${base[@]}" --restart "$out/checkpoint.bin"

for v in 300 500 700; do
    "$ex/impact_1d/impact_1d" --velocity "$v" --threads 1 --output "$out/impact_usf_$v" >/dev/null
done
for s in musl usl; do
    "$ex/impact_1d/impact_1d" --velocity 500 --scheme "$s" --threads 1 --output "$out/impact_${s}_500" >/dev/null
done
"$ex/contact_validation/contact_validation" --cell 1 --threads 2 --output "$out/contact_validation" >/dev/null

# Drop the wall-clock column (wall_s) from every summary.csv, in place, so the files compare.
find "$out" -name summary.csv -print0 | while IFS= read -r -d '' f; do
    awk -F, -v OFS=, 'NR == 1 { for (i = 1; i <= NF; ++i) if ($i == "wall_s") skip = i }
        { if (skip) { for (i = skip; i < NF; ++i) $i = $(i + 1); NF-- } print }' "$f" >"$f.tmp"
    mv "$f.tmp" "$f"
done
find "$out" \( -name '*.png' -o -name '*.log' \) -delete

if [ "$mode" = record ]; then
    echo "golden.sh: recorded $(find "$out" -type f | wc -l) files in $out"
    exit 0
fi
if differences=$(diff -rq "$dir" "$out" 2>&1); then
    echo "golden.sh: all $(find "$dir" -type f | wc -l) files byte-identical to $dir"
else
    printf '%s\n' "$differences" >&2
    echo "golden.sh: outputs differ from $dir" >&2
    exit 1
fi
