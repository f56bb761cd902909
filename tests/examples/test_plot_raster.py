#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""examples/cavity_collapse/plot.py's raster(): each particle is painted as its current domain,
its initial square mapped by its deformation gradient F, so that a lattice that has sheared,
rotated or stretched renders with no blank pixel inside the material, and only a real gap, about
a particle spacing wide or more, renders as a gap. numpy only (the drawing itself needs
matplotlib, which is stubbed).

Run: python3 tests/examples/test_plot_raster.py (exit status 0 when every case passes)."""
import math
import sys
import types
from pathlib import Path

import numpy as np

SCRIPT = Path(__file__).resolve().parent.parent.parent / "examples" / "cavity_collapse" / "plot.py"
for name in ("matplotlib", "matplotlib.pyplot"):
    sys.modules.setdefault(name, types.ModuleType(name))
sys.modules["matplotlib"].use = lambda *a, **k: None
sys.modules["matplotlib"].pyplot = sys.modules["matplotlib.pyplot"]
sys.path.insert(0, str(SCRIPT.parent))
import plot  # noqa: E402

SPACING = 0.25  # mm: the flagship's particle spacing at 0.5 mm cells
N = 40  # particles a side


def lattice(F, gap=0.0, with_F=True, shift=(0.0, 0.0)):
    """N x N particles at SPACING, the upper half moved up by `gap` (mm), then mapped by F (as a
    homogeneous deformation moves them) and shifted; each particle carries F."""
    i, j = np.meshgrid(np.arange(N), np.arange(N), indexing="ij")
    X = (i.ravel() + 0.5) * SPACING
    Y = (j.ravel() + 0.5) * SPACING + np.where(j.ravel() >= N // 2, gap, 0.0)
    x = F[0, 0] * X + F[0, 1] * Y + shift[0]
    y = F[1, 0] * X + F[1, 1] * Y + shift[1]
    m = {"x_mm": x, "y_mm": y, "T": np.ones(x.size)}
    if with_F:
        for k, (r, c) in zip(plot.F_COLUMNS, ((0, 0), (0, 1), (1, 0), (1, 1))):
            m[k] = np.full(x.size, F[r, c])
    return m


def pixel_centres(extent, image):
    ny, nx = image.shape
    x0, x1, y0, y1 = extent
    px = (x1 - x0) / nx
    return np.meshgrid(x0 + (np.arange(nx) + 0.5) * px, y0 + (np.arange(ny) + 0.5) * px)


def blank_inside(F, **kw):
    """Blank pixels whose centres lie inside the deformed lattice, one spacing in from its edge,
    over a few shifts of the lattice against the pixels; and the pixels counted."""
    blank = counted = 0
    for k in range(4):
        shift = (0.037 * k, 0.051 * k)
        image, extent = plot.raster(lattice(F, shift=shift, **kw), "T", SPACING)
        cx, cy = pixel_centres(extent, image)
        inv = np.linalg.inv(F)
        u = inv[0, 0] * (cx - shift[0]) + inv[0, 1] * (cy - shift[1])
        w = inv[1, 0] * (cx - shift[0]) + inv[1, 1] * (cy - shift[1])
        inner = (u > SPACING) & (u < (N - 1) * SPACING) & (w > SPACING) & (w < (N - 1) * SPACING)
        blank += int(np.isnan(image[inner]).sum())
        counted += int(inner.sum())
    return blank, counted


def rotation(deg):
    t = math.radians(deg)
    return np.array([[math.cos(t), -math.sin(t)], [math.sin(t), math.cos(t)]])


failures = []


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what)
    if not ok:
        failures.append(what)


CASES = {
    "sheared (simple shear 1.0)": np.array([[1.0, 1.0], [0.0, 1.0]]),
    "rotated 30 degrees": rotation(30),
    "rotated 30 degrees, stretched 1.8 along its x": rotation(30) @ np.diag([1.8, 1 / 1.8]),
    "sheared 0.5 and stretched 1.6 along x": np.array([[1.6, 0.5], [0.0, 1 / 1.6]]),
}
for name, F in CASES.items():
    blank, counted = blank_inside(F)
    check(counted > 1000 and blank == 0, f"{name}: {blank} blank of {counted} pixels inside the material")

# The test can fail: without F, a stretched lattice's squares leave blank seams.
blank, counted = blank_inside(CASES["rotated 30 degrees, stretched 1.8 along its x"], with_F=False)
check(blank > 0, f"squares without F on the stretched lattice: {blank} blank of {counted} (seams expected)")

# A 0.5 mm gap (two spacings) between the halves renders as a gap: every pixel whose centre lies
# in it, a pixel in from its edges, is blank, along the whole width.
image, extent = plot.raster(lattice(np.eye(2), gap=0.5), "T", SPACING)
cx, cy = pixel_centres(extent, image)
below = (N // 2 - 0.5) * SPACING + 0.525 * SPACING  # the top of the lower half's domains
above = (N // 2 + 0.5) * SPACING + 0.5 - 0.525 * SPACING  # the bottom of the upper half's
pixel = SPACING / 2
in_gap = (cy > below + pixel) & (cy < above - pixel) & (cx > 0) & (cx < N * SPACING)
painted = int(np.isfinite(image[in_gap]).sum())
check(in_gap.sum() > 0 and painted == 0, f"0.5 mm gap: {painted} of {int(in_gap.sum())} pixels in it painted")

# Without F columns (a map written before they existed) the particles are their squares.
blank, counted = blank_inside(np.eye(2), with_F=False)
check(blank == 0, f"undeformed lattice without F: {blank} blank of {counted}")

sys.exit(1 if failures else 0)
