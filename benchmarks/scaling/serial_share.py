#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The serial share of a multi-threaded run, from where its threads' samples fall in time
(docs/performance.md, "What limits scaling to 16 threads"): what a
machine with few cores says of what limits scaling to many.

    serial_share.py [--frequency HZ] [--window MS] [--after NAME] [--top N] -- COMMAND [ARG ...]

runs COMMAND under `perf record` (every thread sampled at HZ, 15000 by default; the command's
standard output goes to this script's standard error) and counts a sample of the process's first
thread as serial where no other thread of the process has a sample within MS milliseconds either
side (0.15 by default, about two sampling intervals at 15000 Hz; widened in proportion where
perf keeps under 0.9 of the rate asked, which it does without an error where the kernel caps
the rate). What it measures:
- the stretches where the first thread runs alone: under OMP_WAIT_POLICY=passive OpenMP's idle
  threads sleep at once, so these are the code that runs on one thread, and the ends of passes
  where the first thread finishes last. (Where another thread finishes last, the first is the
  one asleep: those stretches are not counted.) Under active waiting the idle threads spin, and
  nothing reads as serial;
- as a share of the first thread's samples, which cover nearly all of a run's wall time where
  that thread drives it (an OpenMP program's master thread).
A thread that waits for a core has no samples either, so the machine must be otherwise idle:
other work running beside it reads as serial. Where the kernel's samples are allowed (root, or
perf_event_paranoid below 2) the process's work in the kernel (page faults, writing files)
counts too; the report says which.

With --after, the count starts after the first thread's last sample in a function whose name
(template arguments and parameters left out) contains NAME, a set-up to leave out such as
seed_particles; it ends at the other threads' last sample either way.

Prints the share of the first thread's samples that are serial, and the functions that hold the
most of them. By Amdahl's law a serial share f of the wall time on T threads caps N threads at
1 / (f + (1 - f) T / N) times the T-thread rate. Needs perf (Debian: linux-perf, which
scripts/setup.sh --bench installs where the package exists) and permission to sample."""
import argparse
import bisect
import collections
import re
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

_SHORT = {}


def short(function):
    """A function's name without its template arguments, parameters and clone suffixes:
    gimlet::solver_core<...>::scatter<true>()::{lambda(unsigned long)#1} as
    gimlet::solver_core::scatter::{lambda#1}; [unknown] where perf has none."""
    name = _SHORT.get(function)
    if name is None:
        name = re.sub(r"\s*\[clone [^\]]*\]", "", function)
        name = re.sub(r"\+0x[0-9a-f]+$", "", name)
        previous = None
        while previous != name:  # innermost first: nested templates and parameter lists
            previous, name = name, re.sub(r"<[^<>]*>|\((?!anonymous namespace\))[^()]*\)", "", name)
        name = name.strip() or "[unknown]"
        _SHORT[function] = name
    return name


def samples(data):
    """(pid, tid, time, short function name, in the kernel) of every sample in perf's file."""
    line = re.compile(r"\s*(\d+)/(\d+)\s+([\d.]+):\s*([0-9a-f]+)\s*(.*)")
    # perf's messages to a file, read if it fails: a pipe read only at the end could fill and
    # stall it while this reads its samples.
    with tempfile.TemporaryFile(mode="w+") as errors:
        try:
            script = subprocess.Popen(["perf", "script", "-i", str(data), "-F", "pid,tid,time,ip,sym"],
                                      stdout=subprocess.PIPE, stderr=errors, text=True)
        except FileNotFoundError:
            sys.exit("serial_share.py: perf not found (Debian: apt-get install linux-perf)")
        for text in script.stdout:
            m = line.match(text)
            if m:
                kernel = len(m[4]) == 16 and m[4].startswith("ffff")
                yield int(m[1]), int(m[2]), float(m[3]), short(m[5].strip()), kernel
        if script.wait() != 0:
            errors.seek(0)
            sys.exit(f"serial_share.py: perf script failed: {errors.read().strip()}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--frequency", type=int, default=15000)
    parser.add_argument("--window", type=float, default=0.15, help="milliseconds either side")
    parser.add_argument("--after", default=None)
    parser.add_argument("--top", type=int, default=10)
    parser.add_argument("command", nargs=argparse.REMAINDER)
    args = parser.parse_args()
    command = args.command[1:] if args.command[:1] == ["--"] else args.command
    if not command:
        parser.error("no COMMAND given (after --)")
    with tempfile.TemporaryDirectory() as tmp:
        data = Path(tmp) / "perf.data"
        try:
            # perf's own messages (and why it refuses) on standard error, as the command's.
            record = subprocess.run(["perf", "record", "-F", str(args.frequency), "-o", str(data), "--"] + command,
                                    stdout=sys.stderr)
        except FileNotFoundError:
            sys.exit("serial_share.py: perf not found (Debian: apt-get install linux-perf)")
        if record.returncode != 0:
            sys.exit(f"serial_share.py: perf record ... {' '.join(command)} exited with {record.returncode} "
                     "(perf's message, if it refused, is above)")
        found = list(samples(data))
    # The command's process: the one whose first thread (tid = pid) has the most samples (perf
    # may run the command through a shell or a wrapper first).
    per_process = collections.Counter(pid for pid, tid, *_ in found if pid == tid)
    if not per_process:
        sys.exit("serial_share.py: no samples (is perf allowed to sample? see perf_event_paranoid)")
    pid = per_process.most_common(1)[0][0]
    first = [(t, f) for p, tid, t, f, _ in found if p == pid and tid == pid]
    others = sorted(t for p, tid, t, *_ in found if p == pid and tid != pid)
    threads = len({tid for p, tid, *_ in found if p == pid})
    kernel = any(k for p, *_, k in found if p == pid)
    if not others:
        sys.exit(f"serial_share.py: only the first thread of process {pid} has samples: nothing to compare "
                 "(does the command run on more than one thread here?)")
    start = first[0][0] - 1.0
    if args.after:
        ends = [t for t, f in first if args.after in f]
        if not ends:
            sys.exit(f"serial_share.py: no sample of the first thread in a function whose name contains "
                     f"'{args.after}'")
        start = max(ends)
    end = others[-1]
    counted = [(t, f) for t, f in first if start < t <= end]
    if len(counted) < 2:
        sys.exit(f"serial_share.py: {len(counted)} samples of the first thread to count between the start "
                 f"({'after ' + args.after if args.after else 'its first sample'}) and the other threads' last")
    # The rate perf kept: the median gap between the first thread's consecutive samples.
    gap = statistics.median(b[0] - a[0] for a, b in zip(counted, counted[1:]))
    rate = 1.0 / gap if gap > 0 else float(args.frequency)
    # (Widened only where perf kept under 0.9 of the rate asked: the measure stays comparable.)
    window = args.window * 1e-3 * (args.frequency / rate if rate < 0.9 * args.frequency else 1.0)
    serial = collections.Counter()
    for t, f in counted:
        k = bisect.bisect_left(others, t - window)
        if k == len(others) or others[k] > t + window:
            serial[f] += 1
    total = sum(serial.values())
    print(f"threads with samples: {threads}; the first thread's samples counted: {len(counted)} over "
          f"{counted[-1][0] - counted[0][0]:.2f} s, at {rate:.0f} Hz ({args.frequency} asked); a window of "
          f"{window * 1e3:.3f} ms either side; kernel samples {'included' if kernel else 'not included'}")
    print(f"serial: {total} samples, {100 * total / len(counted):.2f} % of them")
    for name, n in serial.most_common(args.top):
        print(f"  {100 * n / len(counted):6.2f} %  {name}")


if __name__ == "__main__":
    main()
