#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Plot the pressure profiles of contact_validation: python3 plot.py OUTPUT_DIR."""
import csv
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

out = Path(sys.argv[1])
labels = {"single": "single field", "bardenhagen": "Bardenhagen et al. 2000", "distance": "distance-switched (paper)"}
fig, ax = plt.subplots(figsize=(6.4, 4.0))
for policy, label in labels.items():
    path = out / f"profile_{policy}.csv"
    if not path.exists():
        continue
    with path.open() as f:
        rows = list(csv.DictReader(f))
    ax.plot([float(r["y_mm"]) for r in rows], [float(r["pressure_Pa"]) / 1e9 for r in rows], label=label, lw=1.2)
ax.set_xlabel("y (mm)")
ax.set_ylabel("pressure (GPa)")
ax.set_title("pressure along the vertical centre line")
ax.legend()
fig.tight_layout()
fig.savefig(out / "profiles.png", dpi=120)
