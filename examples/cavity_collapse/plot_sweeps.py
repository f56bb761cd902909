#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The reference paper's figures from the sweeps of sweep.py:

    python3 plot_sweeps.py [SWEEPS_DIR] [--figures DIR]

Reads SWEEPS_DIR (default results/sweeps)/<sweep>/summary.csv and each run's series.csv, and
writes to DIR (default SWEEPS_DIR/figures) whichever of these it has data for:
  D_weak_velocity.png, D_weak_radius.png, D_strong_velocity.png   D(t) like the paper's figures
  wall_velocity.png    maximum relative wall velocity against v for each R
  hot_spot.png         hot-spot temperature (5 us after its peak) against v for each R
  hot_spot_peak.png    its peak, when the jet lands
  hot_mass.png         the largest mass hotter than T_EP(v) + 100 K against v for each R
  collapse_mode.png    aspect at collapse and jet speed / v against v for each R
  threshold.png        the asymmetric-collapse threshold speed against R
  resolution.png       D_max and hot spot against the cell size
Needs matplotlib (Debian: python3-matplotlib; run with /usr/bin/python3).
"""
import argparse
import csv
from collections import defaultdict
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def rows(path):
    if not path.exists():
        return []
    with path.open() as f:
        return list(csv.DictReader(f))


def series(run_dir):
    data = rows(run_dir / "series.csv")
    return [float(r["time_after_contact_us"]) for r in data], [float(r["D_mm"]) for r in data]


def d_of_t(root, sweep, label, key, fig_dir, name, title):
    runs = rows(root / sweep / "summary.csv")
    if not runs:
        return
    fig, ax = plt.subplots(figsize=(5.6, 3.6))
    for r in runs:
        t, d = series(root / sweep / r["run"])
        ax.plot(t, d, lw=1.2, label=label.format(float(r[key])))
    ax.set_xlabel("time after contact (us)")
    ax.set_ylabel("D (mm)")
    ax.set_xlim(left=0)
    ax.set_ylim(0, None)
    ax.set_title(title + f" (cell {float(runs[0]['cell_mm']):g} mm)", fontsize=10)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(fig_dir / name, dpi=100)
    plt.close(fig)


def against_v(root, column, ylabel, fig_dir, name, title, log=False):
    runs = rows(root / "velocity-radius" / "summary.csv")
    if not runs:
        return
    by_r = defaultdict(list)
    for r in runs:
        if float(r[column]) > 0:  # -1: not reached (e.g. the run stopped first)
            by_r[float(r["radius_mm"])].append((float(r["velocity_m_s"]), float(r[column])))
    fig, ax = plt.subplots(figsize=(5.0, 3.6))
    for radius, pts in sorted(by_r.items()):
        pts.sort()
        ax.plot([p[0] for p in pts], [p[1] for p in pts], "o-", ms=3, lw=1.2, label=f"R = {radius:g} mm")
    if log:
        ax.set_yscale("log")
    ax.set_xlabel("impact speed v (m/s)")
    ax.set_ylabel(ylabel)
    ax.set_title(title + f" (cell {float(runs[0]['cell_mm']):g} mm)", fontsize=10)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(fig_dir / name, dpi=100)
    plt.close(fig)


def max_upstream_speed(run_dir):
    """The largest upstream wall speed while a cavity is open, from the run's series."""
    best = 0.0
    for r in rows(run_dir / "series.csv"):
        for side in ("lower", "upper"):
            if r[f"{side}_cavity_open"] == "1":
                best = max(best, float(r[f"{side}_upstream_wall_speed_m_s"]))
    return best


def collapse_mode(root, fig_dir):
    """The two measures of the collapse mode against v: the aspect at collapse (the threshold
    criterion) and the jet speed over v."""
    runs = rows(root / "velocity-radius" / "summary.csv")
    if not runs:
        return
    by_r = defaultdict(list)
    for r in runs:
        v = float(r["velocity_m_s"])
        aspect = float(r.get("lower_aspect_at_collapse") or -1)
        by_r[float(r["radius_mm"])].append((v, aspect, max_upstream_speed(root / "velocity-radius" / r["run"]) / v))
    fig, ax = plt.subplots(1, 2, figsize=(8.4, 3.4))
    for radius, pts in sorted(by_r.items()):
        pts.sort()
        coll = [p for p in pts if p[1] > 0]
        ax[0].plot([p[0] for p in coll], [p[1] for p in coll], "o-", ms=3, label=f"R = {radius:g} mm")
        ax[1].plot([p[0] for p in pts], [p[2] for p in pts], "o-", ms=3, label=f"R = {radius:g} mm")
    ax[0].axhline(1.25, color="grey", ls=":", lw=1)
    ax[0].set_ylabel("width / axial chord at collapse")
    ax[1].set_ylabel("max upstream wall speed / v")
    for a in ax:
        a.set_xlabel("impact speed v (m/s)")
        a.legend(fontsize=7)
    fig.suptitle(f"collapse mode (cell {float(runs[0]['cell_mm']):g} mm); dotted: the asymmetry cut", fontsize=9)
    fig.tight_layout()
    fig.savefig(fig_dir / "collapse_mode.png", dpi=100)
    plt.close(fig)


