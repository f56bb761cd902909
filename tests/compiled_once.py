#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The shared solver types are compiled once (docs/testing.md, "Solver types compiled once").

tests/instantiations.hpp declares the shared solvers and their contact-independent cores
(gimlet::solver_core) `extern template`, and tests/instantiations_*.cpp define them. The saving
holds only while no family's unit compiles their members again. A unit does so for a member
defined inside its class (an inline member is instantiated where it is called, `extern` or not),
and for the member templates such a member reaches (`extern template` does not cover member
templates: they stay out only because their callers do). So the members that the step, the
constructor and the time step reach are defined outside their classes, and this checks it two
ways:
- in the headers: each member of REQUIRED is still defined outside its class (a member moved
  back into its class fails here by name, whatever the compiler then emits);
- in the objects (nm): no family's object defines a member of a shared core that is defined
  outside the class (the headers' list: the passes, the destructor, the member templates), the
  slab loops and the stages (include/gimlet/solver/stages/) only those reach, a shared core's
  constructor from a scene, or a shared solver's `advance`.
The schemes (gimlet::solver's members, reached only from `advance`) and the small inline members
are not checked.

usage: compiled_once.py NM SOLVER_HEADER_DIR INSTANTIATION_OBJECTS... -- FAMILY_OBJECTS...
"""
import collections
import pathlib
import re
import subprocess
import sys

CORE = "gimlet::solver_core<"
SOLVER = "gimlet::solver<"
# What must stay defined outside its class (docs/performance.md, "Solvers that differ only in
# their contact law share the rest"): the core's members that the step, the constructor and the
# time step reach, and the solver's own step.
REQUIRED_CORE = ["solver_core", "~solver_core", "scatter_all", "scatter_for_usf", "scatter", "map_forces",
                 "find_shared_nodes", "stable_time_step", "check_particles", "check_light_possible",
                 "update_grid_momentum",
                 "grid_to_particles", "update_material_points", "finish_step", "check_step_start",
                 "compute_stencils", "group_into_slabs", "start_grid", "find_light_particles",
                 "start_of_step_velocities", "clear_forces", "remapped_velocities", "average_volumetric_rates",
                 "average_mean_stress", "filter_volumes", "sort_by_cell"]
REQUIRED_SOLVER = ["advance"]
SLAB_LOOPS = {"for_each_particle_by_slab", "for_each_particle_by_slab_reaching"}
# The stages' members take the core as a template argument (include/gimlet/solver/stages/): those
# the passes reach are instantiated with them, so none may be defined in a family's object for a
# shared core either.
STAGES = "gimlet::stages::"


def defined_names(nm, obj):
    out = subprocess.run([nm, "-C", "--defined-only", obj], capture_output=True, text=True, check=True).stdout
    names = []
    for line in out.splitlines():
        parts = line.split(" ", 2)
        if len(parts) == 3 and parts[1] not in ("n", "N"):  # not debugging symbols
            names.append(parts[2])
    return names


def member_of(name, key):
    """(type, member) when `name` is a member function of a class template named by `key`
    (its type's template-id at the top level of the name: a member template's demangled name
    starts with its return type, which may itself name the type), else None."""
    found = None
    i = name.find(key)
    while i >= 0:
        prefix = name[:i]
        if prefix.count("<") == prefix.count(">") and (not prefix or prefix.endswith(" ")):
            depth, j = 1, i + len(key)
            while j < len(name) and depth:
                depth += {"<": 1, ">": -1}.get(name[j], 0)
                j += 1
            if name.startswith("::", j):
                member = re.split(r"[(<\[]", name[j + 2:], maxsplit=1)[0]
                found = (name[i:j], member)  # the last one at the top level: the qualifier
        i = name.find(key, i + 1)
    return found


def main(argv):
    nm, headers, rest = argv[1], argv[2], argv[3:]
    text = "".join(p.read_text() for p in sorted(pathlib.Path(headers).glob("*.hpp")))
    out_of_class = set(re.findall(r"solver_core<S, Sh, M, Fields, MultiField, Part, Distributed>::(~?\w+)\(", text))
    solver_out_of_class = set(re.findall(r"solver<S, Sh, M, C, ExtraFields, Part, Distributed>::(\w+)\(", text))
    missing = [m for m in REQUIRED_CORE if m not in out_of_class] + \
              [f"solver::{m}" for m in REQUIRED_SOLVER if m not in solver_out_of_class]
    if missing:
        print(f"compiled_once.py: no longer defined outside their classes in {headers}: {', '.join(missing)} "
              "(an inline member is compiled again in every unit that calls it)", file=sys.stderr)
        return 1
    # The constructor is checked by its argument (a copy or a move is inline by design: a test
    # may copy a solver).
    watched = (out_of_class - {"solver_core"}) | SLAB_LOOPS
    split = rest.index("--")
    instantiations, families = rest[:split], rest[split + 1:]
    if not families:
        print("compiled_once.py: no family objects given", file=sys.stderr)
        return 1
    shared_cores, shared_solvers = set(), set()
    for obj in instantiations:
        for name in defined_names(nm, obj):
            for key, into in ((CORE, shared_cores), (SOLVER, shared_solvers)):
                found = member_of(name, key)
                if found:
                    into.add(found[0])
    if not shared_cores or not shared_solvers:
        print("compiled_once.py: no solver or solver_core defined in the instantiation objects", file=sys.stderr)
        return 1
    bad = 0
    for obj in families:
        members = collections.Counter()
        for name in defined_names(nm, obj):
            core = member_of(name, CORE)
            if core and core[0] in shared_cores:
                if core[1] in watched:
                    members[core[1]] += 1
                elif core[1] == "solver_core" and "gimlet::scene::scene<" in name:
                    members["solver_core (from a scene)"] += 1
            if STAGES in name and any(c in name for c in shared_cores):
                stage = re.split(r"[<(]", name[name.index(STAGES) + len(STAGES):], maxsplit=1)[0]
                members[f"stages::{stage}"] += 1
            solver = member_of(name, SOLVER)
            if solver and solver[0] in shared_solvers and solver[1] in REQUIRED_SOLVER:
                members[f"solver::{solver[1]}"] += 1
        if members:
            bad += 1
            print(f"{obj}: defines members of a shared solver type again: "
                  + ", ".join(f"{m} ({n} symbols)" for m, n in sorted(members.items())), file=sys.stderr)
    print(f"compiled_once.py: {len(shared_cores)} shared cores, {len(shared_solvers)} shared solvers, "
          f"{len(watched)} members watched, {len(families)} family objects, "
          f"{'none' if not bad else bad} compiling them again")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
