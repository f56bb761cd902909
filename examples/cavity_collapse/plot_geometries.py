#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Several cavity_collapse runs side by side (the plane run's cylindrical cavity and the
spherical pores of the axisymmetric and 3-D runs, docs/reproduction.md "Spherical pores"):

    python3 plot_geometries.py OUT.png LABEL=DIR [LABEL=DIR ...]

draws, against the time after the nominal first contact, the lower cavity's axial chord over
its initial diameter, its upstream wall's speed (the jet's), and the mass hotter than
T_EP(v) + 100 K. The plane run's hot mass is per metre of depth (g/m) and the others' the whole
body's (g), so it has an axis of its own.
"""
import csv
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(directory):
    with open(Path(directory) / "series.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    with open(Path(directory) / "summary.csv", newline="") as f:
        summary = next(csv.DictReader(f))
    return rows, summary


def column(rows, name):
    return [float(r[name]) for r in rows]


def hot_column(rows):
    for name in rows[0]:
        if name.startswith("hot_mass_above_TEP_plus_100K_"):
            return name
    raise SystemExit("no hot-mass column above T_EP + 100 K")


def main(argv):
    if len(argv) < 3 or any("=" not in a for a in argv[2:]):
        raise SystemExit(__doc__)
    out = Path(argv[1])
    fig, (chord, jet, hot) = plt.subplots(1, 3, figsize=(15, 4.5))
    plane_axis = None
    for item in argv[2:]:
        label, directory = item.split("=", 1)
        rows, summary = read(directory)
        t = column(rows, "time_after_contact_us")
        diameter = 2 * float(summary["radius_mm"])
        is_open = [r["lower_cavity_open"] == "1" for r in rows]
        ratio = [float(r["lower_axial_chord_mm"]) / diameter if o else 0.0 for r, o in zip(rows, is_open)]
        (line,) = chord.plot(t, ratio, label=label)
        jet.plot(t, column(rows, "lower_upstream_wall_speed_m_s"), color=line.get_color(), label=label)
        name = hot_column(rows)
        grams = [1e3 * v for v in column(rows, name)]
        if summary.get("geometry", "plane") == "plane":
            plane_axis = plane_axis or hot.twinx()
            plane_axis.plot(t, grams, color=line.get_color(), linestyle="--", label=label + " (g/m, right)")
        else:
            hot.plot(t, grams, color=line.get_color(), label=label)
    chord.set_ylabel("lower cavity's axial chord / 2R")
    jet.set_ylabel("upstream wall speed (m/s)")
    hot.set_ylabel("mass above T_EP + 100 K (g, whole body)")
    if plane_axis is not None:
        plane_axis.set_ylabel("plane: mass above T_EP + 100 K (g per m of depth)")
    for ax in (chord, jet, hot):
        ax.set_xlabel("time after contact (us)")
        ax.grid(alpha=0.3)
    chord.legend(fontsize=8)
    handles, labels = hot.get_legend_handles_labels()
    if plane_axis is not None:
        more = plane_axis.get_legend_handles_labels()
        handles, labels = handles + more[0], labels + more[1]
    hot.legend(handles, labels, fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=100)
    print(f"wrote {out}")


if __name__ == "__main__":
    main(sys.argv)
