"""Compare the planes two checkouts draw for the same random IRIS GL call sequences.

    python bench/compare_front_ends.py COMMIT [--seeds N]

Checks out COMMIT into a temporary git worktree, draws the random call sequences of
tests/stream/random_calls.py there (in a subprocess that imports that checkout's
vgxsim), immediately and through nested display objects, and draws them again with
this checkout; prints how many of the colour, z and stencil planes differ.  This is
how the command-stream front end (issue 6) was checked against the front end it
replaced (commit 74ce134: per-primitive numpy arrays and the compiled display
objects): 40 seeds x 2 modes x 3 planes, 0 differences.  Nothing is stored: the old
checkout's planes live in a temporary folder for the run.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
RANDOM_CALLS = os.path.join(ROOT, "tests", "stream", "random_calls.py")

_WORKER = """
import sys
sys.path.insert(0, {tree!r})
import vgxsim
assert vgxsim.__file__.startswith({tree!r}), vgxsim.__file__
import numpy as np
ns = {{}}
exec(open({script!r}).read(), ns)
out = {{}}
for s in range({seeds}):
    for mode in (False, True):
        for k, v in ns["render"](ns["sequence"](s, n=60), objects=mode, seed=s).items():
            out[f"{{s}}_{{int(mode)}}_{{k}}"] = v
np.savez({path!r}, **out)
"""


def planes_of(tree: str, seeds: int, path: str) -> dict:
    code = _WORKER.format(tree=tree, script=RANDOM_CALLS, seeds=seeds, path=path)
    env = dict(os.environ, PYTHONPATH=tree)
    subprocess.run([sys.executable, "-c", code], env=env, check=True, cwd=tree)
    return dict(np.load(path))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("commit")
    ap.add_argument("--seeds", type=int, default=40)
    args = ap.parse_args(argv)
    with tempfile.TemporaryDirectory() as tmp:
        old_tree = os.path.join(tmp, "old")
        subprocess.run(["git", "-C", ROOT, "worktree", "add", "-q", "--detach", old_tree,
                        args.commit], check=True)
        try:
            old = planes_of(old_tree, args.seeds, os.path.join(tmp, "old.npz"))
            new = planes_of(ROOT, args.seeds, os.path.join(tmp, "new.npz"))
        finally:
            subprocess.run(["git", "-C", ROOT, "worktree", "remove", "--force", old_tree],
                           check=False)
    differ = [k for k in new if not np.array_equal(new[k], old[k])]
    print(f"{len(new)} planes compared, {len(differ)} differ")
    for k in differ:
        print("  differs:", k)
    return 1 if differ else 0


if __name__ == "__main__":
    sys.exit(main())
