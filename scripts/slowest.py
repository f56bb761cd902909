#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Print the slowest tests and translation units of one preset's build tree.

Tests come from the JUnit file ctest wrote (scripts/test.sh passes --output-junit
<build>/test-results.xml); translation units from ninja's log (<build>/.ninja_log), where the
latest build of each object file counts. Used by scripts/test.sh (docs/testing.md); run it by
hand on any build tree:

    python3 scripts/slowest.py --preset release --build build/release --count 10

With --test-guard and --unit-guard it also names every test slower than the guard that is not
labelled `long`, and every translation unit slower than its guard: the growth guard of
docs/testing.md (such a test needs the `long` label or a reason in a comment; such a unit is
split).
"""

import argparse
import os
import re
import subprocess
import sys
import xml.etree.ElementTree as ET


def slowest_tests(junit, count):
    """(seconds, name) of the `count` slowest test cases in a ctest JUnit file."""
    root = ET.parse(junit).getroot()
    cases = [(float(c.get("time", "0")), c.get("name", "?")) for c in root.iter("testcase")]
    return sorted(cases, reverse=True)[:count], len(cases)


def slowest_units(ninja_log, count):
    """(seconds, output) of the `count` slowest object files in a .ninja_log (format v5)."""
    latest = {}
    with open(ninja_log, encoding="utf-8") as f:
        for line in f:
            if line.startswith("#"):
                continue
            fields = line.rstrip("\n").split("\t")
            if len(fields) < 5:
                continue
            start, end, output = int(fields[0]), int(fields[1]), fields[3]
            if output.endswith(".o"):
                latest[output] = (end - start) / 1000.0
    units = sorted(((s, o) for o, s in latest.items()), reverse=True)
    return units[:count], len(latest)


def long_tests(build):
    """Names of the tests labelled `long` in a build tree (empty if ctest cannot list them)."""
    try:
        out = subprocess.run(["ctest", "--test-dir", build, "-N", "-L", "^long$"],
                             capture_output=True, text=True, check=False).stdout
    except OSError:
        return set()
    return {m.group(1) for m in re.finditer(r"^\s*Test\s+#\d+: (.*)$", out, re.M)}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--preset", required=True)
    ap.add_argument("--build", required=True, help="the preset's build tree")
    ap.add_argument("--count", type=int, default=10)
    ap.add_argument("--test-guard", type=float, help="seconds above which a test needs `long` or a reason")
    ap.add_argument("--unit-guard", type=float, help="seconds above which a translation unit is split")
    a = ap.parse_args()
    over = []

    junit = os.path.join(a.build, "test-results.xml")
    try:
        found = slowest_tests(junit, a.count) if os.path.exists(junit) else None
    except ET.ParseError as err:  # ctest stopped while writing it
        print(f"=== {a.preset}: unreadable test results ({junit}: {err}) ===")
        found = ()
    if found:
        tests, n = found
        print(f"=== {a.preset}: the {len(tests)} slowest of {n} tests (s) ===")
        for s, name in tests:
            print(f"  {s:8.2f}  {name}")
        if a.test_guard is not None:
            labelled = long_tests(a.build)
            every, _ = slowest_tests(junit, n)
            over += [f"test {name}: {s:.1f} s > {a.test_guard:g} s" for s, name in every
                     if s > a.test_guard and name not in labelled]
    elif found is None:
        print(f"=== {a.preset}: no test results ({junit}) ===")

    log = os.path.join(a.build, ".ninja_log")
    if os.path.exists(log):
        units, n = slowest_units(log, a.count)
        print(f"=== {a.preset}: the {len(units)} slowest of {n} translation units (s, 2 at a time) ===")
        for s, out in units:
            print(f"  {s:8.2f}  {out}")
        if a.unit_guard is not None:
            every, _ = slowest_units(log, n)
            over += [f"unit {out}: {s:.1f} s > {a.unit_guard:g} s" for s, out in every if s > a.unit_guard]
    else:
        print(f"=== {a.preset}: no build log ({log}) ===")
    if over:
        print(f"=== {a.preset}: over the growth guard (docs/testing.md: a test takes the `long` label or a reason in a comment; a unit is split) ===")
        for line in over:
            print(f"  {line}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
