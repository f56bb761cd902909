#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The per-phase roofline of docs/performance.md ("What bounds each phase"), measured.

For each scene of bench_throughput (reference, hmx; one thread, 0.5 mm cells, 64,000 particles)
it measures, per particle-update and per phase of solver::timings():

  time      the phase's share of the step times the step's wall time per particle-update (the
            run with the median step time of --runs runs, so that the phases add up);
  work      the instructions the phase executes, counted by valgrind's callgrind (--dump-instr)
            and classified by disassembly (objdump -M intel): floating-point operations (add,
            subtract, multiply: one per lane; a fused multiply-add two), divisions and square
            roots (per lane), the calls into libm by name, the level-1 cache's loads and stores
            (an operand in memory read, written, or both), and the bytes the L3 or memory
            delivers (the 64-byte lines of the read and write misses of callgrind's simulated
            caches, set to this machine's L1 data cache and L2; write-backs and prefetches not
            counted). A run of --short steps is subtracted from one of --long steps, so setting
            up the scene cancels.

and sets them against the machine's ceilings, which bench_ceilings measures just before and
just after each scene's timed runs, their mean taken (a shared machine's speed drifts over
minutes): the scalar and vector multiply-add throughput, the 22 MB triad, the cost of a
division, a square root, pow and log, each at its throughput (one at a time, independent
inputs), the clock, the rate of independent register additions and the level-1 cache's load
and store rates.