def threshold(root, fig_dir):
    table = rows(root / "threshold" / "threshold.csv")
    found = [t for t in table if t["bracket_high_m_s"]]
    if not found:
        return
    fig, ax = plt.subplots(figsize=(4.4, 3.4))
    r = [float(t["radius_mm"]) for t in found]
    ax.errorbar(r, [float(t["threshold_m_s"]) for t in found],
                yerr=[0.5 * (float(t["bracket_high_m_s"]) - float(t["bracket_low_m_s"])) for t in found],
                fmt="o-", label="gimlet")
    ax.plot([6, 8, 10], [120, 150, 200], "s--", label="paper")
    ax.set_xlabel("cavity radius R (mm)")
    ax.set_ylabel("threshold speed (m/s)")
    ax.set_title("asymmetric collapse threshold", fontsize=10)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(fig_dir / "threshold.png", dpi=100)
    plt.close(fig)


def resolution(root, fig_dir):
    runs = rows(root / "resolution" / "summary.csv")
    if not runs:
        return
    fig, ax = plt.subplots(1, 2, figsize=(8.0, 3.4))
    for v in sorted({float(r["velocity_m_s"]) for r in runs}):
        pts = sorted((float(r["cell_mm"]), float(r["D_max_mm"]), float(r["max_hotspot_temperature_K"]),
                      float(r["settled_hotspot_temperature_K"])) for r in runs if float(r["velocity_m_s"]) == v)
        h = [p[0] for p in pts]
        ax[0].plot(h, [p[1] for p in pts], "o-", label=f"v = {v:g} m/s")
        ax[1].plot(h, [p[2] for p in pts], "o-", label=f"v = {v:g} m/s, peak")
        # -1: the run ended less than 5 us after its peak, so there is no value to draw.
        settled = [(p[0], p[3]) for p in pts if p[3] > 0]
        ax[1].plot([q[0] for q in settled], [q[1] for q in settled], "s--",
                   label=f"v = {v:g} m/s, 5 us after the peak")
    ax[1].set_yscale("log")
    for a, label in zip(ax, ("D_max (mm)", "hot-spot temperature (K)")):
        a.set_xscale("log")
        a.set_xticks([0.5, 1, 2], ["0.5", "1", "2"])
        a.tick_params(axis="x", which="minor", bottom=False, labelbottom=False)
        a.set_xlabel("cell size (mm)")
        a.set_ylabel(label)
        a.legend(fontsize=7)
    fig.suptitle("resolution study, R = 10 mm", fontsize=10)
    fig.tight_layout()
    fig.savefig(fig_dir / "resolution.png", dpi=100)
    plt.close(fig)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("sweeps", nargs="?", default="results/sweeps")
    p.add_argument("--figures", default=None)
    args = p.parse_args()
    root = Path(args.sweeps)
    fig_dir = Path(args.figures) if args.figures else root / "figures"
    fig_dir.mkdir(parents=True, exist_ok=True)
    d_of_t(root, "weak-velocity", "v = {:g} m/s", "velocity_m_s", fig_dir, "D_weak_velocity.png", "D(t), R = 10 mm")
    d_of_t(root, "weak-radius", "R = {:g} mm", "radius_mm", fig_dir, "D_weak_radius.png", "D(t), v = 150 m/s")
    d_of_t(root, "strong-velocity", "v = {:g} m/s", "velocity_m_s", fig_dir, "D_strong_velocity.png",
           "D(t), R = 10 mm, strong shocks")
    against_v(root, "max_wall_relative_velocity_m_s", "max relative wall velocity (m/s)", fig_dir,
              "wall_velocity.png", "maximum relative wall velocity")
    against_v(root, "settled_hotspot_temperature_K", "hot-spot temperature (K)", fig_dir, "hot_spot.png",
              "hot spot, 5 us after its peak")
    against_v(root, "max_hotspot_temperature_K", "hot-spot temperature (K)", fig_dir, "hot_spot_peak.png",
              "hot spot, peak (jet landing)", log=True)
    # The hot material (summary.csv of runs that record it): the largest mass over the run
    # hotter than the bulk shock temperature T_EP(v) by 100 K.
    runs = rows(root / "velocity-radius" / "summary.csv")
    if runs and "max_hot_mass_above_TEP_plus_100K_kg_m" in runs[0]:
        against_v(root, "max_hot_mass_above_TEP_plus_100K_kg_m", "largest mass above T_EP + 100 K (kg/m)", fig_dir,
                  "hot_mass.png", "hot material")
    collapse_mode(root, fig_dir)
    threshold(root, fig_dir)
    resolution(root, fig_dir)
    print(f"plot_sweeps.py: figures in {fig_dir}")


if __name__ == "__main__":
    main()
