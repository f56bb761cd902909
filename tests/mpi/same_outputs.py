# SPDX-License-Identifier: MIT
"""An example run on one process and under mpirun writes the same files, byte for byte.

    same_outputs.py --exe EXE --one ONE -- ARG...
    same_outputs.py --exe EXE --one ONE --out DIR --ranks N --mpiexec MPIRUN --files F1,F2,...
                    [--pieces P1,...] [--restart-at-us T --restart-ranks M] -- ARG...

The first form runs EXE ARG... --output ONE on one process (the reference). The second runs it
under `MPIRUN -np N --oversubscribe` into DIR and compares with ONE. With --restart-at-us, the
run on N processes checkpoints at T and a run on M processes resumes from that checkpoint into
the same directory: its files must still be those of one process. Each of the files (glob
patterns relative to the output directory, each matching at least one file, the same names in
both) must be equal byte for byte; in a summary.csv the columns that name the run rather than
its results (wall_s, ranks) are left out of the comparison.

--pieces: ParaView snapshots (glob patterns of one process's .vtp files). Under mpirun each is a
.pvtp of one piece a process; VTK's own readers (vtkXMLPolyDataReader, vtkXMLPPolyDataReader)
read both, and, the pieces' particles put in the order of their ordinals, every array, the points
and the time must be equal bit for bit. In a .pvd listed in --files, the many processes' .pvtp
names are read as the one process's .vtp names.
"""
import argparse
import csv
import glob
import io
import os
import re
import shutil
import subprocess
import sys

VARYING = {"wall_s", "ranks"}


def run(command):
    done = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if done.returncode != 0:
        sys.exit(f"exit {done.returncode}: {' '.join(command)}\n{done.stdout}")


def comparable(path):
    with open(path, "rb") as f:
        data = f.read()
    if path.endswith(".pvd"):
        return re.sub(rb'(file="[^"]*)\.pvtp"', rb'\1.vtp"', data)
    if os.path.basename(path) != "summary.csv":
        return data
    rows = list(csv.reader(io.StringIO(data.decode())))
    keep = [i for i, name in enumerate(rows[0]) if name not in VARYING]
    return [[row[i] for i in keep] for row in rows]


def dataset(path):
    """Every array of a .vtp or .pvtp as bytes, by name: the points, the point data, the time.
    A .pvtp's points are put in the order of their ordinals (its `ordinal` array, which must
    number them 0 .. N - 1 once each), and the ordinals left out."""
    import numpy
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOXML import vtkXMLPolyDataReader, vtkXMLPPolyDataReader
    reader = vtkXMLPPolyDataReader() if path.endswith(".pvtp") else vtkXMLPolyDataReader()
    reader.SetFileName(path)
    reader.Update()
    data = reader.GetOutput()
    arrays = {"Points": vtk_to_numpy(data.GetPoints().GetData())}
    point_data = data.GetPointData()
    for k in range(point_data.GetNumberOfArrays()):
        arrays["point " + point_data.GetArrayName(k)] = vtk_to_numpy(point_data.GetArray(k))
    if path.endswith(".pvtp"):
        ordinal = arrays.pop("point ordinal", None)
        if ordinal is None or not numpy.array_equal(numpy.sort(ordinal), numpy.arange(len(ordinal))):
            return {"ordinal": "missing, or not 0 .. N - 1 once each"}
        order = numpy.argsort(ordinal, kind="stable")
        arrays = {name: a[order] for name, a in arrays.items()}
    time = data.GetFieldData().GetArray("TimeValue")
    if time is not None:
        arrays["TimeValue"] = vtk_to_numpy(time)
    return {name: (a.dtype.str, a.shape, a.tobytes()) for name, a in arrays.items()}


def pieces_differ(one, many, pattern):
    names = sorted(os.path.relpath(f, one) for f in glob.glob(os.path.join(one, pattern)))
    if not names:
        return [f"{pattern}: one process wrote none"]
    theirs = sorted(os.path.relpath(f, many) for f in glob.glob(os.path.join(many, pattern[:-len(".vtp")] + ".pvtp")))
    wanted = [name[:-len(".vtp")] + ".pvtp" for name in names]
    if theirs != wanted:
        return [f"{pattern}: one process wrote {names}, many processes {theirs}"]
    differ = []
    for name, pieces in zip(names, wanted):
        a, b = dataset(os.path.join(one, name)), dataset(os.path.join(many, pieces))
        if a != b:
            bad = sorted(k for k in a.keys() | b.keys() if a.get(k) != b.get(k))
            differ.append(f"{pieces} ({', '.join(bad)})")
    return differ


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--exe", required=True)
    p.add_argument("--one", required=True)
    p.add_argument("--out")
    p.add_argument("--ranks", type=int)
    p.add_argument("--mpiexec")
    p.add_argument("--files", default="")
    p.add_argument("--pieces", default="")
    p.add_argument("--restart-at-us")
    p.add_argument("--restart-ranks", type=int)
    p.add_argument("args", nargs="*")
    a = p.parse_args()
    one = a.one
    if a.ranks is None:
        shutil.rmtree(one, ignore_errors=True)
        run([a.exe, *a.args, "--output", one])
        return
    if not (a.out and a.mpiexec and a.files):
        sys.exit("--ranks needs --out, --mpiexec and --files")
    if not os.path.isdir(one):
        sys.exit(f"{one}: no one-process run to compare with (its test runs first)")
    shutil.rmtree(a.out, ignore_errors=True)
    many = a.out
    mpi = [a.mpiexec, "-np"]
    if a.restart_at_us:
        checkpoint = os.path.join(a.out, "run.ckpt")
        run(mpi + [str(a.ranks), "--oversubscribe", a.exe, *a.args, "--output", many, "--checkpoint", checkpoint,
                   "--checkpoint-at-us", a.restart_at_us])
        run(mpi + [str(a.restart_ranks), "--oversubscribe", a.exe, *a.args, "--output", many, "--restart", checkpoint])
    else:
        run(mpi + [str(a.ranks), "--oversubscribe", a.exe, *a.args, "--output", many])
    differ = []
    for pattern in a.files.split(","):
        names = sorted(os.path.relpath(f, one) for f in glob.glob(os.path.join(one, pattern)))
        theirs = sorted(os.path.relpath(f, many) for f in glob.glob(os.path.join(many, pattern)))
        if not names or names != theirs:
            differ.append(f"{pattern}: one process wrote {names}, many {theirs}")
            continue
        differ += [name for name in names if comparable(os.path.join(one, name)) != comparable(os.path.join(many, name))]
    for pattern in filter(None, a.pieces.split(",")):
        differ += pieces_differ(one, many, pattern)
    if differ:
        sys.exit("differ from one process's: " + ", ".join(differ))


if __name__ == "__main__":
    main()
