#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""How examples/cavity_collapse/plot.py --follow shares the figures between its idle-priority
child and the pool at the run's end (class Follower, draw()), with the drawing replaced by stubs
that record who drew what: the hand-over is what is tested here, not matplotlib (CI installs no
plotting packages; the figures' bytes are checked by hand, docs/performance.md). Every figure
must be drawn, at least once, whoever draws it; a run that ends without `end` draws nothing more;
a child that is slow, fails or dies costs at most its own job; a child whose parent dies exits.

Run: python3 tests/examples/test_plot_follow.py (exit status 0 when every case passes)."""
import os
import signal
import subprocess
import sys
import tempfile
import time
import types
from pathlib import Path

HERE = Path(__file__).resolve().parent
SCRIPT = HERE.parent.parent / "examples" / "cavity_collapse" / "plot.py"

# plot.py imports matplotlib and numpy at the top: empty stand-ins (the stubs below replace
# everything that would use them).
for name in ("matplotlib", "matplotlib.pyplot", "numpy"):
    sys.modules.setdefault(name, types.ModuleType(name))
sys.modules["matplotlib"].use = lambda *a, **k: None
sys.modules["matplotlib"].pyplot = sys.modules["matplotlib.pyplot"]
sys.path.insert(0, str(SCRIPT.parent))
import plot  # noqa: E402

# The start of a script that runs plot.py's parts in a process of its own, with the same empty
# stand-ins for matplotlib and numpy (cases 8 and 9).
STANDALONE = f"""
import os, sys, time, types
for name in ("matplotlib", "matplotlib.pyplot", "numpy"):
    sys.modules.setdefault(name, types.ModuleType(name))
sys.modules["matplotlib"].use = lambda *a, **k: None
sys.path.insert(0, {str(SCRIPT.parent)!r})
from pathlib import Path
import plot
"""

SLOW = {}  # map index -> seconds the child takes on it (the pool is never slow)
FAIL_IN_CHILD = set()  # map indices the child fails on


def mark(out, what):
    """Records a figure drawn: out/drawn/WHAT.PID (the pid tells the child from the pool)."""
    (out / "drawn").mkdir(exist_ok=True)
    (out / "drawn" / f"{what}.{os.getpid()}").write_text("")


def stub_map(out, spacing, i, tc):
    i = int(i)
    if IN_CHILD:
        (out / "child.pid").write_text(str(os.getpid()))
        if i in FAIL_IN_CHILD:
            raise RuntimeError(f"map {i} fails in the child")
        time.sleep(SLOW.get(i, 0.0))
    mark(out, f"map_{i}")
    return [(None, [i]) for _ in plot.PANELS]  # the panels, as plot_map returns them


def stub_maps(out, times, panels, label, cmap, lo, name):
    assert [p[1][0] for p in panels] == [int(i) for i in times["index"]], "the panels in snapshot order"
    mark(out, name)


# The child would lower its priority: here it only says it is the child. At idle priority it
# could wait for long while ctest runs another test beside this one, and the cases below
# depend on what it has done when the run ends, not on the scheduler.
IN_CHILD = False


def stub_lower_priority():
    global IN_CHILD
    IN_CHILD = True


plot.lower_priority = stub_lower_priority
plot.plot_map = stub_map
plot.plot_maps = stub_maps
def stub_series(out):
    mark(out, "series")


def stub_hot_material(out):
    mark(out, "hot_material")


plot.plot_series = stub_series
plot.plot_hot_material = stub_hot_material


def scene(snapshots):
    """A run's folder with `snapshots` maps listed in snapshots/times.csv."""
    out = Path(tempfile.mkdtemp(prefix="plot_follow_"))
    (out / "snapshots").mkdir()
    rows = "".join(f"{i},{10.0 + i},{2.0 * i + 0.5}\n" for i in range(snapshots))
    (out / "snapshots" / "times.csv").write_text("index,time_us,time_after_contact_us\n" + rows)
    return out


def lines(indices, last=True, end=True):
    text = [f"{i} {2.0 * i + 0.5!r}" + (" last" if last and i == indices[-1] else "") for i in indices]
    return [t + "\n" for t in text] + (["end\n"] if end else [])


def drawn(out):
    """Each figure's name and how many times it was drawn."""
    names = [f.name.rsplit(".", 1)[0] for f in (out / "drawn").iterdir()] if (out / "drawn").exists() else []
    return {n: names.count(n) for n in set(names)}


def follow(out, feed, pause=0.0):
    """Runs the Follower over the lines in feed (pausing between them, as a run would) and then
    draw(); returns the seconds draw() took."""
    follower = plot.Follower(out, 0.25)
    follower.read(_slow(feed, pause))
    start = time.monotonic()
    plot.draw(out, 0.25, follower)
    return time.monotonic() - start


def _slow(feed, pause):
    for line in feed:
        time.sleep(pause)
        yield line


failures = []


def check(name, condition, detail=""):
    if not condition:
        failures.append(f"{name}: {detail}")
    print(("ok   " if condition else "FAIL ") + name + (f" ({detail})" if detail and not condition else ""))


def every_figure(snapshots):
    want = {f"map_{i}" for i in range(snapshots)} | {"series", "hot_material"}
    if snapshots >= 2:
        want |= {name for *_, name in plot.PANELS}
    return want


# 1. A run whose child keeps up: every figure, the maps and the many-panel figures by the child.
out = scene(4)
follow(out, lines(range(4)), pause=0.3)
got = drawn(out)
check("every figure drawn", set(got) == every_figure(4), f"{sorted(got)}")
check("each drawn once when the child keeps up", all(n == 1 for n in got.values()), f"{got}")

# 2. The child slow on its first map, which it holds when the run ends: stopped 1 s after the
# pool's work, the map drawn again.
out = scene(3)
SLOW.update({0: 30.0})
seconds = follow(out, lines(range(3)), pause=0.3)
SLOW.clear()
got = drawn(out)
check("a slow child's map drawn by the pool", set(got) == every_figure(3), f"{sorted(got)}")
check("a slow child costs at most its grace", seconds < 5.0, f"draw() took {seconds:.1f} s")

# 3. A restarted run: the maps before the restart were never sent; the pool draws them.
out = scene(5)
follow(out, lines([3, 4]), pause=0.2)
got = drawn(out)
check("a restart's earlier maps drawn", set(got) == every_figure(5), f"{sorted(got)}")

# 4. A run with periodic snapshots sends no `last`: the many-panel figures are drawn at the end.
out = scene(3)
follow(out, lines(range(3), last=False), pause=0.2)
check("no `last`: every figure drawn", set(drawn(out)) == every_figure(3), f"{sorted(drawn(out))}")

# 5. A map that fails in the child is drawn again by the pool, the maps after it too.
out = scene(4)
FAIL_IN_CHILD.add(1)
follow(out, lines(range(4)), pause=0.2)
FAIL_IN_CHILD.clear()
check("a map the child failed on drawn", set(drawn(out)) == every_figure(4), f"{sorted(drawn(out))}")

# 6. No snapshot, and one: series and hot material (no many-panel figure of one snapshot).
for n in (0, 1):
    out = scene(n)
    follow(out, lines(list(range(n))) if n else ["end\n"])
    check(f"{n} snapshot(s): its figures", set(drawn(out)) == every_figure(n), f"{sorted(drawn(out))}")

# 7. A run that ends without `end` (it threw, or was killed): nothing more is drawn, status 1.
out = scene(3)
follower = plot.Follower(out, 0.25)
try:
    follower.read(lines(range(3), end=False))
    check("no `end`: exits", False, "read() returned")
except SystemExit as e:
    check("no `end`: exit status 1", e.code == 1, f"status {e.code}")
check("no `end`: no series drawn", "series" not in drawn(out), f"{sorted(drawn(out))}")

# 8. The script's parent killed while its child draws: the child exits after its map (it does
# not wait for ever on the pipes, whose parent ends it closed).
out = scene(3)
plotter = out / "plotter.py"
plotter.write_text(STANDALONE + f"""
def busy(out, spacing, i, tc):
    (out / "child.pid").write_text(str(os.getpid()))
    time.sleep(3)
plot.plot_map = busy
plot.lower_priority = lambda: None  # as above: the child at normal priority
plot.Follower(Path({str(out)!r}), 0.25).read(sys.stdin)
""")
runner = subprocess.Popen([sys.executable, str(plotter)], stdin=subprocess.PIPE, text=True)
runner.stdin.write("0 0.5\n")
runner.stdin.flush()
deadline = time.monotonic() + 10
while not (out / "child.pid").exists() and time.monotonic() < deadline:
    time.sleep(0.05)
time.sleep(0.1)  # the pid written: the child is in its map
child = int((out / "child.pid").read_text()) if (out / "child.pid").exists() else None
runner.send_signal(signal.SIGKILL)
runner.wait()
check("the child found", child is not None)
alive = child is not None
deadline = time.monotonic() + 8  # its map takes 3 s; then it reads the end of its jobs
while alive and time.monotonic() < deadline:
    try:
        os.kill(child, 0)
        time.sleep(0.05)
    except ProcessLookupError:
        alive = False
check("the child exits with its parent", not alive, f"pid {child} still running")
if alive:
    os.kill(child, signal.SIGKILL)

# 9. The script's end (exit_now, after draw()): its status 0, and every figure drawn before it.
# In a process of its own, with its own stand-ins (os._exit would end this one).
out = scene(3)
ender = out / "ender.py"
ender.write_text(STANDALONE + f"""
def mark(out, what):  # (named functions: the pool's processes find them by name)
    (out / "drawn").mkdir(exist_ok=True)
    (out / "drawn" / f"{{what}}.{{os.getpid()}}").write_text("")
    return [(None, [0]) for _ in plot.PANELS]
def one_map(out, spacing, i, tc):
    return mark(out, f"map_{{int(i)}}")
def many(out, times, panels, label, cmap, lo, name):
    mark(out, name)
def series(out):
    mark(out, "series")
def hot(out):
    mark(out, "hot_material")
plot.plot_map, plot.plot_maps, plot.plot_series, plot.plot_hot_material = one_map, many, series, hot
plot.draw(Path({str(out)!r}), 0.25)
plot.exit_now()
""")
ended = subprocess.run([sys.executable, str(ender)])
check("exit_now: status 0", ended.returncode == 0, f"status {ended.returncode}")
check("exit_now: every figure drawn first", set(drawn(out)) == every_figure(3), f"{sorted(drawn(out))}")

print(f"{len(failures)} failure(s)")
sys.exit(1 if failures else 0)
