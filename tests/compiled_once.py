#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The shared solver types are compiled once (docs/testing.md, "Solver types compiled once").

tests/instantiations.hpp declares the shared solvers and their contact-independent cores
(gimlet::solver_core) `extern template`, and tests/instantiations_*.cpp define them. The saving
holds only while no family's unit compiles a shared core's members again, which it does for any
member defined inside the class (an inline member is instantiated where it is called, `extern`
or not) that the step reaches: the scatter, the shared-node search. This reads the objects'
symbols (nm) and fails, naming them, if a family's object defines one of a shared core's members
that are defined outside the class (read from the solver's headers: not inline, so `extern`
keeps them out at any optimisation level; the constructor from a scene, the destructor, the
passes) or that only those reach (the slab loops). The step's order (a template on the law: a
unit's own laws need their own) and the small inline members are not checked.

usage: compiled_once.py NM SOLVER_HEADER_DIR INSTANTIATION_OBJECTS... -- FAMILY_OBJECTS...
"""
import pathlib
import re
import collections
import subprocess
import sys

CORE = "gimlet::solver_core<"


def defined_names(nm, obj):
    out = subprocess.run([nm, "-C", "--defined-only", obj], capture_output=True, text=True, check=True).stdout
    names = []
    for line in out.splitlines():
        parts = line.split(" ", 2)
        if len(parts) == 3 and parts[1] not in ("n", "N"):  # not debugging symbols
            names.append(parts[2])
    return names


def member_of_core(name):
    """(core type, member) when `name` is a member function of a solver_core (a member
    template's name starts with its return type), else None."""
    i = name.find(CORE)
    while i >= 0:
        prefix = name[:i]
        if prefix.count("<") == prefix.count(">") and (not prefix or prefix.endswith(" ")):
            break
        i = name.find(CORE, i + 1)
    if i < 0:
        return None
    depth, j = 1, i + len(CORE)
    while j < len(name) and depth:
        depth += {"<": 1, ">": -1}.get(name[j], 0)
        j += 1
    if not name.startswith("::", j):
        return None
    member = name[j + 2:].split("(")[0].split("<")[0]
    return name[i:j], member


def main(argv):
    nm, headers, rest = argv[1], argv[2], argv[3:]
    out_of_class = set()
    for header in pathlib.Path(headers).glob("*.hpp"):
        out_of_class |= set(re.findall(r"solver_core<S, Sh, M, Fields, MultiField, Part>::(~?\w+)\(",
                                       header.read_text()))
    # The constructor is checked by its argument (a copy or a move is inline by design: a test may
    # copy a solver); the slab loops are templates that only the passes call.
    out_of_class.discard("solver_core")
    watched = out_of_class | {"for_each_particle_by_slab", "for_each_particle_by_slab_reaching"}
    if len(out_of_class) < 10:
        print(f"compiled_once.py: found only {sorted(out_of_class)} defined outside the class in {headers}",
              file=sys.stderr)
        return 1
    split = rest.index("--")
    instantiations, families = rest[:split], rest[split + 1:]
    shared = set()
    for obj in instantiations:
        for name in defined_names(nm, obj):
            found = member_of_core(name)
            if found:
                shared.add(found[0])
    if not shared:
        print("compiled_once.py: no solver_core defined in the instantiation objects", file=sys.stderr)
        return 1
    bad = 0
    for obj in families:
        members = collections.Counter()
        for name in defined_names(nm, obj):
            found = member_of_core(name)
            if not found or found[0] not in shared:
                continue
            if found[1] in watched:
                members[found[1]] += 1
            elif found[1] == "solver_core" and "gimlet::scene::scene<" in name:
                members["solver_core (from a scene)"] += 1
        if members:
            bad += 1
            print(f"{obj}: defines members of a shared solver_core again: "
                  + ", ".join(f"{m} ({n} symbols)" for m, n in sorted(members.items())), file=sys.stderr)
    print(f"compiled_once.py: {len(shared)} shared cores, {len(watched)} members watched, "
          f"{len(families)} family objects, "
          f"{'none' if not bad else bad} compiling them again")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
