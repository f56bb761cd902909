#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The serial share of a multi-threaded run, from where its threads' samples fall in time
(docs/performance.md, "What limits scaling to 16 threads, from the one-thread profile"): what a
machine with few cores says of what limits scaling to many.

    serial_share.py [--frequency HZ] [--window MS] [--after SYMBOL] [--top N] -- COMMAND [ARG ...]

runs COMMAND under `perf record` (every thread sampled at HZ, 15000 by default) and counts a
sample of the process's first thread as serial where no other thread of the process has a
sample within MS milliseconds either side (0.15 by default): the other threads were asleep.
Under OMP_WAIT_POLICY=passive, OpenMP's idle threads sleep at once, so the serial samples are
the code that runs on one thread (and the tails of passes where the others have finished);
under active waiting the idle threads spin, and nothing reads as serial. With --after, the count
starts after the first thread's last sample in a function whose name contains SYMBOL (a set-up
to leave out, such as seed_particles), and it ends at the other threads' last sample either way.

Prints the share of the first thread's samples that are serial, and the functions that hold
the most of them (template arguments left out). By Amdahl's law a serial share f of a run on
T threads caps N threads at 1 / (f + (1 - f) T / N) times the T-thread rate. Needs perf (Debian:
linux-perf, which scripts/setup.sh --bench installs) and permission to sample the process."""
import argparse
import bisect
import collections
import re
import subprocess
import sys
import tempfile
from pathlib import Path


def samples(data):
    """(pid, tid, time, function) of every sample in perf's file `data`."""
    script = subprocess.run(["perf", "script", "-i", str(data), "-F", "pid,tid,time,ip,sym"], check=True,
                            capture_output=True, text=True).stdout
    line = re.compile(r"\s*(\d+)/(\d+)\s+([\d.]+):\s*[0-9a-f]+\s*(.*)")
    for text in script.splitlines():
        m = line.match(text)
        if m:
            yield int(m[1]), int(m[2]), float(m[3]), m[4].strip()


def short(function):
    """A function's name without its template arguments and parameters (the part before '<' or
    '('), or [unknown]."""
    name = re.split(r"[<(]", function, maxsplit=1)[0].strip()
    return name or "[unknown]"


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
        record = subprocess.run(["perf", "record", "-q", "-F", str(args.frequency), "-o", str(data), "--"] + command)
        if record.returncode != 0:
            sys.exit(f"serial_share.py: perf record {' '.join(command)} exited with {record.returncode}")
        found = list(samples(data))
    # The command's process: the one whose first thread (tid = pid) has the most samples (perf
    # may run the command through a shell or a wrapper first).
    per_process = collections.Counter(pid for pid, tid, _, _ in found if pid == tid)
    if not per_process:
        sys.exit("serial_share.py: no samples (is perf allowed to sample? see perf_event_paranoid)")
    pid = per_process.most_common(1)[0][0]
    first = [(t, f) for p, tid, t, f in found if p == pid and tid == pid]
    others = sorted(t for p, tid, t, _ in found if p == pid and tid != pid)
    threads = len({tid for p, tid, _, _ in found if p == pid})
    if not others:
        sys.exit(f"serial_share.py: only the first thread of process {pid} has samples: nothing to compare")
    start = first[0][0]
    if args.after:
        ends = [t for t, f in first if args.after in f]
        if not ends:
            sys.exit(f"serial_share.py: no sample of the first thread in a function named like '{args.after}'")
        start = max(ends)
    end = others[-1]
    window = args.window * 1e-3
    counted = [(t, f) for t, f in first if start < t <= end]
    serial = collections.Counter()
    for t, f in counted:
        k = bisect.bisect_left(others, t - window)
        if k == len(others) or others[k] > t + window:
            serial[short(f)] += 1
    total = sum(serial.values())
    print(f"threads with samples: {threads}; the first thread's samples counted: {len(counted)} "
          f"over {end - start:.2f} s ({args.frequency} Hz, a window of {args.window} ms either side)")
    print(f"serial: {total} samples, {100 * total / max(1, len(counted)):.2f} % of them")
    for name, n in serial.most_common(args.top):
        print(f"  {100 * n / max(1, len(counted)):6.2f} %  {name}")


if __name__ == "__main__":
    main()
