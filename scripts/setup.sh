#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Install what gimlet needs, from the Debian packages. Idempotent: it only calls apt-get when a
# package is missing.
#
#   bash scripts/setup.sh           building the release preset and the examples' figures
#                                   (scripts/quickstart.sh)
#   bash scripts/setup.sh --tests   building and running the test suite: both presets, the
#                                   asan-ubsan one with clang (scripts/test.sh; docs/testing.md)
#   bash scripts/setup.sh --bench   running the benchmarks (scripts/bench.sh; docs/performance.md)
set -euo pipefail

# Both: the compiler and build tools, Eigen, and Catch2 (the release preset configures the tests).
packages=(cmake ninja-build g++ libeigen3-dev catch2)
case "${1:-}" in
    "") packages+=(python3-matplotlib python3-numpy) ;;  # the examples' figures
    # clang with its OpenMP and sanitizer runtimes (the asan-ubsan preset); python3 lists the
    # slowest tests and units; VTK's Python module reads our .vtp files back in the
    # independent-reader test (tests/io/independent/); numpy runs the flagship's map painter
    # (tests/examples/test_plot_raster.py); Doxygen builds the API reference, whose warnings fail
    # the run (the `docs` target); Open MPI builds and runs the MPI component's tests.
    --tests) packages+=(clang libomp-dev libclang-rt-dev python3 python3-vtk9 python3-numpy doxygen libopenmpi-dev
                        openmpi-bin) ;;
    # the plots and the per-phase roofline's instruction counts (valgrind's callgrind, objdump);
    # perf for the flagship's serial share is optional (below)
    --bench) packages+=(python3-matplotlib python3-numpy valgrind binutils) ;;
    *) echo "setup.sh: unknown argument '$1'; usage: setup.sh [--tests | --bench]" >&2; exit 2 ;;
esac

is_installed() {
    dpkg-query -W -f='${Status}' "$1" 2>/dev/null | grep -q "install ok installed"
}

if ! command -v dpkg-query >/dev/null 2>&1; then
    echo "setup.sh: dpkg-query not found; this script supports Debian/Ubuntu only." >&2
    echo "setup.sh: install by hand: ${packages[*]}" >&2
    exit 1
fi

missing=()
for p in "${packages[@]}"; do
    if is_installed "$p"; then
        echo "setup.sh: $p is installed"
    else
        missing+=("$p")
    fi
done
# Optional packages: installed where the package exists; nothing fails without them. perf for
# the flagship's serial share in scripts/bench.sh (Debian's linux-perf; Ubuntu names it
# otherwise, and one unknown name would fail the whole install).
optional=()
[ "${1:-}" = "--bench" ] && optional+=(linux-perf)
missing_optional=()
for p in "${optional[@]}"; do
    # A perf from elsewhere (Ubuntu's linux-tools) will do: no apt-get on every run for it.
    [ "$p" = linux-perf ] && command -v perf >/dev/null 2>&1 && continue
    is_installed "$p" || missing_optional+=("$p")
done

if [ "${#missing[@]}" -eq 0 ] && [ "${#missing_optional[@]}" -eq 0 ]; then
    echo "setup.sh: nothing to do, all ${#packages[@]} packages are installed"
    exit 0
fi

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
    if command -v sudo >/dev/null 2>&1; then
        sudo_cmd=(sudo)
    elif [ "${#missing[@]}" -gt 0 ]; then
        echo "setup.sh: missing ${missing[*]}, and not root and no sudo: install them by hand" >&2
        exit 1
    else
        echo "setup.sh: optional ${missing_optional[*]} not installed: not root and no sudo"
        exit 0
    fi
fi

"${sudo_cmd[@]}" apt-get update
if [ "${#missing[@]}" -gt 0 ]; then
    echo "setup.sh: installing ${missing[*]}"
    "${sudo_cmd[@]}" env DEBIAN_FRONTEND=noninteractive \
        apt-get install -y --no-install-recommends "${missing[@]}"
    for p in "${missing[@]}"; do
        if ! is_installed "$p"; then
            echo "setup.sh: $p is still not installed" >&2
            exit 1
        fi
    done
    echo "setup.sh: installed ${missing[*]}"
fi
for p in "${missing_optional[@]}"; do
    if "${sudo_cmd[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "$p"; then
        echo "setup.sh: installed the optional $p"
    else
        echo "setup.sh: the optional $p is not installed (no such package here?); going on without it"
    fi
done
