#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The communication model of a run on many processes (docs/performance.md, "Many processes").

Each process owns consecutive slabs of node rows along the grid's last axis. Per step it exchanges,
with each neighbouring process, the bands of SLAB_ROWS node rows both add to: every slab pass
that adds into nodal arrays sends its running sums one way and the completed sums back (one
message each way per band), the contact's reaches once, and the particles that cross. The
collectives (time step, closing speed, health, the stages' failure checks) are a few dozen
allreduces of a few bytes. This script counts the bytes and messages and predicts the time per
step from a particle-update time, the node passes and a network's bandwidth and latency.

    python3 benchmarks/mpi/model.py                 # the 3-D flagship at 0.25 mm (defaults below)
    python3 benchmarks/mpi/model.py --cell 0.5      # another cell (mm)

Assumptions (each a flag): double precision; uGIMP (slab rows 2); the flagship's fields (2 bodies x
2 sides for self-contact = 4 blocks), MUSL with the consistent mass (k = 4 iterations) and the
distance contact, so the bands carry per entry: P2G mass + momentum + force (8 + 24 + 24 bytes),
the mass gradients (24), k products M a (24 each) and MUSL's re-mapped momentum (24); all of a
band's entries are sent, empty or not; self-contact merges per band entry of each body its reference
direction (40 bytes), fronts (16) and gaps (1). The flagship measures the hot spot every step: each
process receives from each neighbour the particles within one bin (the hot-spot radius R) of its
box, on average 1.5 R of the neighbour's particles along the last axis, 48 bytes each (ordinal,
position, mass, temperature). A particle-update takes T_U seconds on one core (measured:
0.78 us for the 3-D array at 2 mm on this machine, setup included); the node passes cost T_E a
grid entry and step. A process has C cores at an efficiency (EFF) of one core each.
"""
import argparse
import math


def main():
    a = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    a.add_argument("--cell", type=float, default=0.25, help="cell (mm)")
    a.add_argument("--lateral", type=float, default=40.0, help="block width along the two other axes (mm)")
    a.add_argument("--length", type=float, default=100.0, help="the pair's length along the last axis (mm)")
    a.add_argument("--ghost", type=int, default=3, help="ghost nodes beyond each side (uGIMP: 3)")
    a.add_argument("--slab-rows", type=int, default=2)
    a.add_argument("--fields", type=int, default=4)
    a.add_argument("--k", type=int, default=4, help="consistent-mass iterations")
    a.add_argument("--t-u", type=float, default=0.7e-6, help="s a particle-update on one core")
    a.add_argument("--t-e", type=float, default=8e-9, help="s a grid entry and step in the node passes, one core")
    a.add_argument("--cores", type=int, default=16, help="cores (threads) a process")
    a.add_argument("--eff", type=float, default=0.6, help="threads' efficiency (16 threads: 10x one thread measured)")
    a.add_argument("--bandwidth", type=float, default=12.5e9, help="bytes/s a process and direction (100 Gb/s)")
    a.add_argument("--latency", type=float, default=3e-6, help="s a message")
    a.add_argument("--allreduces", type=int, default=24, help="allreduces a step")
    a.add_argument("--particle-bytes", type=float, default=250, help="bytes a particle's fields (3-D HMX)")
    a.add_argument("--stencil-bytes", type=float, default=27 * 4 * 8 + 117, help="bytes a particle's weights and entry list (3-D)")
    a.add_argument("--entry-bytes", type=float, default=8 * 13 + 8 * 3 * 4, help="bytes a grid entry's arrays")
    a.add_argument("--hot-spot-radius", type=float, default=0.75, help="mm, the hot spot's radius (0: no hot spot)")
    a.add_argument("--ghost-bytes", type=float, default=48, help="bytes a hot-spot ghost particle")
    a.add_argument("--bodies", type=int, default=2)
    a.add_argument("--whole-grid", action="store_true",
                   help="charge every process the whole grid's node passes (the step sweeps each process's own rows)")
    o = a.parse_args()

    cells_l = round(o.lateral / o.cell)
    cells_z = round(o.length / o.cell)
    particles = cells_l * cells_l * cells_z * 8
    per_row = (cells_l + 1 + 2 * o.ghost) ** 2
    rows = cells_z + 1 + 2 * o.ghost
    slabs = rows // o.slab_rows
    entries = o.fields * per_row * rows
    entry_bytes = 56 + 24 + 24 * o.k + 24
    folds = 3 + o.k  # P2G, gradients, k products, re-map
    band_bytes = o.fields * o.slab_rows * per_row * entry_bytes + o.bodies * o.slab_rows * per_row * (40 + 16 + 1)
    ghosts = 1.5 * o.hot_spot_radius * o.lateral**2 * 8 / o.cell**3  # a neighbour's particles within a bin
    ghost_bytes = ghosts * o.ghost_bytes
    print(f"cell {o.cell} mm: {particles / 1e6:.1f} M particles, {per_row:,} nodes a row, {rows} rows, {slabs} slabs, "
          f"{entries / 1e6:.1f} M grid entries")
    print(f"a band: {o.slab_rows * per_row:,} nodes, {band_bytes / 1e6:.1f} MB a step each way "
          f"({folds} passes, {entry_bytes} bytes an entry, and self-contact's merges); an inner process has two bands")
    print(f"the hot spot's ghosts: {ghosts / 1e6:.2f} M particles, {ghost_bytes / 1e6:.1f} MB a step from each neighbour")
    rate = o.cores * o.eff
    compute_1 = particles * o.t_u / rate
    print(f"one process of {o.cores} cores: {compute_1:.2f} s a step of particle work, "
          f"{entries * o.t_e / rate:.3f} s of node passes")
    print()
    print("| processes | slabs each | particle work (s) | node passes (s) | bands (s) | hot-spot ghosts (s) | "
          "collectives (s) | step (s) | speed-up | efficiency |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    base = None
    counts = sorted({1 << k for k in range(12) if (1 << k) <= slabs} | {slabs})
    for r in counts:
        work = compute_1 / r
        nodes = entries * o.t_e / rate / (1 if o.whole_grid else r)
        bands = 0.0 if r == 1 else 2 * band_bytes / o.bandwidth + 2 * 2 * folds * o.latency
        ghost = 0.0 if r == 1 else 2 * ghost_bytes / o.bandwidth + 3 * o.latency * r  # three all-to-alls
        coll = 0.0 if r == 1 else o.allreduces * math.ceil(math.log2(r)) * o.latency
        step = work + nodes + bands + ghost + coll
        base = base or step
        print(f"| {r} | {slabs / r:.1f} | {work:.3f} | {nodes:.3f} | {bands:.4f} | {ghost:.4f} | {coll:.5f} | {step:.3f} | "
              f"{base / step:.1f} | {base / step / r:.2f} |")
    print()
    store, stencil, grid_entry = o.particle_bytes, o.stencil_bytes, o.entry_bytes
    print(f"Memory a process: its particles, {particles * (store + stencil) / 2**30:.0f} GiB / P (kept batch by "
          f"batch from the seeding on), and the whole grid's arrays, {entries * grid_entry / 2**30:.1f} GiB "
          f"(arrays of its own rows would make it {entries * grid_entry / 2**30:.1f} GiB / P).")
    print()
    print("Weak scaling (the last axis grown with the processes, the same slabs a process): the particle work, the")
    print("bands and the node passes stay the same a process; only the collectives grow, as log2 of the")
    print(f"processes: {o.allreduces} allreduces x {o.latency * 1e6:.0f} us x log2(P) a step.")


if __name__ == "__main__":
    main()
