#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Configure, build and test every preset in GIMLET_TEST_PRESETS (default: "release asan-ubsan fuzz").
# Goes on after a failing preset so that one run reports them all; exits non-zero if any failed.
#
# It first runs the docs check (scripts/check_docs.py); the release preset also builds the API
# reference (the `docs` target: Doxygen, which fails on an undocumented public name).
#
# The CI budget (docs/testing.md): at the end it prints the seconds of each phase (setup, then
# configure, build and test of each preset) and the total, writes the same lines to
# build/test-times.txt ("phase seconds", one per line, "total N" last), and lists the ten
# slowest tests and the ten slowest translation units of each preset.
set -uo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"

now() { date +%s.%N; }
t_all=$(now)
phases=()     # "name seconds"
summary=()
failed=0
times_file="build/test-times.txt"
mkdir -p build

# build/test-times.txt is written however the run ends (a failed phase, an interrupt).
write_times() {
    local total
    total=$(awk -v a="$t_all" -v b="$(now)" 'BEGIN { printf "%.0f", b - a }')
    { [ "${#phases[@]}" -eq 0 ] || printf '%s\n' "${phases[@]}"; echo "total $total"; } > "$times_file"
}
trap write_times EXIT

# Runs "$@" as phase $1 (the rest is the command) and records its seconds; returns its status.
timed() {
    local name=$1
    shift
    local t0 rc
    t0=$(now)
    "$@"
    rc=$?
    phases+=("$name $(awk -v a="$t0" -v b="$(now)" 'BEGIN { printf "%.1f", b - a }')")
    return $rc
}

if ! timed setup bash scripts/setup.sh --tests; then
    echo "test.sh: FAILED: scripts/setup.sh"
    exit 1
fi

# The docs check (links, the docs/ pages named, the wording rule); the guide's code blocks are
# built and run by the release preset's tests.
if ! timed docs python3 scripts/check_docs.py; then
    failed=1
    summary+=("docs: FAIL")
fi

presets="${GIMLET_TEST_PRESETS:-release asan-ubsan fuzz}"

for p in $presets; do
    echo "=== test.sh: preset $p ==="
    junit="$repo_root/build/$p/test-results.xml"
    rm -f "$junit"  # never report an earlier run's tests as this one's
    # The release preset builds the mpi component's tests where MPI is found; here MPI must be
    # found (setup.sh --tests installs it), so that a missing MPI fails instead of skipping them.
    extra=()
    [ "$p" = release ] && extra=(-DGIMLET_REQUIRE_MPI=ON)
    if ! timed "$p.configure" cmake --preset "$p" "${extra[@]}"; then
        status="FAIL(configure)"
    elif ! timed "$p.build" cmake --build --preset "$p" -j2; then
        status="FAIL(build)"
    elif [ "$p" = release ] && ! timed "$p.docs" cmake --build --preset "$p" --target docs; then
        status="FAIL(API reference)"  # a header's public name without its /// comment
    elif ! timed "$p.test" ctest --preset "$p" --output-junit "$junit"; then
        status="FAIL(test)"
    else
        status="ok"
    fi
    [ "$status" = ok ] || failed=1
    summary+=("$p: $status")
done

write_times
trap - EXIT
total=$(awk '$1 == "total" { print $2 }' "$times_file")

# The growth guard (docs/testing.md): a test over 20 s in release or 60 s under asan-ubsan
# carries the `long` label or a reason; a unit over 150 s to compile under asan-ubsan is split.
command -v python3 >/dev/null 2>&1 || echo "test.sh: no python3: the slowest tests and units are not listed"
for p in $presets; do
    command -v python3 >/dev/null 2>&1 || break
    case "$p" in
        asan-ubsan) guards=(--test-guard 60 --unit-guard 150) ;;
        release) guards=(--test-guard 20) ;;
        *) guards=() ;;
    esac
    python3 scripts/slowest.py --preset "$p" --build "build/$p" --count 10 "${guards[@]}" || true
done

echo "=== test.sh: seconds per phase (also in $times_file; the CI budget is 900 s: docs/testing.md) ==="
sed 's/^/  /' "$times_file"
echo "=== test.sh summary ==="
printf '  %s\n' "${summary[@]}"
if [ "$failed" -eq 0 ]; then
    echo "test.sh: ALL PASSED [$presets] in $total s"
else
    echo "test.sh: FAILED [${summary[*]}]"
fi
exit "$failed"
