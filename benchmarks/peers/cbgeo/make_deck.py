#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Writes the CB-Geo mpm (github.com/cb-geo/mpm, commit 53fcb76) input deck of gimlet's reference
scene (benchmarks/throughput --scene reference --cell 0.5) into a directory:

  mpm.json                 the analysis: MPMExplicit2D, USL, FLIP, dt 1.4e-8 s, STEPS steps
  mesh.txt                 0.5 mm cells over x 0..40 mm, y -10..114 mm (gimlet's grid), as
                           16-node GIMP cells (ED2Q16G), with the ring of nodes one cell
                           outside that the GIMP cells on the edges name
  entity_sets.json         the cells of the two blocks (cell sets 0 and 1)
  velocity_constraints.txt zero x-velocity on the node lines x = -0.5, 0, 40, 40.5 mm

Usage: make_deck.py DIR [STEPS]   (STEPS default 1000)

Two linear-elastic blocks 40 mm x 50 mm, 4 mm apart, at +-300 m/s along y; E = 11.87 GPa,
nu = 0.25, rho = 1900 kg/m^3; 2x2 particles per cell. CB-Geo sets an initial velocity only on
injected particles, so the blocks are "inject" generators active for the first step only; they
place the particles at the cell's 2x2 Gauss points (+-1/sqrt(3) of the half cell), not at the
quarter-cell centres gimlet uses.
"""
import json
import os
import sys

CELL = 0.5e-3
X0, X1 = 0.0, 40e-3          # gimlet's periodic width
Y0, Y1 = -10e-3, 114e-3      # gimlet's grid in y
NX = round((X1 - X0) / CELL)  # 80 cells
NY = round((Y1 - Y0) / CELL)  # 248 cells
NI, NJ = NX + 3, NY + 3       # nodes, one ring outside the cells
DT = 1.4e-8


def node(i, j):
    return j * NI + i


def main():
    out = sys.argv[1]
    steps = int(sys.argv[2]) if len(sys.argv) > 2 else 1000
    os.makedirs(out, exist_ok=True)
    # 16-node GIMP cell: the 4 corners, then the outer ring from (-3,-3) anticlockwise, in
    # natural coordinates (the element spans -1..1); natural -3,-1,1,3 -> node offset -1,0,1,2.
    nat = [(-1, -1), (1, -1), (1, 1), (-1, 1), (-3, -3), (-1, -3), (1, -3), (3, -3), (3, -1), (3, 1),
           (3, 3), (1, 3), (-1, 3), (-3, 3), (-3, 1), (-3, -1)]
    off = {-3: -1, -1: 0, 1: 1, 3: 2}
    with open(os.path.join(out, "mesh.txt"), "w") as f:
        f.write(f"{NI * NJ} {NX * NY}\n")
        for j in range(NJ):
            for i in range(NI):
                f.write(f"{X0 + (i - 1) * CELL:.6e} {Y0 + (j - 1) * CELL:.6e}\n")
        for cj in range(NY):
            for ci in range(NX):
                i, j = ci + 1, cj + 1  # lower-left node of the cell
                f.write(" ".join(str(node(i + off[a], j + off[b])) for a, b in nat) + "\n")

    def cells(y_lo, y_hi):
        j0, j1 = round((y_lo - Y0) / CELL), round((y_hi - Y0) / CELL)
        return [cj * NX + ci for cj in range(j0, j1) for ci in range(NX)]

    with open(os.path.join(out, "entity_sets.json"), "w") as f:
        json.dump({"cell_sets": [{"id": 0, "set": cells(0.0, 50e-3)}, {"id": 1, "set": cells(54e-3, 104e-3)}]}, f)
    with open(os.path.join(out, "velocity_constraints.txt"), "w") as f:
        for i in (0, 1, NI - 2, NI - 1):
            for j in range(NJ):
                f.write(f"{node(i, j)} 0 0\n")

    def inject(cset, vy):
        return {"generator": {"type": "inject", "particle_type": "P2D", "material_id": 0, "cset_id": cset,
                              "nparticles_per_dir": 2, "velocity": [0.0, vy], "duration": [0.0, 0.5 * DT]}}

    deck = {
        "title": "gimlet reference scene (benchmarks/peers)",
        "mesh": {"mesh": "mesh.txt", "entity_sets": "entity_sets.json", "io_type": "Ascii2D",
                 "check_duplicates": False, "isoparametric": False, "node_type": "N2D", "cell_type": "ED2Q16G",
                 "boundary_conditions": {"velocity_constraints": [{"file": "velocity_constraints.txt"}]}},
        "particles": [inject(0, 300.0), inject(1, -300.0)],
        "materials": [{"id": 0, "type": "LinearElastic2D", "density": 1900.0, "youngs_modulus": 11.87e9,
                       "poisson_ratio": 0.25}],
        "external_loading_conditions": {"gravity": [0.0, 0.0]},
        "analysis": {"type": "MPMExplicit2D", "mpm_scheme": "usl", "velocity_update": False,
                     "locate_particles": False, "dt": DT, "nsteps": steps, "resume": {"resume": False}},
        # an output interval of the whole run: CB-Geo writes its HDF5 particle file at step 0 only
        "post_processing": {"path": "results/", "output_steps": steps},
    }
    with open(os.path.join(out, "mpm.json"), "w") as f:
        json.dump(deck, f, indent=2)


if __name__ == "__main__":
    main()
