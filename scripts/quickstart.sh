#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# From a fresh clone to the flagship example's results: install the dependencies, configure
# and build the release preset (only what the flagship needs), run it.
set -euo pipefail

# The paper's strong-shock run: R = 10 mm cavities, +-300 m/s, to 33 us after contact, with
# snapshots at the times of the paper's pressure and temperature figures.
FLAGSHIP=cavity_collapse
FLAGSHIP_ARGS=(--velocity 300 --radius 10 --cell 0.5 --end-us 40 --snapshot-every-us 0
               --snapshots-after-contact-us 4,6,8,12,14,20,24,25,30 --output results/cavity_collapse)
PRESET=release

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"

bash scripts/setup.sh
cmake --preset "$PRESET"
cmake --build --preset "$PRESET" --target "$FLAGSHIP" -j2

build_dir="build/$PRESET"
binary="$build_dir/examples/$FLAGSHIP/$FLAGSHIP"
if [ ! -x "$binary" ]; then
    # The example may set its own output directory: look for the executable anywhere in the tree.
    binary="$(find "$build_dir" -type f -name "$FLAGSHIP" -perm -u+x -print -quit)"
fi
if [ -z "$binary" ] || [ ! -x "$binary" ]; then
    echo "quickstart.sh: built target $FLAGSHIP but found no executable of that name in $build_dir" >&2
    exit 1
fi

echo "quickstart.sh: running $binary ${FLAGSHIP_ARGS[*]}"
"$binary" "${FLAGSHIP_ARGS[@]}"

# Report where the outputs are: the value following --output, if there is one.
output=""
for ((i = 0; i < ${#FLAGSHIP_ARGS[@]}; i++)); do
    if [ "${FLAGSHIP_ARGS[$i]}" = "--output" ] && [ $((i + 1)) -lt ${#FLAGSHIP_ARGS[@]} ]; then
        output="${FLAGSHIP_ARGS[$((i + 1))]}"
    fi
done
if [ -n "$output" ] && [ -e "$output" ]; then
    echo "quickstart.sh: outputs are in $repo_root/$output:"
    find "$output" -maxdepth 2 -type f | sort | head -n 50
else
    echo "quickstart.sh: done ($FLAGSHIP wrote its outputs relative to $repo_root)"
fi
