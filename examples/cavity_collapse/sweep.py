#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Run one of the reference paper's sweeps of cavity_collapse and collect its summaries.

    python3 sweep.py SWEEP [--cell MM] [--jobs N] [--binary PATH] [--output DIR]

SWEEP is one of (docs/physics.md section 8; docs/reproduction.md):
  weak-velocity    D(t) for v = 100, 150, 200 m/s, R = 10 mm
  weak-radius      D(t) for R = 0, 6, 8, 10 mm, v = 150 m/s
  strong-velocity  D(t) for v = 230, 300, 500, 700 m/s, R = 10 mm
  velocity-radius  maximum relative wall velocity and hot spot against v, R = 6, 8, 10 mm
  threshold        the asymmetric-collapse threshold speed for R = 6, 8, 10 mm (bisection)
  resolution       D_max and the hot spot at cells of 2, 1, 0.5 mm (v = 150 and 300, R = 10)
  all              every sweep above

Each run writes OUTPUT/SWEEP/<run>/ (series.csv, summary.csv); the sweep writes
OUTPUT/SWEEP/summary.csv (one row per run). plot_sweeps.py turns them into figures. Uses only
the standard library, so it runs with any python3.
"""
import argparse
import concurrent.futures
import csv
import hashlib
import os
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
GAP_MM = 4.0


def contact_us(v):
    """Nominal first contact: the 4 mm gap closes at 2v."""
    return GAP_MM * 1e-3 / (2 * v) * 1e6


class Runner:
    def __init__(self, args):
        self.binary = args.binary
        self.cell = args.cell
        self.out = Path(args.output)
        self.jobs = args.jobs
        # A finished run is reused only if the same binary made it: the flags name what a run
        # changes, the binary's defaults (the viscosity, the mass matrix, ...) the rest.
        self.binary_id = hashlib.sha256(Path(self.binary).read_bytes()).hexdigest()[:16]

    def run(self, sweep, v, r, after_us, cell=None):
        """One run; returns its summary row (a dict). Reuses a finished run with the same flags and binary."""
        cell = cell or self.cell
        name = f"v{v:g}_R{r:g}_h{cell:g}"
        out = self.out / sweep / name
        end = contact_us(v) + after_us
        flags = [f"--velocity={v:g}", f"--radius={r:g}", f"--cell={cell:g}", f"--end-us={end:.6g}",
                 "--snapshot-every-us=0", "--threads=1", "--quiet", "--no-figures", f"--output={out}"]
        stamp = out / "flags.txt"
        summary = out / "summary.csv"
        key = " ".join(flags) + f" [binary {self.binary_id}]"
        if not (summary.exists() and stamp.exists() and stamp.read_text() == key):
            out.mkdir(parents=True, exist_ok=True)
            done = subprocess.run([self.binary, *flags], capture_output=True, text=True)
            # 3: the library stopped the run (e.g. the EOS singularity); its outputs say where.
            if done.returncode not in (0, 3):
                sys.exit(f"sweep.py: {self.binary} {' '.join(flags)} failed:\n{done.stdout}{done.stderr}")
            stamp.write_text(key)
        with summary.open() as f:
            row = next(csv.DictReader(f))
        row["run"] = name
        print(f"  {sweep}: v = {v:g} m/s, R = {r:g} mm, cell {cell:g} mm: D_max {float(row['D_max_mm']):.3f} mm, "
              f"wall {float(row['max_wall_relative_velocity_m_s']):.0f} m/s, "
              f"hot spot {float(row['max_hotspot_temperature_K']):.0f} K "
              f"(settled {float(row['settled_hotspot_temperature_K']):.0f} K), {float(row['wall_s']):.0f} s"
              + ("" if row["status"] == "completed" else f" [{row['status'][:60]}]"), flush=True)
        return row

    def many(self, sweep, cases):
        """Runs (v, R, after_us[, cell]) cases, self.jobs at a time; writes the sweep's summary."""
        with concurrent.futures.ThreadPoolExecutor(self.jobs) as pool:
            rows = list(pool.map(lambda c: self.run(sweep, *c), cases))
        self.write(sweep, rows)
        return rows

    def write(self, sweep, rows):
        path = self.out / sweep / "summary.csv"
        path.parent.mkdir(parents=True, exist_ok=True)
        with path.open("w", newline="") as f:
            names = ["run"]
            for row in rows:  # runs by an older binary may lack a newer column
                names += [k for k in row if k not in names]
            w = csv.DictWriter(f, fieldnames=names, restval="")
            w.writeheader()
            w.writerows(rows)
        print(f"sweep.py: {path}")


def asymmetric(row):
    return row["lower_asymmetric"] == "1" or row["upper_asymmetric"] == "1"


def threshold(runner):
    """Bisection on v for each R: the slowest impact that collapses a cavity asymmetrically
    within 60 us of contact, to 5 m/s."""
    rows, table = [], []
    for r in (6, 8, 10):
        lo, hi = 50.0, 400.0
        row_hi = runner.run("threshold", hi, r, 60)
        rows.append(row_hi)
        if not asymmetric(row_hi):
            table.append({"radius_mm": r, "threshold_m_s": "> 400", "bracket_low_m_s": hi, "bracket_high_m_s": ""})
            continue
        while hi - lo > 5:
            mid = 0.5 * (lo + hi)
            row = runner.run("threshold", mid, r, 60)
            rows.append(row)
            lo, hi = (lo, mid) if asymmetric(row) else (mid, hi)
        table.append({"radius_mm": r, "threshold_m_s": f"{0.5 * (lo + hi):.1f}", "bracket_low_m_s": lo,
                      "bracket_high_m_s": hi})
    runner.write("threshold", rows)
    path = runner.out / "threshold" / "threshold.csv"
    with path.open("w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(table[0]))
        w.writeheader()
        w.writerows(table)
    print(f"sweep.py: {path}")


SWEEPS = {
    "weak-velocity": lambda run: run.many("weak-velocity", [(v, 10, 180) for v in (100, 150, 200)]),
    "weak-radius": lambda run: run.many("weak-radius", [(150, r, 180) for r in (0, 6, 8, 10)]),
    "strong-velocity": lambda run: run.many("strong-velocity", [(v, 10, 80) for v in (230, 300, 500, 700)]),
    "velocity-radius": lambda run: run.many(
        "velocity-radius", [(v, r, 40) for r in (6, 8, 10) for v in (100, 150, 200, 300, 400, 500, 600, 700)]),
    "threshold": threshold,
    "resolution": lambda run: run.many(
        "resolution", [(v, 10, after, h) for h in (2, 1, 0.5) for v, after in ((150, 180), (300, 40))]),
}


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("sweep", choices=[*SWEEPS, "all"])
    p.add_argument("--cell", type=float, default=1.0, help="cell size in mm (default 1)")
    p.add_argument("--jobs", type=int, default=2, help="runs at once, one thread each (default 2)")
    p.add_argument("--binary", default=str(HERE.parents[1] / "build/release/examples/cavity_collapse/cavity_collapse"))
    p.add_argument("--output", default="results/sweeps")
    args = p.parse_args()
    if not (args.cell > 0 and args.jobs >= 1):
        sys.exit("sweep.py: --cell must be > 0 and --jobs >= 1")
    if not os.access(args.binary, os.X_OK):
        sys.exit(f"sweep.py: no cavity_collapse binary at {args.binary}; build it (cmake --build --preset release "
                 "--target cavity_collapse) or pass --binary")
    runner = Runner(args)
    for name in SWEEPS if args.sweep == "all" else [args.sweep]:
        SWEEPS[name](runner)


if __name__ == "__main__":
    main()
