#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Configure, build and test every preset in GIMLET_TEST_PRESETS (default: "release asan-ubsan").
# Goes on after a failing preset so that one run reports them all; exits non-zero if any failed.
set -uo pipefail

repo_root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$repo_root"

bash scripts/setup.sh || { echo "test.sh: FAILED: scripts/setup.sh"; exit 1; }

presets="${GIMLET_TEST_PRESETS:-release asan-ubsan}"
summary=()
failed=0
start_all=$SECONDS

for p in $presets; do
    start=$SECONDS
    echo "=== test.sh: preset $p ==="
    if ! cmake --preset "$p"; then
        status="FAIL(configure)"
    elif ! cmake --build --preset "$p" -j2; then
        status="FAIL(build)"
    elif ! ctest --preset "$p"; then
        status="FAIL(test)"
    else
        status="ok"
    fi
    [ "$status" = ok ] || failed=1
    summary+=("$p: $status ($((SECONDS - start)) s)")
done

echo "=== test.sh summary ==="
printf '  %s\n' "${summary[@]}"
if [ "$failed" -eq 0 ]; then
    echo "test.sh: ALL PASSED [$presets] in $((SECONDS - start_all)) s"
else
    echo "test.sh: FAILED [${summary[*]}]"
fi
exit "$failed"
