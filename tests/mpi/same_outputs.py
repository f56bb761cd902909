# SPDX-License-Identifier: MIT
"""An example run on one process and under mpirun writes the same files, byte for byte.

    same_outputs.py --exe EXE --mpiexec MPIRUN --ranks N --out DIR --files F1,F2,...
                    [--restart-at-us T --restart-ranks M] -- ARG...

Runs EXE ARG... --output DIR/one, then under `MPIRUN -np N --oversubscribe` into DIR/many. With
--restart-at-us, the run on N processes checkpoints at T and a run on M processes resumes from
that checkpoint into the same directory: its files must still be those of one process. Each
of the files (glob patterns relative to the output directory, each matching at least one file,
the same names in both) must be equal byte for byte; in a summary.csv the columns that name the
run rather than its results (wall_s, ranks) are left out of the comparison.
"""
import argparse
import csv
import glob
import io
import os
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
    if os.path.basename(path) != "summary.csv":
        return data
    rows = list(csv.reader(io.StringIO(data.decode())))
    keep = [i for i, name in enumerate(rows[0]) if name not in VARYING]
    return [[row[i] for i in keep] for row in rows]


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--exe", required=True)
    p.add_argument("--mpiexec", required=True)
    p.add_argument("--ranks", type=int, required=True)
    p.add_argument("--out", required=True)
    p.add_argument("--files", required=True)
    p.add_argument("--restart-at-us")
    p.add_argument("--restart-ranks", type=int)
    p.add_argument("args", nargs="*")
    a = p.parse_args()
    shutil.rmtree(a.out, ignore_errors=True)
    one, many = os.path.join(a.out, "one"), os.path.join(a.out, "many")
    mpi = [a.mpiexec, "-np"]
    run([a.exe, *a.args, "--output", one])
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
    if differ:
        sys.exit("differ from one process's: " + ", ".join(differ))


if __name__ == "__main__":
    main()
