#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Install what gimlet needs to build, test and plot, from the Debian packages. Idempotent: it
# only calls apt-get when a package is missing.
#
#   bash scripts/setup.sh           everything: build, test, and the figures (matplotlib)
#   bash scripts/setup.sh --tests   what building and running the test suite needs, nothing for
#                                   the figures (scripts/test.sh: saves about 20 s of CI)
set -euo pipefail

# What the build and the tests need. clang, its OpenMP runtime and its sanitizer runtimes build
# the asan-ubsan preset (docs/testing.md).
packages=(cmake ninja-build g++ clang libomp-dev libclang-rt-dev libeigen3-dev catch2)
case "${1:-}" in
    --tests) ;;
    "") packages+=(python3-matplotlib python3-numpy) ;;  # the examples' figures
    *) echo "setup.sh: unknown argument '$1'; usage: setup.sh [--tests]" >&2; exit 2 ;;
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

if [ "${#missing[@]}" -eq 0 ]; then
    echo "setup.sh: nothing to do, all ${#packages[@]} packages are installed"
    exit 0
fi

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
    if command -v sudo >/dev/null 2>&1; then
        sudo_cmd=(sudo)
    else
        echo "setup.sh: missing ${missing[*]}, and not root and no sudo: install them by hand" >&2
        exit 1
    fi
fi

echo "setup.sh: installing ${missing[*]}"
"${sudo_cmd[@]}" apt-get update
"${sudo_cmd[@]}" env DEBIAN_FRONTEND=noninteractive \
    apt-get install -y --no-install-recommends "${missing[@]}"

for p in "${missing[@]}"; do
    if ! is_installed "$p"; then
        echo "setup.sh: $p is still not installed" >&2
        exit 1
    fi
done
echo "setup.sh: installed ${missing[*]}"
