"""Cold and warm start to the first image, in fresh processes (issue 7, item 4).

    python bench/startup.py [--rounds N] [--workload triangle|shadows|all]
                            [--python NAME=PATH ...] [--serial]
                            [--variant NAME=VAR=VALUE[,VAR=VALUE...] ...] [--no-pyc]
    python bench/startup.py --compiles [--with-helper] [--workload ...]

Each measurement is one new ``python -c`` process: the time runs from just before
the process is started to the moment its first image exists, so it includes the
interpreter, the imports, the Numba compiles (cold) or cache loads (warm) and the
first frame's Python work.  *Cold*: ``NUMBA_CACHE_DIR`` is a new, empty folder;
*warm*: the same folder again, filled by the cold run just before.  CPU seconds
are given for the process and, apart, for its children (the parallel-compile
helper of vgxsim/coldstart.py): on a loaded machine they move less than wall time,
and on an idle one with two CPUs the larger of the two bounds the cold start.

Python's own bytecode cache goes with the Numba cache, for vgxsim's sources only:
``PYTHONDONTWRITEBYTECODE`` is cleared and ``PYTHONPYCACHEPREFIX`` is one folder
(``PYC_PREFIX``) whose entries for the measured checkout are removed before each cold
run, so a cold run compiles vgxsim's sources to bytecode (as a fresh editable install
would) and a warm one reads them as an installed package would (where the environment
sets PYTHONDONTWRITEBYTECODE, as this project's machines do, every "warm" run used to
compile some 130 modules again: about 0.5 s CPU, bench/startup.py --no-pyc measures
that way).  Python's, numpy's and Numba's own bytecode stays in the folder (filled
once, before the first round), as an installed interpreter's does: with an empty
prefix per cold run, as this script used to give, every cold process -- the helper
too -- compiled the standard library, numpy and Numba to bytecode as well (about
1.5 s CPU each, which no user with an empty Numba cache pays).

Workloads:

* ``triangle``: a 320x256 context, one clear and one Gouraud triangle, read back
  (the figure bench/report.py prints);
* ``shadows``: ``vgxsim shadows -o OUT.png --size 320x256``, the three cubes of
  Heidmann's program with both lights, written to a PNG.

``--python NAME=PATH`` (repeatable) measures other interpreters beside this one,
e.g. one whose editable install is an older checkout: rounds alternate between
them, so that a change of machine load hits every variant alike; compare the
ratios.  ``--serial`` sets VGXSIM_PARALLEL_COMPILE=0 in a second variant of this
interpreter.  ``--variant`` (repeatable) adds this interpreter with other
environment variables, e.g.
``--variant stock=VGXSIM_LINEAR_INLINE=0,VGXSIM_LAZY_REFRESH=0`` for the start-up
switches off (docs/architecture.md).  A ``python -c "import numba"`` line gives
the floor no vgxsim change can go below.  Medians are printed with the load
average before and after.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

# Printed by every workload when its image exists: wall seconds since t0, CPU seconds
# of this process, CPU seconds of its finished children (the cold-start helper).
_DONE = r"""
import resource
_me = resource.getrusage(resource.RUSAGE_SELF)
_kids = resource.getrusage(resource.RUSAGE_CHILDREN)
print(time.time() - t0, _me.ru_utime + _me.ru_stime, _kids.ru_utime + _kids.ru_stime)
"""

TRIANGLE = r"""
import time, sys
t0 = float(sys.argv[1])
from vgxsim.pipeline.context import Context
from vgxsim.geometry.transform import orthographic
ctx = Context(320, 256, stencil=8)
ctx.matrices.load_projection(orthographic(-0.5, 319.5, -0.5, 255.5, -1, 1))
ctx.raster.set(zbuffer=True)
ctx.clear_planes(7, 0xff000000)
ctx.draw_arrays('polygon', [[10, 10, 0], [300, 20, 0], [160, 240, 0]],
                [[1, 0, 0, 1], [0, 1, 0, 1], [0, 0, 1, 1]])
