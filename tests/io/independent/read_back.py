#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Reads every file type gimlet writes with implementations that share no code with its
writers, and compares each value with the manifest to the bit (docs/testing.md, "Independent
readers"):

- .vtp: VTK's own XML reader (vtkXMLPolyDataReader, Debian's python3-vtk9);
- .pvd: Python's xml.etree;
- .csv: Python's csv module and float();
- checkpoint: struct, following the format table of docs/io.md.

    read_back.py WRITER DIR    runs WRITER DIR (tests/io/independent/write_samples.cpp), then reads

Exits 0 if everything matches, 1 with a line per mismatch otherwise.
"""
import csv
import math
import os
import struct
import subprocess
import sys
import xml.etree.ElementTree as ET

errors = []


def fail(msg):
    errors.append(msg)


def same(a, b):
    """Equal to the bit as values: NaN matches NaN, and zeros must agree in sign."""
    if math.isnan(a) or math.isnan(b):
        return math.isnan(a) and math.isnan(b)
    return a == b and math.copysign(1.0, a) == math.copysign(1.0, b)


def parse_hex(token):
    return float("nan") if token == "nan" else float.fromhex(token)


def compare(where, got, want):
    if len(got) != len(want):
        fail(f"{where}: {len(got)} values, expected {len(want)}")
        return
    bad = [i for i, (g, w) in enumerate(zip(got, want)) if not same(g, w)]
    if bad:
        i = bad[0]
        fail(f"{where}: {len(bad)} values differ, first at {i}: read {got[i]!r}, expected {want[i]!r}")


def read_manifest(path):
    lines = open(path, encoding="utf-8").read().splitlines()
    out = []
    k = 0
    while k < len(lines):
        t = lines[k].split(" ")
        if t[0] == "array_named":  # the name is on the next line (it holds spaces)
            name = lines[k + 1][len("name "):]
            out.append(["array", t[1], t[2], t[3], name] + t[4:])
            k += 2
            continue
        out.append(t)
        k += 1
    return out


# ---- .vtp with VTK --------------------------------------------------------------------------

VTK_TYPES = {"Float64": "double", "Float32": "float", "Int32": "int", "Int64": "long long"}


def read_vtp(path):
    from vtkmodules.vtkIOXML import vtkXMLPolyDataReader

    reader = vtkXMLPolyDataReader()
    reader.SetFileName(path)
    reader.Update()
    if reader.GetErrorCode() != 0:
        fail(f"{path}: VTK reports error code {reader.GetErrorCode()}")
    return reader.GetOutput()


def values_of(array):
    n, c = array.GetNumberOfTuples(), array.GetNumberOfComponents()
    return [array.GetComponent(i, k) for i in range(n) for k in range(c)]


def check_vtp(dir_, entry, arrays):
    _, file, n, time = entry
    n = int(n)
    path = os.path.join(dir_, file)
    poly = read_vtp(path)
    if poly.GetNumberOfPoints() != n:
        fail(f"{file}: {poly.GetNumberOfPoints()} points, expected {n}")
        return
    # One vertex per particle, vertex i at point i.
    verts = poly.GetVerts()
    if verts.GetNumberOfCells() != n:
        fail(f"{file}: {verts.GetNumberOfCells()} vertices, expected {n}")
    conn = [int(v) for v in values_of(verts.GetConnectivityArray())]
    if conn != list(range(n)):
        fail(f"{file}: vertex connectivity is not 0..n-1")
    tv = poly.GetFieldData().GetArray("TimeValue")
    if tv is None:
        fail(f"{file}: no TimeValue")
    else:
        compare(f"{file} TimeValue", [tv.GetValue(0)], [parse_hex(time)])
    for _, _, type_, comps, name, *vals in arrays:
        comps = int(comps)
        if name == "Points":
            array = poly.GetPoints().GetData()
        else:
            array = poly.GetPointData().GetArray(name)
            if array is None:
                fail(f"{file}: no point-data array {name!r} (found: "
                     f"{[poly.GetPointData().GetArrayName(i) for i in range(poly.GetPointData().GetNumberOfArrays())]})")
                continue
        if array.GetDataTypeAsString() != VTK_TYPES[type_]:
            fail(f"{file} {name!r}: type {array.GetDataTypeAsString()}, expected {VTK_TYPES[type_]}")
        if array.GetNumberOfComponents() != comps:
            fail(f"{file} {name!r}: {array.GetNumberOfComponents()} components, expected {comps}")
        compare(f"{file} {name!r}", values_of(array), [parse_hex(v) for v in vals])


# ---- .pvd with xml.etree --------------------------------------------------------------------

def check_pvd(dir_, entries):
    by_file = {}
    for _, pvd, k, file, time in entries:
        by_file.setdefault(pvd, []).append((int(k), file, parse_hex(time)))
    for pvd, want in by_file.items():
        root = ET.parse(os.path.join(dir_, pvd)).getroot()
        if root.tag != "VTKFile" or root.get("type") != "Collection":
            fail(f"{pvd}: root is <{root.tag} type={root.get('type')!r}>, expected a VTKFile Collection")
            continue
        sets = root.findall("./Collection/DataSet")
        if len(sets) != len(want):
            fail(f"{pvd}: {len(sets)} data sets, expected {len(want)}")
            continue
        for ds, (k, file, time) in zip(sets, sorted(want)):
            if ds.get("file") != file:
                fail(f"{pvd} entry {k}: file {ds.get('file')!r}, expected {file!r}")
            compare(f"{pvd} entry {k} timestep", [float(ds.get("timestep"))], [time])
            if not os.path.exists(os.path.join(dir_, ds.get("file"))):
                fail(f"{pvd} entry {k}: {ds.get('file')!r} does not exist next to the series")


# ---- CSV with the csv module ----------------------------------------------------------------

def check_csv(dir_, header, rows):
    _, file, nrows, ncols = header
    with open(os.path.join(dir_, file), newline="", encoding="utf-8") as f:
        table = list(csv.reader(f))
    if len(table) != int(nrows) + 1:
        fail(f"{file}: {len(table)} lines, expected a header and {nrows} rows")
        return
    if any(len(r) != int(ncols) for r in table):
        fail(f"{file}: a line without {ncols} fields")
        return
    for _, _, i, *vals in rows:
        row = table[int(i) + 1]
        compare(f"{file} row {i}", [float(x) for x in row[:3]], [parse_hex(v) for v in vals[:3]])
        if row[3] != vals[3]:
            fail(f"{file} row {i}: label {row[3]!r}, expected {vals[3]!r}")


# ---- checkpoint with struct (docs/io.md, "The checkpoint file, format version 1") ----------

def fnv1a64(data):
    h = 0xCBF29CE484222325
    for b in data:
        h ^= b
        h = (h * 0x100000001B3) & 0xFFFFFFFFFFFFFFFF
    return h


def check_checkpoint(dir_, header, values, columns):
    _, file, dim, real, n, time, steps = header
    data = open(os.path.join(dir_, file), "rb").read()
    if data[:8] != b"GIMLETCK":
        fail(f"{file}: magic {data[:8]!r}")
        return
    version, bom, size = struct.unpack_from("<IIQ", data, 8)
    if (version, bom, size) != (1, 0x01020304, len(data)):
        fail(f"{file}: version {version}, byte-order mark {bom:#x}, size {size} (file {len(data)})")
        return
    (checksum,) = struct.unpack_from("<Q", data, len(data) - 8)
    if checksum != fnv1a64(data[:-8]):
        fail(f"{file}: FNV-1a checksum does not match")
    d, r, count, t, st, nf, nv = struct.unpack_from("<IIQdQII", data, 24)
    if (d, r, count, st) != (int(dim), int(real), int(n), int(steps)):
        fail(f"{file}: dim {d}, real {r}, n {count}, steps {st}; expected {dim} {real} {n} {steps}")
        return
    compare(f"{file} time", [t], [parse_hex(time)])
    at = 64
    layout = []
    for _ in range(nf):
        (ln,) = struct.unpack_from("<I", data, at)
        name = data[at + 4:at + 4 + ln].decode()
        (per,) = struct.unpack_from("<I", data, at + 4 + ln)
        layout.append((name, per))
        at += 8 + ln
    stored = {}
    for _ in range(nv):
        (ln,) = struct.unpack_from("<I", data, at)
        key = data[at + 4:at + 4 + ln].decode()
        (stored[key],) = struct.unpack_from("<d", data, at + 4 + ln)
        at += 12 + ln
    cols = {}
    for name, per in layout:
        cols[name] = (data[at:at + count * per], per)
        at += count * per
    if at != len(data) - 8:
        fail(f"{file}: the columns end at byte {at}, the checksum starts at {len(data) - 8}")
    for _, _, key, v in values:
        if key not in stored:
            fail(f"{file}: no value {key!r} (found {sorted(stored)})")
        else:
            compare(f"{file} value {key!r}", [stored[key]], [parse_hex(v)])
    for _, _, name, comps, *vals in columns:
        if name not in cols:
            fail(f"{file}: no column {name!r} (found {[c for c, _ in layout]})")
            continue
        raw, per = cols[name]
        comps = int(comps)
        if name == "body":  # u32 ids
            got = [float(x) for x in struct.unpack(f"<{count}I", raw)]
        else:
            got = list(struct.unpack(f"<{count * per // 8}d", raw))
            if per != 8 * comps:
                fail(f"{file} column {name!r}: {per} bytes per particle, expected {8 * comps}")
        compare(f"{file} column {name!r}", got, [parse_hex(v) for v in vals])


def main():
    if len(sys.argv) != 3:
        print(__doc__)
        return 2
    writer, dir_ = sys.argv[1], sys.argv[2]
    try:
        import vtkmodules.vtkIOXML  # noqa: F401
    except ImportError:
        print("read_back.py: VTK's Python module is missing: install Debian's python3-vtk9 "
              "(scripts/setup.sh --tests does)")
        return 1
    subprocess.run([writer, dir_], check=True)
    manifest = read_manifest(os.path.join(dir_, "manifest.txt"))
    kinds = {}
    for t in manifest:
        kinds.setdefault(t[0], []).append(t)
    for entry in kinds.get("vtp", []):
        check_vtp(dir_, entry, [a for a in kinds.get("array", []) if a[1] == entry[1]])
    check_pvd(dir_, kinds.get("pvd", []))
    for header in kinds.get("csv", []):
        check_csv(dir_, header, [r for r in kinds.get("row", []) if r[1] == header[1]])
    for header in kinds.get("ckpt", []):
        check_checkpoint(dir_, header, [v for v in kinds.get("value", []) if v[1] == header[1]],
                         [c for c in kinds.get("column", []) if c[1] == header[1]])
    counted = {k: len(v) for k, v in kinds.items()}
    if errors:
        print("\n".join(errors))
        print(f"read_back.py: {len(errors)} mismatches")
        return 1
    print(f"read_back.py: every value read back exactly ({counted})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
