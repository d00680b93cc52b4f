"""A long hostile-input campaign over every public vgxsim.gl call (issue 11 item 5).

    python bench/fuzz_campaign.py [--calls 100000] [--seed 0] [--per-sequence 40]
                                  [--per-call-s 60] [--json FILE]

Draws random call sequences with the generator of tests/gl/test_fuzz.py (random
calls, argument counts and kinds), counts every exception outside the GLError family
(and ScriptExhausted) by call and type, prints one example traceback of each, and
exits 1 if there was any.  A call that runs past ``--per-call-s`` counts as a hang.
"""

from __future__ import annotations

import argparse
import importlib.util
import json
import os
import random
import sys
import time
import warnings
from collections import Counter

HERE = os.path.dirname(os.path.abspath(__file__))


def _load_generator():
    path = os.path.join(HERE, "..", "tests", "gl", "test_fuzz.py")
    spec = importlib.util.spec_from_file_location("vgxsim_fuzz_generator", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--calls", type=int, default=100_000)
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--per-sequence", type=int, default=40)
    p.add_argument("--per-call-s", type=float, default=60.0)
    p.add_argument("--json", help="write the counts to this file")
    a = p.parse_args(argv)
    fuzz = _load_generator()
    rng = random.Random(a.seed)
    failures: Counter = Counter()
    examples: dict = {}
    made = sequences = 0
    t0 = time.perf_counter()
    warnings.simplefilter("ignore")  # numpy overflow warnings are not failures
    with fuzz.fuzz_limits():
        while made < a.calls:
            n = min(a.per_sequence, a.calls - made)
            made += fuzz.run_sequence(rng, rng.randint(1, n) if n > 1 else 1,
                                      per_call_s=a.per_call_s, failures=failures,
                                      examples=examples)
            sequences += 1
    dt = time.perf_counter() - t0
    total = sum(failures.values())
    print(f"{made} calls in {sequences} sequences over {len(fuzz.CALLS)} public calls, "
          f"{dt:.1f} s; {total} exceptions outside the GLError family")
    for (name, kind), count in failures.most_common():
        print(f"  {count:6d}  {name}: {kind}")
    for key, text in examples.items():
        print(f"\n--- {key[0]}: {key[1]}\n{text}")
    if a.json:
        with open(a.json, "w") as f:
            json.dump({"calls": made, "sequences": sequences, "seconds": dt,
                       "exceptions": total,
                       "by_call": {f"{n}: {k}": c for (n, k), c in failures.items()}}, f,
                      indent=1)
    return 1 if total else 0


if __name__ == "__main__":
    sys.exit(main())