img = ctx.read_rgba()
""" + _DONE

SHADOWS = r"""
import time, sys
t0 = float(sys.argv[1])
from vgxsim.cli import main
status = main(["shadows", "-o", sys.argv[2], "--overwrite", "--size", "320x256"])
assert status == 0, status
""" + _DONE

FLOOR = r"""
import time, sys
t0 = float(sys.argv[1])
import numba
""" + _DONE

WORKLOADS = {"triangle": TRIANGLE, "shadows": SHADOWS}

# --compiles: every Numba compile of the first image (one process, empty cache, no
# helper unless --with-helper), with its own CPU time (nested compiles subtracted) and the
# kernel called from Python whose compile it was part of (its tree).
COUNTER = r"""
import json, sys, time
from numba.core import event
_stack, _rows = [], []
def _name(ev):
    f = ev.data["dispatcher"].py_func
    return f.__module__ + "." + f.__qualname__
class _Count(event.Listener):
    def on_start(self, ev):
        _stack.append([time.process_time(), 0.0, _name(ev)])
    def on_end(self, ev):
        t, nested, name = _stack.pop()
        dt = time.process_time() - t
        if _stack:
            _stack[-1][1] += dt
        root = _stack[0][2] if _stack else name
        _rows.append((name, str(ev.data["args"]), dt - nested, root))