A phase's bound is the largest of its resources' times: flops at the vector ceiling (the vector
width bench_ceilings was built for: SSE2 in the portable `bench` build), bytes at the 22 MB
triad, and the division and root instructions one after another at their throughput (one
divider; a packed division costs about what a scalar one does). The table also gives the bound
with flops at the scalar ceiling (what code one particle at a time can reach), the time over
the level-1 cache's ports' bound (the loads and the stores at their measured rates; a column of
its own, as fewer loads were measured not to make a phase faster), and the phase's
instructions per ns, per cycle (bench_ceilings' clock) and as a share of the rate of the
independent additions measured beside it (a loop the integer units bound, not the most the core
issues of a mix). Calls into libm count as their own instructions, flops and divisions included
(their costs are printed for reference).

Attribution: each function callgrind saw is given to a phase by its name (the solver member a
lambda or an OpenMP region belongs to, table PHASES below); a function no pattern names (a
helper, libm) is shared out among its callers in proportion to the instructions each call
costs. What no phase owns is reported as `other` (chiefly what the compiler inlined into the
benchmark's own loop).

    roofline.py BENCH_THROUGHPUT BENCH_CEILINGS [--runs 3] [--steps 300] [--short 3] [--long 13]
    roofline.py BENCH_THROUGHPUT --work-only     the work per phase only: compares two builds exactly
    roofline.py --self-test     checks the classifier and the parser on known input
"""
import argparse
import collections
import functools
import os
import re
import subprocess
import sys
import tempfile

# solver::timings()' phases, in its order, with the names of the solver's stages (and the
# policies' hooks) that run in each (include/gimlet/solver/solver.hpp, the schemes, which time
# each stage into its phase; the stages' own state under include/gimlet/solver/stages/).
PHASES = [
    ("P2G", r"compute_stencils?\b|::scatter(_all|_for_usf|_and_search)?\b|begin_step|slab_schedule::bucket\b|"
            r"\bbucket\(|::prepare\(|group_into_slabs|field_choice::|start_grid|map_forces|"
            r"clear_grid|find_light_particles|light_particles::find\b|find_shared_nodes|average_mean_stress|"
            r"volumetric_average::average_stress\b|self_contact::initialize"),
    ("grid", r"update_grid_momentum|consistent_mass|start_of_step_velocities"),
    ("contact", r"resolve_contact\b|exchange::resolve\b|multi_field::correct\b|clear_forces"),
    ("G2P", r"grid_to_particles|light_particles::move\b|remapped_velocities|nodal_velocity|apply_walls"),
    ("material", r"finish_step|material_pass|update_material_point|update_material_pair|update_stress|"
                 r"velocity_gradient|filter_volumes|volume_filter::apply\b|average_volumetric_rates|"
                 r"volumetric_average::average_rates\b|contact_hook\b|check_step_start|check_pending|count_health"),
]
SCENE_NAMES = {"reference": "reference (elastic)", "hmx": "HMX, the flagship's defaults"}


def strip_templates(name):
    """A demangled name without its template arguments (a lambda's enclosing function and the
    parameter types stay)."""
    out, depth = [], 0
    for ch in name:
        if ch == "<":
            depth += 1
        elif ch == ">":
            depth = max(depth - 1, 0)
        elif depth == 0:
            out.append(ch)
    return "".join(out)


def phase_of(name):
    """The phase a function belongs to by its name: first without template arguments (so that a
    policy's type named among them cannot decide), then, where that names none, with them (a
    lambda that appears only as a template argument, e.g. for_each_kept<...::initialize(...)::
    {lambda}>)."""
    for s in (strip_templates(name), name):
        for phase, pattern in PHASES:
            if re.search(pattern, s):
                return phase
    return None


# ---- callgrind's output (format version 1, positions "instr line", events "Ir")
def parse_callgrind(path):
    """Self counts per (object, function, address) and the call edges (caller, callee,
    calls, inclusive Ir)."""
    names = {"ob": {}, "fn": {}}
    events = ["Ir"]
    self_counts = collections.defaultdict(dict)  # (ob, fn) -> addr -> [count per event]
    edges = collections.defaultdict(lambda: [0, 0])  # ((ob, fn), (cob, cfn)) -> [calls, inclusive Ir]
    ob = fn = cob = cfn = None
    last = 0
    pending_call = None

    def ref(kind, rest):
        m = re.match(r"\((\d+)\)(?: (.*))?", rest)
        if not m:
            return rest
        if m.group(2) is not None:
            names[kind][m.group(1)] = m.group(2)
        return names[kind].get(m.group(1), m.group(1))

    def position(tok):
        nonlocal last
        if tok.startswith("0x"):
            last = int(tok, 16)
        elif tok.startswith("+"):
            last += int(tok[1:])
        elif tok.startswith("-"):
            last -= int(tok[1:])
        # "*": the same position
        return last

    with open(path) as f:
        for line in f:
            line = line.rstrip("\n")
            if not line or line[0] == "#":
                continue
            c = line[0]
            if c in "0123456789+-*":
                parts = line.split()
                addr = position(parts[0])
                counts = [int(x) for x in parts[2:]]  # after the two positions (instr, line)
                counts += [0] * (len(events) - len(counts))
                if pending_call is not None:
                    e = edges[((ob, fn), pending_call)]
                    e[1] += counts[0]
                    pending_call = None
                else:
                    acc = self_counts[(ob, fn)].setdefault(addr, [0] * len(events))
                    for k, v in enumerate(counts):
                        acc[k] += v
                continue
            if line.startswith("events:"):
                events = line.split()[1:]
                continue
            key, _, rest = line.partition("=")
            if key == "ob":
                ob = ref("ob", rest)
                cob = None
            elif key == "fn":
                fn = ref("fn", rest)
                cob = None
            elif key in ("fl", "fi", "fe", "cfi", "cfl"):
                pass
            elif key == "cob":
                cob = ref("ob", rest)
            elif key == "cfn":
                cfn = ref("fn", rest)
            elif key == "calls":
                calls = int(rest.split()[0])
                callee = (cob if cob is not None else ob, cfn)
                edges[((ob, fn), callee)][0] += calls
                pending_call = callee
                # the next line's position is the call's; positions stay relative to it
                cob = None
    return events, self_counts, edges


# ---- classification of instructions
FLOP_OPS = re.compile(r"^v?(add|sub|mul)(s|p)(d|s)$")
FMA_OPS = re.compile(r"^vf(n?)m(add|sub)(132|213|231)(s|p)(d|s)$")
DIV_OPS = re.compile(r"^v?div(s|p)(d|s)$")
SQRT_OPS = re.compile(r"^v?sqrt(s|p)(d|s)$")


def lanes(kind, prec, operands):
    if kind == "s":
        return 1
    width = 16
    if "ymm" in operands:
        width = 32
    if "zmm" in operands:
        width = 64
    return width // (8 if prec == "d" else 4)


def classify(mnemonic, operands):
    """(flops, divisions, roots) of one execution."""
    flops = divs = roots = 0
    m = FLOP_OPS.match(mnemonic)
    if m:
        flops = lanes(m.group(2), m.group(3), operands)
    m = FMA_OPS.match(mnemonic)
    if m:
        flops = 2 * lanes(m.group(4), m.group(5), operands)
    m = DIV_OPS.match(mnemonic)
    if m:
        divs = lanes(m.group(1), m.group(2), operands)
    m = SQRT_OPS.match(mnemonic)
    if m:
        roots = lanes(m.group(1), m.group(2), operands)
    return flops, divs, roots


# Level-1 data cache accesses of one execution (loads, stores), from the operands in Intel
# syntax: an operand in brackets is read, or written where it is the destination of a move or
# a store, or both (a read-modify-write: `add QWORD PTR [rax],rdx`). push and call write the
# stack, pop, ret and leave read it; lea and nop name an address without touching it; a string
# instruction reads or writes its implicit operands; a gather reads, and a scatter writes, one
# element per lane. Counted as one access each, whatever their width (the ceilings measure
# 16-byte accesses, what the portable SSE2 build makes).
STORE_ONLY_OPS = re.compile(
    r"^(v?mov(|s[sd]|ap[sd]|up[sd]|dq[au]|dqa(32|64)|dqu(8|16|32|64)|q|d|[hl]p[sd]|nt\w*|ddup)"
    r"|set\w+|stos\w*|vp?maskmov\w*|v?extract\w+|v?pextr[bwdq]|vcvtps2ph|vpmov[a-z]*[bwdq]|kmov[bwdq]|"
    r"stmxcsr|vstmxcsr|fn?st\w*|fistp?|fisttp)$")
READ_ONLY_DESTINATION_OPS = re.compile(r"^(cmp|test|bt)$")
# One memory operand that is only read (the rest of the operation is on fixed registers).
READ_ONLY_SINGLE_OPS = re.compile(r"^(i?mul|i?div|f(i)?ld\w*|ldmxcsr|vldmxcsr|f(i)?(add|sub|subr|mul|div|divr|com|comp|ucom)\w*|"
                                  r"jmp)$")
NO_ACCESS_OPS = re.compile(r"^(lea|nop\w*|prefetch\w*|endbr64|clflush\w*)$")
GATHER_OPS = re.compile(r"^vp?gather[dq](p[sd]|[dq])$")
SCATTER_OPS = re.compile(r"^vp?scatter[dq](p[sd]|[dq])$")


def _elements(mnemonic, register):
    """Lanes of a gather's or scatter's data register."""
    width = 64 if register.startswith("zmm") else 32 if register.startswith("ymm") else 16
    return width // (8 if mnemonic.endswith(("pd", "q")) else 4)


def memory_accesses(mnemonic, operands):
    """(loads, stores) of one execution."""
    if NO_ACCESS_OPS.match(mnemonic):
        return 0, 0
    if mnemonic == "push":
        return ("[" in operands), 1
    if mnemonic == "pop":
        return 1, ("[" in operands)
    if mnemonic.startswith("call"):
        return ("[" in operands), 1
    if mnemonic.startswith("ret") or mnemonic == "leave":
        return 1, 0
    if mnemonic in ("movs", "movsb", "movsw", "movsq") or (mnemonic == "movsd" and "es:[" in operands):
        return 1, 1  # the string move: ds:[rsi] to es:[rdi]
    if mnemonic.startswith("cmps"):
        return 2, 0
    if mnemonic.startswith(("lods", "scas")):
        return 1, 0
    if GATHER_OPS.match(mnemonic):
        return _elements(mnemonic, operands.split(",")[0].strip()), 0
    if SCATTER_OPS.match(mnemonic):
        return 0, _elements(mnemonic, operands.split(",")[-1].strip())
    if "[" not in operands:
        return 0, 0
    destination = operands.split(",")[0]
    if "[" not in destination:
        return 1, 0
    if READ_ONLY_DESTINATION_OPS.match(mnemonic):
        return 1, 0
    if "," not in operands and READ_ONLY_SINGLE_OPS.match(mnemonic):
        return 1, 0
    if STORE_ONLY_OPS.match(mnemonic):
        return 0, 1
    return 1, 1


_disassembly = {}
PREFIXES = ("rep", "repz", "repnz", "repe", "repne", "lock", "bnd", "notrack", "data16", "addr32",
            "cs", "ds", "es", "ss", "fs", "gs")


def instruction(text):
    """(mnemonic, operands) of one line of objdump's Intel syntax, without its prefixes (as many
    as objdump prints: newer binutils write padding as `data16 cs nop WORD PTR [rax+rax*1+0x0]`)."""
    mnem, _, ops = text.strip().partition(" ")
    ops = ops.strip()
    while mnem in PREFIXES and ops:
        mnem, _, ops = ops.partition(" ")
        ops = ops.strip()
    return mnem, ops


def disassembly(obj):
    """address -> (mnemonic, operands) of an object file (addresses as callgrind gives them:
    file-relative for position-independent objects)."""
    if obj in _disassembly:
        return _disassembly[obj]
    table = {}
    if os.path.exists(obj):
        try:
            text = subprocess.run(["objdump", "-d", "-M", "intel", "--no-show-raw-insn", "-w", obj],
                                  capture_output=True, text=True, check=False).stdout
        except FileNotFoundError:
            sys.exit("roofline.py: objdump not found (scripts/setup.sh --bench installs binutils)")
        for line in text.splitlines():
            m = re.match(r"\s*([0-9a-f]+):\s+(\S+\s*.*)$", line)
            if m:
                table[int(m.group(1), 16)] = instruction(m.group(2))
    _disassembly[obj] = table
    return table


LIBM_CALLS = ("pow", "log", "exp", "cbrt", "floor", "ceil", "sqrt", "atan2", "sin", "cos", "tanh", "fmod")


def callee_label(fn_name):
    base = fn_name.split("@")[0].strip()
    return base if base in LIBM_CALLS else None


def measure_work(events, self_counts, edges):
    """Per phase: instructions, flops, divisions, roots, the bytes from beyond the simulated L2
    (`far bytes`, the 64-byte lines of its read and write misses), and libm calls by name."""
    far = [events.index(e) for e in ("DLmr", "DLmw") if e in events]
    # Each function's own totals.
    own = {}
    for (ob, fn), addrs in self_counts.items():
        table = disassembly(ob)
        t = collections.Counter()
        for addr, counts in addrs.items():
            count = counts[0]
            t["instructions"] += count
            t["far bytes"] += 64 * sum(counts[k] for k in far)
            ins = table.get(addr)
            if ins is None:
                continue
            f, d, r = classify(*ins)
            t["flops"] += f * count
            loads, stores = memory_accesses(*ins)
            t["loads"] += loads * count
            t["stores"] += stores * count
            t["divisions"] += d * count
            t["roots"] += r * count
            # The divider's time: a packed division costs about what a scalar one does.
            t["divider instructions"] += (d > 0) * count
            t["root instructions"] += (r > 0) * count
        own[(ob, fn)] = t

    callers = collections.defaultdict(list)  # callee -> [(caller, inclusive Ir of its calls)]
    for (caller, callee), (_, incl) in edges.items():
        if caller != callee and incl > 0:
            callers[callee].append((caller, float(incl)))

    share = {}

    def distribution(node):
        """A function's phases, as fractions."""
        if node in share:
            return share[node]
        p = phase_of(node[1] or "")
        if p is not None:
            share[node] = {p: 1.0}
            return share[node]
        share[node] = {"other": 1.0}  # what a call cycle back to this function sees
        total = collections.Counter()
        weight = 0.0
        for caller, w in callers.get(node, []):
            for ph, fr in distribution(caller).items():
                total[ph] += w * fr
            weight += w
        share[node] = {ph: v / weight for ph, v in total.items()} if weight > 0 else {"other": 1.0}
        return share[node]

    per_phase = collections.defaultdict(collections.Counter)
    for node, t in own.items():
        for ph, fr in distribution(node).items():
            for k, v in t.items():
                per_phase[ph][k] += v * fr
    # Calls into libm, by name, from the phase of the caller.
    for (caller, callee), (calls, _) in edges.items():
        label = callee_label(callee[1] or "")
        if label is None or "libm" not in (callee[0] or ""):
            continue
        if "libm" in (caller[0] or ""):
            continue  # libm's own internal calls
        for ph, fr in distribution(caller).items():
            per_phase[ph]["call " + label] += calls * fr
    return per_phase


@functools.cache
def cache_args():
    """callgrind's simulated caches set to this machine's L1 data cache and L2 (the simulated
    last level), from sysfs: a miss there is a line the L3 or memory delivers. Stops with a
    message where sysfs does not give both (valgrind's own defaults would make the bytes
    column mean something else)."""
    found = {}
    base = "/sys/devices/system/cpu/cpu0/cache"
    units = {"K": 1024, "M": 1024 * 1024, "G": 1024 ** 3}
    try:
        for index in sorted(i for i in os.listdir(base) if i.startswith("index")):
            d = os.path.join(base, index)
            read = lambda f: open(os.path.join(d, f)).read().strip()
            level, kind, size = read("level"), read("type"), read("size")
            size = int(size[:-1]) * units[size[-1]] if size[-1] in units else int(size)
            geometry = f"{size},{read('ways_of_associativity')},{read('coherency_line_size')}"
            if level == "1" and kind == "Data":
                found["D1"] = geometry
            elif level == "2":
                found["LL"] = geometry
    except (OSError, ValueError, KeyError) as e:
        sys.exit(f"roofline.py: cannot read this machine's cache sizes from {base} ({e})")
    if set(found) != {"D1", "LL"}:
        sys.exit(f"roofline.py: {base} gives no {' and no '.join(sorted({'D1', 'LL'} - set(found)))} cache")
    return [f"--D1={found['D1']}", f"--LL={found['LL']}"]


def callgrind(bench, scene, steps, cell, workdir):
    """The work of a run (measure_work's table) and its particle count."""
    out = os.path.join(workdir, f"cg_{scene}_{steps}.out")
    r = subprocess.run(["valgrind", "--tool=callgrind", "--dump-instr=yes", "--cache-sim=yes", *cache_args(),
                        f"--callgrind-out-file={out}", bench, "--scene", scene, "--threads", "1", "--cell", str(cell),
                        "--steps", str(steps), "--repeats", "1"], check=True, capture_output=True, text=True)
    particles = int(r.stdout.strip().splitlines()[-1].split(",")[3])
    return measure_work(*parse_callgrind(out)), particles


def work_per_update(bench, scene, cell, short, long_, workdir):
    """Per phase, the work of one particle-update: a run of `long_` steps less one of `short`."""
    (s, particles), (l, _) = (callgrind(bench, scene, n, cell, workdir) for n in (short, long_))
    updates = particles * (long_ - short)
    phases = [ph for ph, _ in PHASES] + ["other"]
    return particles, {ph: collections.Counter({k: (l[ph][k] - s[ph][k]) / updates for k in set(l[ph]) | set(s[ph])})
                       for ph in phases}


def whole(x):
    """x to the unit; a difference that rounds to zero prints 0, not -0."""
    return f"{x:.0f}" if round(x) != 0 else "0"


def work_cells(w):
    """The work columns of a row: instructions, flops, divisions and roots, libm calls, level-1
    loads and stores, bytes."""
    calls = {k[5:]: v for k, v in w.items() if k.startswith("call ") and v >= 0.01}
    call_text = ", ".join(f"{v:.2f} {k}" for k, v in sorted(calls.items())) or "–"
    return (f"{whole(w['instructions'])} | {whole(w['flops'])} | {w['divisions']:.1f}, {w['roots']:.1f} | {call_text} "
            f"| {whole(w['loads'])}, {whole(w['stores'])} | {whole(w['far bytes'])}")


def timed(bench, scene, steps, cell, runs):
    """ns per particle-update, of the step and of each phase: the run with the median step time
    and its phases' shares (so that the phases add up to the step)."""
    results = []
    particles = None
    for _ in range(runs):
        r = subprocess.run([bench, "--scene", scene, "--threads", "1", "--cell", str(cell), "--steps", str(steps),
                            "--repeats", "1", "--phases", "1"], capture_output=True, text=True, check=True)
        m = re.search(r"phases \(share of [0-9.]+ s\): (.*)", r.stderr)
        row = r.stdout.strip().splitlines()[-1].split(",")
        particles, wall = int(row[3]), float(row[7])
        per_update = wall / (particles * steps) * 1e9
        shares = {}
        for item in m.group(1).split(","):
            k, v = item.split()
            shares[k] = float(v) * per_update
        results.append((per_update, shares))
    results.sort(key=lambda t: t[0])
    per_update, shares = results[(len(results) - 1) // 2]
    return particles, per_update, shares


def ceilings(bench_ceilings, quick):
    """bench_ceilings' one-thread figures, measured now."""
    text = subprocess.run([bench_ceilings, "--threads", "1", "--quick", "1" if quick else "0"],
                          capture_output=True, text=True, check=True).stdout
    row = re.search(r"^\|\s*1\s*\|\s*([0-9.]+)\s*\|\s*([0-9.]+)\s*\|\s*([0-9.]+)\s*\|\s*([0-9.]+)\s*\|", text, re.M)
    calls = dict(re.findall(r"(division|square root|pow|log) ([0-9.]+)", text))
    if row is None or float(row.group(1)) <= 0 or float(row.group(2)) <= 0 or float(row.group(3)) <= 0:
        sys.exit(f"roofline.py: {bench_ceilings} gave no usable one-thread ceilings:\n{text}")
    clock = re.search(r"clock .*: ([0-9.]+) GHz", text)
    adds = re.search(r"independent register additions: ([0-9.]+) instructions per ns", text)
    l1 = re.search(r"16-byte loads ([0-9.]+) per ns, 16-byte stores ([0-9.]+) per ns", text)
    return {"scalar": float(row.group(1)), "vector": float(row.group(2)), "triad": float(row.group(3)),
            "division": float(calls["division"]), "root": float(calls["square root"]),
            "pow": float(calls["pow"]), "log": float(calls["log"]),
            "clock": float(clock.group(1)) if clock and float(clock.group(1)) > 0 else None,
            "adds": float(adds.group(1)) if adds and float(adds.group(1)) > 0 else None,
            "l1 loads": float(l1.group(1)) if l1 and float(l1.group(1)) > 0 else None,
            "l1 stores": float(l1.group(2)) if l1 and float(l1.group(2)) > 0 else None}


def self_test():
    """The classifier and the parser on known input; exits non-zero on a mismatch."""
    cases = [
        (("addsd", "xmm0,QWORD PTR [rax+0x8]"), (1, 0, 0)),
        (("mulpd", "xmm1,xmm2"), (2, 0, 0)),
        (("vfmadd231pd", "ymm0,ymm1,YMMWORD PTR [rdx]"), (8, 0, 0)),
        (("vfnmadd132sd", "xmm0,xmm1,xmm2"), (2, 0, 0)),
        (("divpd", "xmm0,xmm3"), (0, 2, 0)),
        (("sqrtsd", "xmm0,xmm0"), (0, 0, 1)),
        (("vdivsd", "xmm0,xmm1,QWORD PTR [rax]"), (0, 1, 0)),
        (("movapd", "XMMWORD PTR [rsp+0x10],xmm4"), (0, 0, 0)),
        (("maxsd", "xmm0,xmm1"), (0, 0, 0)),
        (("addpd", "zmm0,zmm1"), (8, 0, 0)),
    ]
    bad = [(ins, classify(*ins), want) for ins, want in cases if classify(*ins) != want]
    accesses = [
        (("movsd", "xmm0,QWORD PTR [rax+0x8]"), (1, 0)),
        (("movaps", "XMMWORD PTR [rdx],xmm1"), (0, 1)),
        (("addpd", "xmm1,XMMWORD PTR [rdx]"), (1, 0)),
        (("add", "QWORD PTR [rax],rdx"), (1, 1)),
        (("cmp", "BYTE PTR [rdi],0x0"), (1, 0)),
        (("comisd", "xmm1,QWORD PTR [rdi+0x470]"), (1, 0)),
        (("lea", "r8,[r8+rax*8]"), (0, 0)),
        (("nop", "WORD PTR cs:[rax+rax*1+0x0]"), (0, 0)),
        (("push", "r15"), (0, 1)),
        (("pop", "rbx"), (1, 0)),
        (("call", "3ccb0 <f>"), (0, 1)),
        (("call", "QWORD PTR [rip+0x2fe2]"), (1, 1)),
        (("ret", ""), (1, 0)),
        (("mulpd", "xmm0,xmm1"), (0, 0)),
        (("vmovapd", "YMMWORD PTR [rsp+0x20],ymm3"), (0, 1)),
        (("sete", "BYTE PTR [rsp+0x8]"), (0, 1)),
        (("jmp", "QWORD PTR [rip+0x2fe2]"), (1, 0)),
        (("nop", "WORD PTR [rax+rax*1+0x0]"), (0, 0)),
        (("movs", "QWORD PTR es:[rdi],QWORD PTR ds:[rsi]"), (1, 1)),
        (("cmps", "BYTE PTR ds:[rsi],BYTE PTR es:[rdi]"), (2, 0)),
        (("leave", ""), (1, 0)),
        (("idiv", "DWORD PTR [rbx+0x4]"), (1, 0)),
        (("inc", "DWORD PTR [rax]"), (1, 1)),
        (("vmaskmovpd", "YMMWORD PTR [rdi],ymm1,ymm0"), (0, 1)),
        (("vextractf128", "XMMWORD PTR [rsp],ymm0,0x1"), (0, 1)),
        (("fstp", "QWORD PTR [rsp]"), (0, 1)),
        (("fld", "QWORD PTR [rsp]"), (1, 0)),
        (("vgatherdpd", "ymm0,QWORD PTR [rax+xmm1*8],ymm2"), (4, 0)),
        (("vscatterdps", "DWORD PTR [rax+zmm1*4]{k1},zmm0"), (0, 16)),
        (("movsd", "xmm0,QWORD PTR [rax]"), (1, 0)),
        (("movsd", "QWORD PTR [rax],xmm0"), (0, 1)),
    ]
    bad += [(ins, memory_accesses(*ins), want) for ins, want in accesses if memory_accesses(*ins) != want]
    parsed = [
        ("data16 cs nop WORD PTR [rax+rax*1+0x0]", ("nop", "WORD PTR [rax+rax*1+0x0]")),
        ("rep stos QWORD PTR es:[rdi],rax", ("stos", "QWORD PTR es:[rdi],rax")),
        ("lock cmpxchg DWORD PTR [rdx],ecx", ("cmpxchg", "DWORD PTR [rdx],ecx")),
        ("addpd  xmm1,XMMWORD PTR [rdx]", ("addpd", "xmm1,XMMWORD PTR [rdx]")),
        ("ret", ("ret", "")),
    ]
    bad += [(text, instruction(text), want) for text, want in parsed if instruction(text) != want]
    text = """version: 1
positions: instr line
events: Ir DLmr DLmw
ob=(1) /nonexistent/a.out
fn=(1) gimlet::solver<x>::compute_stencils() [clone ._omp_fn.0]
0x100 0 5 1 0
+4 * 5 0 1
cob=(2) /nonexistent/libm.so.6
cfn=(2) pow
calls=3 0x50 0
+2 * 90
-2 * 1
fn=(3) main
0x200 0 1
fn=(1)
0x100 0 2
cob=(2)
cfn=(2)
calls=1 0x50 0
0x108 0 30
"""
    with tempfile.NamedTemporaryFile("w", suffix=".out", delete=False) as f:
        f.write(text)
    try:
        events, own, edges = parse_callgrind(f.name)
    finally:
        os.unlink(f.name)
    stencil = ("/nonexistent/a.out", "gimlet::solver<x>::compute_stencils() [clone ._omp_fn.0]")
    checks = [
        (events, ["Ir", "DLmr", "DLmw"]),
        (own[stencil], {0x100: [7, 1, 0], 0x104: [6, 0, 1]}),
        (own[("/nonexistent/a.out", "main")], {0x200: [1, 0, 0]}),
        (dict(edges), {(stencil, ("/nonexistent/libm.so.6", "pow")): [4, 120]}),
        (phase_of(stencil[1]), "P2G"),
        (phase_of("gimlet::solver<a<b>>::grid_to_particles_pass<false>(double, bool)::{lambda(unsigned long)#2}"), "G2P"),
        (phase_of("pow"), None),
        (phase_of("void gimlet::detail::slab_schedule<2>::for_each_kept<gimlet::multi_field::self_contact::"
                  "initialize<V>(V&)::{lambda(unsigned long)#1}>(unsigned char const*, bool, int, V&&) const"), "P2G"),
        (phase_of("void gimlet::multi_field::exchange::resolve<G>(G&)"), "contact"),
        (phase_of("gimlet::solver<a, b>::resolve_contact(gimlet::multi_field::pass)"), "contact"),
        (phase_of("gimlet::solver<a, b>::contact_hook() [clone ._omp_fn.0]"), "material"),
        (phase_of("void gimlet::stages::light_particles<a>::move<b>(b&, double)"), "G2P"),
        (phase_of("void gimlet::stages::consistent_mass<a, 9ul>::apply<b>(b&) [clone ._omp_fn.0]"), "grid"),
        (phase_of("void gimlet::stages::volume_filter<a>::apply<b>(b&)"), "material"),
        (phase_of("gimlet::solver_core<a, b>::scatter_all()"), "P2G"),
        (phase_of("gimlet::solver_core<a, b>::scatter_for_usf()"), "P2G"),
        (phase_of("gimlet::solver<a, b>::begin_step(double)"), "P2G"),
    ]
    bad += [(got, want) for got, want in checks if got != want]
    for b in bad:
        print("roofline.py self-test: mismatch", b, file=sys.stderr)
    print("roofline.py self-test:", "failed" if bad else
          f"{len(cases) + len(accesses) + len(parsed) + len(checks)} checks pass")
    return 1 if bad else 0


def main():
    if sys.argv[1:] == ["--self-test"]:
        sys.exit(self_test())
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("bench")
    ap.add_argument("ceilings", nargs="?", help="the bench_ceilings binary, run just before and after each scene's "
                    "timed runs (not with --work-only)")
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--steps", type=int, default=300)
    ap.add_argument("--short", type=int, default=3)
    ap.add_argument("--long", type=int, default=13)
    ap.add_argument("--cell", type=float, default=0.5)
    ap.add_argument("--scenes", default="reference,hmx")
    ap.add_argument("--quick", action="store_true", help="bench_ceilings' smoke run (its numbers meaningless)")
    ap.add_argument("--work-only", action="store_true",
                    help="only the work per particle-update (no timing, no ceilings): instruction counts do not "
                         "drift with a shared machine's speed, so two builds compare exactly")
    a = ap.parse_args()
    if a.runs < 1 or a.steps < 1:
        ap.error(f"--runs ({a.runs}) and --steps ({a.steps}) must be at least 1")
    if not 0 <= a.short < a.long:
        ap.error(f"--short ({a.short}) and --long ({a.long}): 0 <= short < long (their difference is what is counted)")
    if not a.cell > 0:
        ap.error(f"--cell ({a.cell} mm) must be > 0")
    if a.work_only:
        print("| scene | phase | instructions | flops | divisions, roots | libm calls | L1 loads, stores "
              "| bytes from beyond L2 |")
        print("| --- | --- | --- | --- | --- | --- | --- | --- |")
        with tempfile.TemporaryDirectory() as work:
            for scene in a.scenes.split(","):
                _, table = work_per_update(a.bench, scene, a.cell, a.short, a.long, work)
                table["**the step**"] = sum(table.values(), collections.Counter())
                for ph, w in table.items():
                    print(f"| {SCENE_NAMES.get(scene, scene)} | {ph} | {work_cells(w)} |")
        return
    if a.ceilings is None:
        ap.error("the bench_ceilings binary is needed (or --work-only)")
    notes = []
    print("| scene | phase | time (ns) | instructions | flops | divisions, roots | libm calls | L1 loads, stores "
          "| bytes from beyond L2 | GFLOP/s (of scalar, SSE2) | GB/s (of triad) | bound (ns): SSE2 flops, bytes, divider "
          "| time / bound | time / scalar-flops bound | time / L1 ports' bound "
          "| instructions per ns (per cycle; share of the additions' rate) |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    with tempfile.TemporaryDirectory() as work:
        for scene in a.scenes.split(","):
            before = ceilings(a.ceilings, a.quick)
            particles, step_ns, times = timed(a.bench, scene, a.steps, a.cell, a.runs)
            after = ceilings(a.ceilings, a.quick)
            # The mean of the two readings; the notes give both.
            c = {k: (before[k] + after[k]) / 2 if before[k] and after[k] else None for k in before}
            both = lambda k: f"{before[k]}/{after[k]}"
            notes.append(f"{SCENE_NAMES.get(scene, scene)} (before/after its timed runs): scalar {both('scalar')} "
                         f"and SSE2 {both('vector')} GFLOP/s, triad 22 MB {both('triad')} GB/s, division "
                         f"{both('division')} ns, root {both('root')} ns, pow {both('pow')} ns, log {both('log')} ns"
                         + (f", clock {both('clock')} GHz" if c["clock"] else ", no clock measured")
                         + (f", independent register additions {both('adds')} instructions per ns" if c["adds"] else "")
                         + (f", level-1 loads {both('l1 loads')} and stores {both('l1 stores')} per ns"
                            if c["l1 loads"] and c["l1 stores"] else ""))
            particles_w, work_table = work_per_update(a.bench, scene, a.cell, a.short, a.long, work)
            assert particles_w == particles
            rows = [ph for ph, _ in PHASES] + ["other"]
            sums = collections.Counter()
            for ph in rows + ["step"]:
                if ph == "step":
                    w = sums
                    t = step_ns
                else:
                    w = work_table[ph]
                    t = times.get(ph) if ph != "other" else None
                    sums.update(w)
                    if ph == "other" and w["instructions"] < 1:
                        continue
                resources = {
                    "flops": w["flops"] / c["vector"],
                    "bytes": w["far bytes"] / c["triad"],
                    "divider": w["divider instructions"] * c["division"] + w["root instructions"] * c["root"],
                }
                bound_by = max(resources, key=resources.get)
                bound = resources[bound_by]
                scalar_bound = max(w["flops"] / c["scalar"], resources["bytes"], resources["divider"])
                # The level-1 cache's ports: a separate column, not in the bound above (measured not to
                # bind: docs/performance.md, "What bounds each phase").
                l1 = ({"loads": w["loads"] / c["l1 loads"], "stores": w["stores"] / c["l1 stores"]}
                      if c["l1 loads"] and c["l1 stores"] else {"loads": 0.0})
                l1_by = max(l1, key=l1.get)
                l1_bound = l1[l1_by]
                if t is None:
                    time_text = gf = gb = ratio = sratio = l1ratio = ipc = "–"
                else:
                    time_text = f"{t:.1f}"
                    gflops = w["flops"] / t if t > 0 else 0.0
                    gf = f"{gflops:.2f} ({100 * gflops / c['scalar']:.0f} %, {100 * gflops / c['vector']:.0f} %)"
                    gbs = w["far bytes"] / t if t > 0 else 0.0
                    gb = f"{gbs:.1f} ({100 * gbs / c['triad']:.0f} %)"
                    ratio = f"{t / bound:.1f} ({bound_by})" if bound > 0 else "–"
                    sratio = f"{t / scalar_bound:.1f}" if scalar_bound > 0 else "–"
                    l1ratio = f"{t / l1_bound:.1f} ({l1_by})" if l1_bound > 0 else "–"
                    rate = w["instructions"] / t if t > 0 else 0.0
                    parts = ([f"{rate / c['clock']:.1f}"] if c["clock"] else []) + \
                        ([f"{100 * rate / c['adds']:.0f} %"] if c["adds"] else [])
                    ipc = f"{rate:.1f}" + (f" ({'; '.join(parts)})" if parts else "")
                name = "**the step**" if ph == "step" else ph
                print(f"| {SCENE_NAMES.get(scene, scene)} | {name} | {time_text} | {work_cells(w)} | {gf} | {gb} "
                      f"| {resources['flops']:.1f}, {resources['bytes']:.1f}, {resources['divider']:.1f} | {ratio} | {sratio} "
                      f"| {l1ratio} | {ipc} |")
            sys.stdout.flush()
    print()
    print("ceilings (bench_ceilings, one thread, measured just before and just after each scene's timed runs; "
          "the table uses their mean):")
    for n in notes:
        print(f"- {n}")
    print()
    print("time: solver::timings()' share times the step's wall time per particle-update (median of "
          f"{a.runs} runs of {a.steps} steps); work: callgrind, {a.long} steps less {a.short}, per particle-update; "
          "bound: the largest of flops at the SSE2 ceiling, bytes at the 22 MB triad, divisions and roots at "
          "their throughput (a packed division or root as one); L1 ports' bound: the loads and the stores at the "
          "level-1 cache's measured rates, the larger of the two; `other`: code no phase's pattern names, chiefly what the "
          "compiler inlined into the benchmark's step loop (the step's own serial work, the clock).")


if __name__ == "__main__":
    main()
