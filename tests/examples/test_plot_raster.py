#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""examples/cavity_collapse/plot.py's raster(): each particle is painted as its current domain,
its initial square mapped by its deformation gradient F, and the pixels within a spacing of its
centre, so that a lattice that has sheared, rotated or stretched, or particles mixed by the flow,
render with no blank pixel inside the material, and a real gap, wider than about a particle
spacing, renders as a gap. numpy only (the drawing itself needs matplotlib, which is stubbed).

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


def lattice(F, gap=0.0, with_F=True, shift=(0.0, 0.0), jitter=0.0, own_F=None):
    """N x N particles at SPACING, the upper half moved up by `gap` (mm), each moved by up to
    `jitter` spacings on each axis (a fixed seed), then mapped by F (as a homogeneous deformation
    moves them) and shifted; each particle carries F, or its own from own_F (an N^2 x 2 x 2
    array)."""
    i, j = np.meshgrid(np.arange(N), np.arange(N), indexing="ij")
    rng = np.random.default_rng(7)
    X = (i.ravel() + 0.5 + jitter * rng.uniform(-1, 1, N * N)) * SPACING
    Y = (j.ravel() + 0.5 + jitter * rng.uniform(-1, 1, N * N)) * SPACING + np.where(j.ravel() >= N // 2, gap, 0.0)
    x = F[0, 0] * X + F[0, 1] * Y + shift[0]
    y = F[1, 0] * X + F[1, 1] * Y + shift[1]
    m = {"x_mm": x, "y_mm": y, "T": np.ones(x.size)}
    if with_F:
        Fs = own_F if own_F is not None else np.broadcast_to(F, (x.size, 2, 2))
        for k, (r, c) in zip(plot.F_COLUMNS, ((0, 0), (0, 1), (1, 0), (1, 1))):
            m[k] = np.array(Fs[:, r, c])
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
    "rotated 30 degrees, stretched 2.5 along its x": rotation(30) @ np.diag([2.5, 1 / 2.5]),
    "sheared 0.5 and stretched 2.2 along x": np.array([[2.2, 0.5], [0.0, 1 / 2.2]]),
}
for name, F in CASES.items():
    blank, counted = blank_inside(F)
    check(counted > 1000 and blank == 0, f"{name}: {blank} blank of {counted} pixels inside the material")

# The test can fail: without F, the particles of a lattice stretched beyond about 1.4 are more
# than a spacing apart, and blank seams show between them.
blank, counted = blank_inside(CASES["rotated 30 degrees, stretched 2.5 along its x"], with_F=False)
check(blank > 0, f"without F, the stretched lattice: {blank} blank of {counted} (seams expected)")

# Particles mixed by the flow: each moved by up to 0.2 spacings, each with its own sliver of an F
# (stretched 5 along a random direction) that does not tile with its neighbours'.
angles = np.random.default_rng(11).uniform(0, np.pi, N * N)
slivers = np.array([rotation(math.degrees(t)) @ np.diag([5.0, 0.2]) @ rotation(-math.degrees(t)) for t in angles])
blank, counted = blank_inside(np.eye(2), jitter=0.2, own_F=slivers)
check(counted > 1000 and blank == 0, f"mixed particles with slivers of F: {blank} blank of {counted}")

# A 0.5 mm gap (two spacings) between the domains of the two halves renders as a gap: every pixel
# more than a spacing from the particle centres on both sides (the middle spacing of the gap) is
# blank, along the whole width, in at least one whole row.
image, extent = plot.raster(lattice(np.eye(2), gap=0.5), "T", SPACING)
cx, cy = pixel_centres(extent, image)
lower_row = (N // 2 - 0.5) * SPACING  # the centres of the lower half's top row
upper_row = (N // 2 + 0.5) * SPACING + 0.5  # and of the upper half's bottom row
in_gap = (cy > lower_row + SPACING) & (cy < upper_row - SPACING) & (cx > 0) & (cx < N * SPACING)
painted = int(np.isfinite(image[in_gap]).sum())
rows = int(np.isnan(image[:, (cx[0] > 0) & (cx[0] < N * SPACING)]).all(axis=1).sum())
check(in_gap.sum() > 0 and painted == 0 and rows >= 1,
      f"0.5 mm gap: {painted} of {int(in_gap.sum())} pixels in its middle painted; {rows} blank rows across")

# Without F columns (a map written before they existed) the particles are their squares.
blank, counted = blank_inside(np.eye(2), with_F=False)
check(blank == 0, f"undeformed lattice without F: {blank} blank of {counted}")

sys.exit(1 if failures else 0)