event.register("numba:compile", _Count())
import atexit
atexit.register(lambda: print("COMPILES " + json.dumps(_rows)))
"""


#: Whether runs keep Python's bytecode with the Numba cache (see the module docstring).
PYC = True
#: The bytecode folder of every run (PYTHONPYCACHEPREFIX): the standard library's,
#: numpy's and Numba's bytecode is kept, the measured checkout's removed for a cold run.
PYC_PREFIX = os.path.join(tempfile.gettempdir(), f"vgxsim-startup-pyc-{os.getuid()}")

# Imports what a first image imports, and compiles one small kernel (Numba's compile
# pipeline), without a cache: fills PYC_PREFIX with the bytecode of all but vgxsim.
PRIME = r"""
import numba, numpy as np
import vgxsim.cli, vgxsim.pipeline.context, PIL.Image, PIL.PngImagePlugin
numba.njit(lambda a: np.zeros(3)[0] + a)(1.0)
"""


def _env(cache: str, env_extra: dict) -> dict:
    env = dict(os.environ, NUMBA_CACHE_DIR=cache)
    if PYC:
        env.pop("PYTHONDONTWRITEBYTECODE", None)
        env["PYTHONPYCACHEPREFIX"] = PYC_PREFIX
    env.update(env_extra)
    return env


def forget_bytecode(python: str, env_extra: dict | None = None) -> None:
    """Remove the bytecode of the checkout that ``python`` imports vgxsim from (its
    sources and kernels/) from ``PYC_PREFIX``: the next run compiles it again."""
    if not PYC:
        return
    env = _env(tempfile.gettempdir(), env_extra or {})
    origin = subprocess.run(
        [python, "-c", "import importlib.util as u; print(u.find_spec('vgxsim').origin)"],
        capture_output=True, text=True, env=env, check=True).stdout.strip()
    root = os.path.dirname(os.path.dirname(os.path.realpath(origin)))
    shutil.rmtree(os.path.join(PYC_PREFIX, root.lstrip(os.sep)), ignore_errors=True)


def prime_bytecode(python: str, env_extra: dict | None = None) -> None:
    """Fill ``PYC_PREFIX`` with the bytecode of all a first image imports (a run in a
    throwaway Numba cache, compiling nothing of vgxsim's)."""
    if not PYC:
        return
    with tempfile.TemporaryDirectory() as cache:
        subprocess.run([python, "-c", PRIME], capture_output=True, check=True,
                       env=_env(cache, env_extra or {}), cwd=tempfile.gettempdir())


def run_once(python: str, code: str, cache: str, out: str, env_extra: dict
             ) -> tuple[float, float, float]:
    """Wall seconds to the first image, CPU seconds of the process and of its helper
    (children finished by then) in one run."""
    env = _env(cache, env_extra)
    t0 = time.time()
    proc = subprocess.run([python, "-c", code, repr(t0), out], capture_output=True,
                          text=True, env=env, cwd=tempfile.gettempdir())
    if proc.returncode != 0:
        raise RuntimeError(f"{python} failed:\n{proc.stderr[-2000:]}")
    wall, cpu, helper = (float(x) for x in proc.stdout.strip().splitlines()[-1].split())
    return wall, cpu, helper


def start_times(code: str = TRIANGLE, python: str = sys.executable, warm_runs: int = 1,
                env_extra: dict | None = None) -> tuple[tuple[float, float], list]:
    """One cold run into a new cache folder, then ``warm_runs`` warm runs from it.

    Returns (cold, [warm, ...]), each (wall s, CPU s, helper CPU s) (:func:`run_once`).
    """
    env_extra = env_extra or {}
    prime_bytecode(python, env_extra)
    forget_bytecode(python, env_extra)
    with tempfile.TemporaryDirectory() as cache:
        out = os.path.join(cache, "first.png")
        cold = run_once(python, code, cache, out, env_extra)
        warm = [run_once(python, code, cache, out, env_extra) for _ in range(warm_runs)]
    return cold, warm


def compiles(code: str, python: str = sys.executable, helper: bool = False) -> list:
    """[(function, argument types, own CPU seconds, tree)] of every compile of one cold
    run; ``tree`` is the kernel called from Python whose compile it was part of.

    ``helper``: with the parallel-compile helper of vgxsim/coldstart.py on, so the
    rows are what this process still compiles itself (everything but the band tree
    there ran serially, after the helper: docs/cold_start.md)."""
    with tempfile.TemporaryDirectory() as cache:
        env = dict(os.environ, NUMBA_CACHE_DIR=cache)
        if helper:
            env.pop("VGXSIM_PARALLEL_COMPILE", None)
        else:
            env["VGXSIM_PARALLEL_COMPILE"] = "0"
        proc = subprocess.run([python, "-c", COUNTER + code, repr(time.time()),
                               os.path.join(cache, "first.png")],
                              capture_output=True, text=True, env=env,
                              cwd=tempfile.gettempdir())
    line = [x for x in proc.stdout.splitlines() if x.startswith("COMPILES ")]
    if proc.returncode != 0 or not line:
        raise RuntimeError(f"{python} failed:\n{proc.stderr[-2000:]}")
    return json.loads(line[-1][len("COMPILES "):])


def print_compiles(workload: str, rows: list) -> None:
    """Compile CPU per tree, then per function (specialisations), by own time."""
    per: dict[str, list] = {}
    trees: dict[str, float] = {}
    for _, _, own, root in rows:
        key = root.replace("vgxsim.kernels.", "")
        trees[key] = trees.get(key, 0.0) + own
    for name, _, own, _ in rows:
        key = name.split(".<locals>")[0].replace("vgxsim.kernels.", "")
        per.setdefault(key, [0, 0.0])
        per[key][0] += 1
        per[key][1] += own
    ours = sum(n for k, (n, _) in per.items() if not k.startswith("numba."))
    print(f"\n{workload}: {len(rows)} compiles, {ours} of vgxsim kernels in "
          f"{sum(1 for k in per if not k.startswith('numba.'))} functions; "
          f"own CPU seconds {sum(r[2] for r in rows):.1f}")
    print(" by tree (a kernel called from Python, with all it compiled):")
    for key, own in sorted(trees.items(), key=lambda kv: -kv[1]):
        print(f"  {own:6.2f} s  {key}")
    print(" by function:")
    for key, (n, own) in sorted(per.items(), key=lambda kv: -kv[1][1]):
        more = f"  x{n}" if n > 1 else ""
        print(f"  {own:6.2f} s  {key}{more}")


def _median(xs):
    return statistics.median(xs) if xs else float("nan")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--warm-runs", type=int, default=3, help="warm runs per cold run")
    ap.add_argument("--workload", choices=(*WORKLOADS, "all"), default="triangle")
    ap.add_argument("--python", action="append", default=[], metavar="NAME=PATH")
    ap.add_argument("--variant", action="append", default=[],
                    metavar="NAME=VAR=VALUE[,VAR=VALUE...]",
                    help="also this interpreter with these environment variables")
    ap.add_argument("--compiles", action="store_true",
                    help="list the compiles of each workload's first image and exit")
    ap.add_argument("--with-helper", action="store_true",
                    help="with --compiles: the parallel-compile helper on, so only the "
                         "main process's compiles are listed")
    ap.add_argument("--serial", action="store_true",
                    help="also this interpreter with VGXSIM_PARALLEL_COMPILE=0")
    ap.add_argument("--no-pyc", action="store_true",
                    help="leave PYTHONDONTWRITEBYTECODE / PYTHONPYCACHEPREFIX as they are")
    args = ap.parse_args(argv)
    global PYC
    PYC = not args.no_pyc
    variants = [("this", sys.executable, {})]
    if args.serial:
        variants.append(("serial", sys.executable, {"VGXSIM_PARALLEL_COMPILE": "0"}))
    for spec in args.python:
        name, _, path = spec.partition("=")
        variants.append((name, path, {}))
    for spec in args.variant:
        name, _, assigns = spec.partition("=")
        env = dict(a.split("=", 1) for a in assigns.split(",") if a)
        variants.append((name, sys.executable, env))
    names = list(WORKLOADS) if args.workload == "all" else [args.workload]
    if args.compiles:
        for w in names:
            for name, python, _ in variants:
                print_compiles(f"{w} ({name})", compiles(WORKLOADS[w], python,
                                                         args.with_helper))
        return 0
    load0 = os.getloadavg()
    floor = []
    keys = ("cold", "cold_cpu", "cold_helper", "warm", "warm_cpu")
    res = {(w, v[0]): {k: [] for k in keys} for w in names for v in variants}
    for _, python, env_extra in variants:
        prime_bytecode(python, env_extra)
    for r in range(args.rounds):
        with tempfile.TemporaryDirectory() as cache:
            floor.append(run_once(sys.executable, FLOOR, cache, "", {})[0])
        order = variants if r % 2 == 0 else variants[::-1]
        for w in names:
            for name, python, env_extra in order:
                (cw, cc, ch), warm = start_times(WORKLOADS[w], python, args.warm_runs,
                                                 env_extra)
                d = res[w, name]
                d["cold"].append(cw)
                d["cold_cpu"].append(cc)
                d["cold_helper"].append(ch)
                d["warm"] += [x[0] for x in warm]
                d["warm_cpu"] += [x[1] for x in warm]
                print(f"  round {r} {w:8s} {name:8s} cold {cw:6.2f} s (cpu {cc:6.2f} + helper "
                      f"{ch:5.2f})  warm " + " ".join(f"{x[0]:.2f}" for x in warm)
                      + f"  load {os.getloadavg()[0]:.1f}", flush=True)
    load1 = os.getloadavg()
    print(f"\nload average before {load0[0]:.1f} {load0[1]:.1f} {load0[2]:.1f}, "
          f"after {load1[0]:.1f} {load1[1]:.1f} {load1[2]:.1f}; {os.cpu_count()} CPUs")
    print(f"floor (python -c 'import numba'): median {_median(floor):.2f} s")
    print("medians; cpu = CPU seconds of the process, helper = of its cold-start helper")
    print(f"{'workload':9s} {'variant':8s} {'cold s':>7s} {'cpu':>6s} {'helper':>6s} "
          f"{'warm s':>7s} {'cpu':>6s}  '{variants[0][0]}' / variant: cold, warm")
    for w in names:
        ref = res[w, variants[0][0]]
        for name, _, _ in variants:
            d = res[w, name]
            m = {k: _median(d[k]) for k in keys}
            print(f"{w:9s} {name:8s} {m['cold']:7.2f} {m['cold_cpu']:6.2f} "
                  f"{m['cold_helper']:6.2f} {m['warm']:7.2f} {m['warm_cpu']:6.2f}  "
                  f"{_median(ref['cold']) / m['cold']:.2f}, "
                  f"{_median(ref['warm']) / m['warm']:.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
