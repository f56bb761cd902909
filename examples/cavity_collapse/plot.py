#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Figures of one cavity_collapse run: python3 plot.py OUTPUT_DIR (cavity_collapse runs it as
plot.py --follow CELL_MM OUTPUT_DIR, to draw the maps while the run goes on: Follower).

series.png: D, the relative wall velocity, the temperatures and the hot material against the
time after the nominal first contact. hot_material.png: the largest mass over the run hotter
than the bulk shock temperature T_EP(v) by each excess (the cumulative hot-spot curve).
map_NNNN.png: pressure and temperature of the particles at each snapshot.
maps_pressure.png, maps_temperature.png (from two snapshots up): every snapshot in one figure
per quantity, like the paper's snapshot figures. Errors of a --follow run go to plot.log, which
cavity_collapse names (docs/io.md, "The flagship's output folder").
"""
import csv
import math
import multiprocessing
import os
import sys
import threading
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# PNG files compressed at zlib's level 1 rather than Pillow's 6: the same pixels, files about a
# fifth larger, and encoding in a third of level 6's time, which is a fifth of the figures'
# (docs/performance.md, "The flagship's outputs").
PNG = {"pil_kwargs": {"compress_level": 1}}


def save(fig, path, dpi):
    """Writes fig to path as PNG through a temporary file in the same folder, renamed when
    complete: a figure drawn while the run goes on, or one whose process is stopped, is never
    seen half written."""
    temporary = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    try:
        fig.savefig(temporary, format="png", dpi=dpi, **PNG)
        os.replace(temporary, path)
    finally:
        if temporary.exists():
            temporary.unlink()


def read(path):
    with path.open() as f:
        rows = list(csv.DictReader(f))
    def number(text):
        try:
            return float(text)
        except ValueError:
            return text

    return {k: [number(r[k]) for r in rows] for k in rows[0]} if rows else {}


def read_map(path):
    """A particle map (all numbers) as one numpy column per field: the maps hold every particle,
    and matplotlib converts Python lists of that length element by element."""
    with path.open() as f:
        names = f.readline().strip().split(",")
    data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    if data.size == 0:  # a map of no particles
        return {k: np.empty(0) for k in names}
    return {k: data[:, j] for j, k in enumerate(names)}


def quantile(values, q):
    """The value at rank int(q (n - 1)) of the sorted finite values (None if there are none)."""
    values = values[np.isfinite(values)]
    if len(values) == 0:
        return None
    k = int(q * (len(values) - 1))
    return np.partition(values, k)[k]


def colour_limits(values, lo):
    """The colour scale of a map: from lo (the 0.1 % quantile where lo is None) to the 99.9 %
    quantile of the finite values (a few extreme particles would wash out the map), never
    below lo."""
    hi = quantile(values, 0.999)
    if lo is None:
        lo = quantile(values, 0.001)
    if lo is not None and hi is not None and hi < lo:
        hi = lo
    return lo, hi


def domains(m, ok, spacing):
    """The inverse of each kept particle's in-plane F (the identity where the map has no F, or
    where F is singular or not finite: the particle's domain is then its initial square) and
    the half-widths along x and y of its domain F [-h, h]^2 (h = 0.525 spacing), each at most
    MAX_REACH spacings (a particle stretched further is painted in part)."""
    half = 0.525 * spacing
    n = int(ok.sum())
    inv = np.tile(np.eye(2), (n, 1, 1))
    ex = np.full(n, half)
    ey = np.full(n, half)
    if not all(k in m for k in F_COLUMNS):
        return inv, ex, ey
    a, b, c, d = (np.asarray(m[k], dtype=float)[ok] for k in F_COLUMNS)
    det = a * d - b * c
    good = np.isfinite(det) & (np.abs(det) > 1e-9)
    inv[good] = np.stack([np.stack([d, -b], -1), np.stack([-c, a], -1)], -2)[good] / det[good, None, None]
    ex[good] = np.minimum(half * (np.abs(a) + np.abs(b))[good], MAX_REACH * spacing)
    ey[good] = np.minimum(half * (np.abs(c) + np.abs(d))[good], MAX_REACH * spacing)
    return inv, ex, ey


F_COLUMNS = ("F_xx", "F_xy", "F_yx", "F_yy")
MAX_REACH = 3  # spacings: the largest half-width of a particle's painted domain


def raster(m, key, spacing):
    """The particles of map m painted as an image, on pixels of half the spacing (about 2000 a
    side at most), empty pixels NaN (left blank). A pixel is material where its centre lies in a
    particle's current domain (its initial square, side 1.05 x the spacing, mapped by its
    deformation gradient F: the map's F_* columns) or within one spacing of a particle's centre;
    it takes the colour of m[key] of the nearest such particle.

    The domains tile a lattice that has rotated, sheared or stretched, where particles drawn
    apart would leave blank seams between fixed squares. Where the flow has mixed the particles
    (in a collapsed cavity's jet, stretches of 3 to 60 and slivers narrower than a pixel, whose F
    disagree with their neighbours') the domains leave specks, and the spacing around each
    centre fills them: there the particles are as dense as elsewhere, and no pixel is more than
    about 1.4 spacings from a centre. So a gap shows where it is wider than about one spacing
    (the material's edges are drawn up to half a spacing beyond the domains' edges).

    A particle far from the rest (flung off) would shrink the material to a few pixels: the
    image covers the 0.1-99.9 % range of the places on each axis, widened by a twentieth of it
    and two spacings, and leaves out what lies beyond. Returns (image, extent) for
    imshow(origin="lower"), or None if no particle has a finite place.

    An image instead of a scatter of one marker per particle: drawing 54,000 markers a panel is
    most of the figures' time, and markers under a pixel wide leave a moire of blank specks where
    the particles tile the material."""
    x, y, v = m["x_mm"], m["y_mm"], m[key]
    ok = np.isfinite(x) & np.isfinite(y)
    if not ok.any():
        return None
    for c in (x, y):
        lo, hi = quantile(c[ok], 0.001), quantile(c[ok], 0.999)
        margin = 0.05 * (hi - lo) + 2 * spacing
        ok &= (c >= lo - margin) & (c <= hi + margin)
    half = 0.525 * spacing
    inv, ex, ey = domains(m, ok, spacing)
    ex, ey = np.maximum(ex, spacing), np.maximum(ey, spacing)  # the spacing around each centre
    x, y, v = x[ok], y[ok], v[ok]
    x0, y0 = (x - ex).min(), (y - ey).min()
    width, height = (x + ex).max() - x0, (y + ey).max() - y0
    px = max(spacing / 2, width / 2000, height / 2000)
    nx = int(width / px) + 1
    ny = int(height / px) + 1
    image = np.full(ny * nx, np.nan, dtype=np.float32)
    nearest = np.full(ny * nx, np.inf)  # squared distance to the particle that painted the pixel
    # Every pixel of the painted area's bounding box, in at most `span` steps per axis.
    ix0 = ((x - ex - x0) / px).astype(int)
    iy0 = ((y - ey - y0) / px).astype(int)
    ix1 = np.minimum(((x + ex - x0) / px).astype(int), nx - 1)
    iy1 = np.minimum(((y + ey - y0) / px).astype(int), ny - 1)
    span = int(max((ix1 - ix0).max(), (iy1 - iy0).max()))
    for a in range(span + 1):
        ix = np.minimum(ix0 + a, ix1)
        dx = x0 + (ix + 0.5) * px - x
        for b in range(span + 1):
            iy = np.minimum(iy0 + b, iy1)
            dy = y0 + (iy + 0.5) * px - y
            d2 = dx * dx + dy * dy
            paint = (d2 <= spacing * spacing) | \
                    ((np.abs(inv[:, 0, 0] * dx + inv[:, 0, 1] * dy) <= half) &
                     (np.abs(inv[:, 1, 0] * dx + inv[:, 1, 1] * dy) <= half))
            k = iy[paint] * nx + ix[paint]
            d2, colour = d2[paint], v[paint]
            np.minimum.at(nearest, k, d2)
            won = d2 <= nearest[k]
            image[k[won]] = colour[won]
    return image.reshape(ny, nx), (x0, x0 + nx * px, y0, y0 + ny * px)


def plot_series(out):
    """series.png: the run's time series."""
    s = read(out / "series.csv")
    t = s["time_after_contact_us"]
    fig, ax = plt.subplots(4, 1, figsize=(6.4, 9.4), sharex=True)
    ax[0].plot(t, s["D_mm"], lw=1.2)
    ax[0].set_ylabel("D (mm)")
    ax[1].plot(t, s["wall_relative_velocity_m_s"], lw=1.0)
    ax[1].set_ylabel("relative wall\nvelocity (m/s)")
    ax[2].plot(t, s["max_temperature_K"], lw=1.0, label="hottest particle")
    ax[2].plot(t, s["hotspot_temperature_K"], lw=1.2, label="hot spot (disc mean)")
    ax[2].set_ylabel("temperature (K)")
    ax[2].legend()
    # The hot-spot distribution: mass hotter than the bulk shock temperature T_EP(v) by each excess.
    hot = [k for k in s if k.startswith("hot_mass_above_TEP_plus_")]
    for k in hot:
        excess = k[len("hot_mass_above_TEP_plus_"):].split("K")[0]
        ax[3].plot(t, [1e3 * v for v in s[k]], lw=1.0, label=f"T - T_EP > {excess} K")
    ax[3].set_ylabel("hot mass (g/m)")
    ax[3].set_yscale("symlog", linthresh=1e-3)
    if hot:
        ax[3].legend(fontsize=7)
    ax[3].set_xlabel("time after contact (us)")
    fig.tight_layout()
    save(fig, out / "series.png", 110)
    plt.close(fig)


def plot_hot_material(out):
    """hot_material.png: the cumulative hot-spot curve."""
    # The cumulative hot-spot curve: the largest mass over the run above T_EP + excess.
    summary = read(out / "summary.csv") if (out / "summary.csv").exists() else {}
    levels = [k for k in summary if k.startswith("max_hot_mass_above_TEP_plus_")]
    if levels:
        excess = [float(k[len("max_hot_mass_above_TEP_plus_"):].split("K")[0]) for k in levels]
        fig, a = plt.subplots(figsize=(5.0, 3.6))
        a.plot(excess, [1e3 * summary[k][0] for k in levels], "o-")
        a.set_xscale("log")
        a.set_yscale("symlog", linthresh=1e-3)
        a.set_xlabel("T - T_EP (K)")
        a.set_ylabel("largest mass above it (g/m)")
        a.set_title(f"hot material, T_EP = {summary['bulk_shock_temperature_K'][0]:.1f} K", fontsize=9,
                    y=1.0)  # placed, not measured (plot_maps says why)
        fig.tight_layout()
        save(fig, out / "hot_material.png", 110)
        plt.close(fig)

# The many-panel figures: the whole pair of blocks in pressure, the upper block (body 1) in
# temperature (the paper shows only that one). Each: the map's column, upper block only, the
# colour bar's label, colour map and lower limit, the file.
PANELS = (("pressure_MPa", False, "pressure (MPa)", "viridis", None, "maps_pressure.png"),
          ("temperature_K", True, "temperature (K)", "inferno", 300.0, "maps_temperature.png"))


# A map's two sides, the many-panel figures' quantities (every particle on both): the column,
# the colour bar's label, colour map and lower limit.
MAP_SIDES = tuple((key, label, cmap, lo) for key, _, label, cmap, lo, _ in PANELS)

# This process's map figure, kept from one map to the next: building its axes, their ticks and
# the colour bars is a third of a map's time. A map drawn on the kept figure is the same PNG
# file, byte for byte, as one drawn on a new figure (the quickstart's nine maps compared).
KEPT_MAP_FIGURE = {}


def map_figure(figure, sides, tc):
    """Draws one map on figure (a dict: empty for a new one, or the one an earlier map left) and
    returns the matplotlib figure. sides: per MAP_SIDES entry, the image and extent (or None,
    that side left empty) and the colour limits. A figure kept for the next map must have had
    both sides drawn."""
    if not figure:
        fig, ax = plt.subplots(1, 2, figsize=(8.0, 5.2), sharey=True)
        for a in ax:
            a.set_aspect("equal")
            a.set_xlabel("x (mm)")
        ax[0].set_ylabel("y (mm)")
        # Margins set by hand, the widest tight_layout chooses over the quickstart's nine maps
        # (their tick labels' widths vary): a layout engine measures every label, a quarter of
        # the map's time, and fixed margins give every map the same layout.
        fig.subplots_adjust(left=0.035, right=0.944, bottom=0.112, top=0.905, wspace=0.075)
        figure.update(fig=fig, axes=ax, title=fig.suptitle(""), images={})
    fig = figure["fig"]
    for a, (key, label, cmap, _), (drawn, (vmin, vmax)) in zip(figure["axes"], MAP_SIDES, sides):
        if drawn is None:
            continue
        image = figure["images"].get(key)
        if image is None:
            image = figure["images"][key] = a.imshow(drawn[0], origin="lower", extent=drawn[1], cmap=cmap,
                                                     vmin=vmin, vmax=vmax)
            fig.colorbar(image, ax=a, label=label, shrink=0.8)
        else:
            image.set_data(drawn[0])
            image.set_extent(drawn[1])
            image.set_clim(vmin, vmax)
            a.relim()  # the view fits this map's image alone
            a.autoscale_view()
    figure["title"].set_text(f"t = {tc:.1f} us after contact")
    return fig


def plot_map(out, spacing, i, tc):
    """map_NNNN.png: pressure and temperature of every particle at one snapshot. Returns this
    snapshot's panels of the many-panel figures, one per PANELS entry: (image and extent, or
    None; the values shown), so that each map is read once."""
    m = read_map(out / "snapshots" / f"map_{int(i):04d}.csv")
    panels = []
    for key, upper_only, *_ in PANELS:
        part = {k: col[m["body"] == 1] for k, col in m.items()} if upper_only else m
        # A copy of the column: a view would keep every column of the map alive with it.
        panels.append((raster(part, key, spacing), np.array(part[key])))
    whole = {key: image for (key, upper_only, *_), (image, _) in zip(PANELS, panels) if not upper_only}
    sides = [(whole[key] if key in whole else raster(m, key, spacing), colour_limits(m[key], lo))
             for key, _, _, lo in MAP_SIDES]
    keep = all(drawn is not None for drawn, _ in sides)  # else a figure of its own
    figure = KEPT_MAP_FIGURE if keep else {}
    try:
        fig = map_figure(figure, sides, tc)
        save(fig, out / f"map_{int(i):04d}.png", 100)
    except BaseException:
        keep = False  # a figure left half changed is not kept for the next map
        raise
    finally:
        if not keep and figure:
            plt.close(figure["fig"])
            figure.clear()
    return panels


# All snapshots in one figure per quantity, like the paper's snapshot figures (PANELS says
# which particles). The panels form a grid whose shape keeps the figure near 4:3 with few empty
# panels, each titled with its time, and share one colour scale and one colour bar.
def plot_maps(out, times, panels, label, cmap, lo, name):
    """maps_pressure.png / maps_temperature.png: every snapshot of one quantity, from the
    snapshots' panels as plot_map returns them."""
    n = len(times["index"])
    drawn = [image for image, _ in panels]
    shown = [d[1] for d in drawn if d is not None]
    if not shown:
        return
    # One view for every panel (the axes are shared): the union of the images' extents.
    box = (min(e[0] for e in shown), max(e[1] for e in shown), min(e[2] for e in shown), max(e[3] for e in shown))
    ratio = (box[3] - box[2]) / max(box[1] - box[0], 1e-9)  # panel height over width
    best = None
    for cols in range(1, n + 1):
        rows = math.ceil(n / cols)
        if rows * cols - n >= cols:
            continue  # a whole empty row
        miss = abs(rows * ratio / cols - 0.75) + 0.1 * (rows * cols - n)  # empty panels cost too
        if best is None or miss < best[0]:
            best = (miss, rows, cols)
    _, rows, cols = best
    # The layout in inches, set by hand: a layout engine measures every tick label of every
    # panel, a third of the figure's time.
    width, height = 2.4, 2.4 * ratio  # a panel
    left, right, bottom, top, title, gap = 0.55, 1.25, 0.45, 0.1, 0.25, 0.12
    fig_w = left + cols * width + (cols - 1) * gap + right
    fig_h = bottom + rows * (height + title) + top
    fig, axes = plt.subplots(rows, cols, figsize=(fig_w, fig_h), squeeze=False, sharex=True, sharey=True)
    fig.subplots_adjust(left=left / fig_w, right=1 - right / fig_w, bottom=bottom / fig_h,
                        top=1 - (top + title) / fig_h, wspace=gap / width, hspace=title / height)
    vmin, vmax = colour_limits(np.concatenate([values for _, values in panels]), lo)  # one scale
    sc = None
    for k, a in enumerate(axes.ravel()):
        if k >= n:
            a.axis("off")
            continue
        if drawn[k] is not None:
            sc = a.imshow(drawn[k][0], origin="lower", extent=drawn[k][1], cmap=cmap, vmin=vmin, vmax=vmax)
        a.set_aspect("equal")
        # y given: matplotlib otherwise measures every tick label to place each title (a sixth of
        # the figure's time) and puts it at the same place, 1.0, with no ticks on top.
        a.set_title(f"t = {times['time_after_contact_us'][k]:.1f} us after contact", fontsize=9, y=1.0)
        a.tick_params(labelsize=7)
    for a in axes[:, 0]:
        a.set_ylabel("y (mm)", fontsize=8)
    for a in axes[-1, :]:
        a.set_xlabel("x (mm)", fontsize=8)
    axes[0, 0].set_xlim(box[0], box[1])
    axes[0, 0].set_ylim(box[2], box[3])
    if sc is not None:  # one colour bar beside the grid, as tall as the panels
        bar = fig.add_axes([1 - (right - gap) / fig_w, bottom / fig_h, 0.15 / fig_w,
                            (rows * height + (rows - 1) * title) / fig_h])
        fig.colorbar(sc, cax=bar).set_label(label, fontsize=9)
        bar.tick_params(labelsize=8)
    save(fig, out / name, 90)
    plt.close(fig)


def lower_priority():
    """Leave the processor to the run: SCHED_IDLE runs this process only on a core the run has
    left idle (its serial phases, its threads' waits), and a core the run wants is handed back
    at once; where the policy is missing, the lowest nice value."""
    try:
        os.sched_setscheduler(0, os.SCHED_IDLE, os.sched_param(0))
    except (AttributeError, OSError):
        try:
            os.nice(19)
        except OSError:
            pass


def draw_while_running(out, spacing, jobs, results, parents_ends):
    """The child of --follow: asks its parent for a job, does it, and asks again (its reply is
    the next request), from idle processor time only. A job: a snapshot's map, whose panels it
    sends back, or, after the last map, one of the many-panel figures, which it draws if it drew
    every map itself. A figure that fails here is drawn again, and its error reported, at the end."""
    lower_priority()
    # The parent's ends of the two pipes, copied by the fork: closed, so that if the parent
    # dies the child reads the end of its jobs and exits rather than wait for ever.
    # (multiprocessing has already pointed the child's standard input, the run's pipe, at
    # /dev/null, so the run does not wait on the child either.)
    for end in parents_ends:
        end.close()
    panels = {}
    try:
        results.send(("ready",))
        for job in iter(jobs.recv, None):
            reply = ("failed",)
            try:
                if job[0] == "map":
                    _, i, tc = job
                    panels[i] = plot_map(out, spacing, i, tc)
                    reply = ("map", i, panels[i])
                elif len(job[2]["index"]) >= 2 and sorted(panels) == list(range(len(job[2]["index"]))):
                    # every map of the run, from the first, drawn here
                    _, k, times = job
                    _, _, label, cmap, lo, name = PANELS[k]
                    plot_maps(out, times, [panels[i][k] for i in times["index"]], label, cmap, lo, name)
                    reply = ("many-panel", k)
            except Exception:  # noqa: BLE001 (drawn again, and reported, at the end)
                pass
            results.send(reply)
    except (EOFError, OSError):  # the parent has gone (its pipes closed): so does the child
        pass


class Follower:
    """The figures of a run still going on (plot.py --follow). The run writes one line on this
    script's standard input after each snapshot's map, INDEX TIME_AFTER_CONTACT_US, with the
    word `last` after the last map it will write, and the line `end` when it has ended and its
    files are complete. Its input closed without `end` (the run failed or was stopped), nothing
    more is drawn: the child is stopped and the script exits with status 1. A child process at
    idle priority draws
    the maps as they come, and the many-panel figures after the last, from processor time the
    run leaves idle. It takes one job at a time, so that at the run's end the jobs it has not
    started go to the figures drawn at full priority (draw()), while it finishes its own."""

    def __init__(self, out, spacing):
        context = multiprocessing.get_context("fork")
        jobs, self.to_child = context.Pipe(duplex=False)
        self.from_child, results = context.Pipe(duplex=False)
        self.child = context.Process(target=draw_while_running,
                                     args=(out, spacing, jobs, results, (self.to_child, self.from_child)), daemon=True)
        self.child.start()
        jobs.close(), results.close()  # the child's ends: the parent sees the child's exit as EOF
        self.panels, self.many_panel = {}, set()  # the many-panel figures drawn: PANELS' indices
        self.lock = threading.Lock()
        self.pending, self.current, self.idle, self.ended = [], None, False, False
        self.times = {"index": [], "time_after_contact_us": []}
        self.receiver = threading.Thread(target=self.receive, daemon=True)
        self.receiver.start()

    def send(self, job):  # under the lock
        try:
            self.to_child.send(job)
        except OSError:  # the child has ended: its jobs are drawn at the end
            pass

    def hand_over(self):  # under the lock: the child is free
        self.current = None
        if self.ended:
            self.send(None)
        elif self.pending:
            self.current = self.pending.pop(0)
            self.send(self.current)
        else:
            self.idle = True

    def add(self, job):
        with self.lock:
            self.pending.append(job)
            if self.idle:
                self.idle = False
                self.hand_over()

    def receive(self):  # the child's replies, as they come (its sends block until read)
        while True:
            try:
                done = self.from_child.recv()
            except (EOFError, OSError):  # the child has ended (a reply cut short by the kill too)
                return
            with self.lock:
                if done[0] == "map":
                    self.panels[done[1]] = done[2]
                elif done[0] == "many-panel":
                    self.many_panel.add(done[1])
                self.hand_over()

    def read(self, lines):
        """Hands the child each map the run reports; returns at the run's end."""
        for line in lines:
            if line.strip() == "end":
                return
            i, tc, *last = line.split()
            self.times["index"].append(int(i))
            self.times["time_after_contact_us"].append(float(tc))
            self.add(("map", int(i), float(tc)))
            if last:
                for k in range(len(PANELS)):
                    self.add(("many-panel", k, {key: list(v) for key, v in self.times.items()}))
        # No `end`: the run failed, or was stopped, and its files may be incomplete.
        self.child.kill()
        sys.exit(1)

    def stop(self):
        """The run is over: the child gets no more jobs. Returns the job it is doing, ("map",
        index) or ("many-panel", PANELS' index), or None."""
        with self.lock:
            self.ended, self.pending = True, []
            if self.idle:
                self.send(None)
            return self.current[:2] if self.current else None

    def finish(self, timeout):
        """Waits for the child to finish its job, at most timeout seconds, then stops it."""
        self.child.join(timeout)
        if self.child.is_alive():
            self.child.kill()
            self.child.join()
        self.receiver.join()


def draw(out, spacing, follower=None):
    """Every figure of the run in out, on every core this process may use (the run that wrote
    the data is over): the snapshots' maps the follower's child (if any) has not drawn (each
    read once; each returns its panels of the many-panel figures), the series and the hot
    material, then the two many-panel figures, which need every snapshot's panel, unless the
    child drew them. Every figure is attempted; if any failed, the first failure's error is
    raised at the end, after the others are written."""
    busy = follower.stop() if follower else None  # the child's job, which it goes on with
    busy_map = busy[1] if busy and busy[0] == "map" else None
    panels = follower.panels if follower else {}
    snaps = out / "snapshots"
    times = read(snaps / "times.csv") if (snaps / "times.csv").exists() else {}
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)
    snapshots = list(zip(times.get("index", []), times.get("time_after_contact_us", [])))
    todo = [(i, tc) for i, tc in snapshots if int(i) not in panels and int(i) != busy_map]
    errors = []

    def result(done):
        try:
            return done.result()
        except Exception as e:  # noqa: BLE001 (reported at the end)
            errors.append(e)

    drawn = follower.many_panel if follower else set()
    submitted = set()

    def many_panel(skip):  # the many-panel figures not drawn yet, once every snapshot's panel is in
        if len(snapshots) < 2 or errors:
            return []
        ordered = [panels[int(i)] for i, _ in snapshots]
        jobs = [(k, pool.submit(plot_maps, out, times, [p[k] for p in ordered], label, cmap, lo, name))
                for k, (_, _, label, cmap, lo, name) in enumerate(PANELS)
                if k not in drawn and k not in submitted and (k,) != skip]
        submitted.update(k for k, _ in jobs)
        return [done for _, done in jobs]

    with ProcessPoolExecutor(max_workers=max(1, min(len(todo) + 2, cores))) as pool:
        # Every panel in (the child drew every map): the many-panel figures, the longest, first,
        # but for the one the child is drawing.
        first = many_panel(busy[1:] if busy else None) if not todo and busy_map is None else []
        maps = [(int(i), pool.submit(plot_map, out, spacing, i, tc)) for i, tc in todo]
        rest = first + [pool.submit(plot_series, out), pool.submit(plot_hot_material, out)]
        found = {i: result(done) for i, done in maps}
        if follower:
            # The child's last job, once the pool's maps are done: on an idle machine it then
            # has a core of its own, and its longest job (a many-panel figure) takes a third of
            # a second; on a busy one, at idle priority, it may not run at all, so after 1 s it
            # is stopped and its job drawn again.
            follower.finish(timeout=1.0)
            if busy_map is not None and busy_map not in panels:  # stopped before it was done
                found[busy_map] = result(pool.submit(plot_map, out, spacing, busy_map, dict(snapshots)[busy_map]))
        panels.update({i: p for i, p in found.items() if p is not None})
        rest += many_panel(None)  # those the child did not draw, and did not finish
        for done in rest:
            result(done)
    if errors:
        raise errors[0]


def exit_now():
    """Ends the process once every figure is drawn, without the interpreter's teardown: freeing
    matplotlib's objects one by one takes about 0.1 s, which the run would wait for (it waits for
    this script). Every figure is written and renamed by then, and every process this script
    started has ended (the pool's, and the child, joined or stopped by finish())."""
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(0)


if __name__ == "__main__":
    if sys.argv[1] == "--follow":  # plot.py --follow CELL_MM OUTPUT_DIR, from cavity_collapse
        out, spacing = Path(sys.argv[3]), float(sys.argv[2]) / 2  # 2 x 2 particles per cell
        follower = Follower(out, spacing)
        follower.read(sys.stdin)
        draw(out, spacing, follower)
    else:
        out = Path(sys.argv[1])
        # 2 x 2 particles per cell
        spacing = read(out / "summary.csv")["cell_mm"][0] / 2 if (out / "summary.csv").exists() else 0.25
        draw(out, spacing)
    exit_now()  # draw() raised if a figure failed: the normal exit, with its status and message
