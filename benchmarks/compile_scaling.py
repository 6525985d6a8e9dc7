"""How numba's compile time grows with the amount of code and with its shape (docs/performance.md).

    python -m benchmarks.compile_scaling [K ...]

Generates one statement, `out[i] += x[j] * x[k] + math.sqrt(x[m])` with fixed pseudo-random
indices, repeated K times, and compiles it (no cache) in four shapes, each in a child process:
in one function; in one function reading the arrays from a named tuple; spread over 20 helper
functions that one function calls; and the same helpers inlined in numba's IR. For each it
reports the wall time of the compile and the part inside LLVM (numba's `numba:llvm_lock`
events), the rest being numba's typing and lowering in Python. Run it on a quiet core.
"""

from __future__ import annotations

import argparse
import os
import random
import subprocess
import sys
import tempfile
from pathlib import Path

N_ARRAYS, N_OUT, N_HELPERS = 40, 64, 20
SHAPES = ("flat", "named_tuple", "helpers", "inlined_helpers")


def _statements(k: int) -> list[tuple[int, int, int, int]]:
    rng = random.Random(1)
    return [(i % N_OUT, rng.randrange(N_ARRAYS), rng.randrange(N_ARRAYS), rng.randrange(N_ARRAYS)) for i in range(k)]


def kernel_source(k: int, shape: str) -> str:
    """The module that defines `f(arg, out)` for K statements in the given shape."""
    lines = ["import math", "from numba import njit", ""]
    stmts = _statements(k)
    if shape == "flat":
        lines += ["@njit(_nrt=False)", "def f(x, out):"]
        lines += [f"    out[{o}] += x[{j}] * x[{p}] + math.sqrt(x[{m}])" for o, j, p, m in stmts]
    elif shape == "named_tuple":
        lines += ["@njit(_nrt=False)", "def f(b, out):"]
        lines += [f"    out[{o}] += b.a{j}[1] * b.a{p}[2] + math.sqrt(b.a{m}[0])" for o, j, p, m in stmts]
    else:
        inline = ', inline="always"' if shape == "inlined_helpers" else ""
        per = max(1, k // N_HELPERS)
        for h in range(N_HELPERS):
            lines += [f"@njit(_nrt=False{inline})", f"def h{h}(x, out):"]
            lines += [f"    out[{o}] += x[{j}] * x[{p}] + math.sqrt(x[{m}])" for o, j, p, m in stmts[h * per:(h + 1) * per]]
            lines += [""]
        lines += ["@njit(_nrt=False)", "def f(x, out):"]
        lines += [f"    h{h}(x, out)" for h in range(N_HELPERS)]
    return "\n".join(lines) + "\n"


_CHILD = """
import importlib, sys, time
from collections import namedtuple
import numpy as np
import numba
from numba.core import event

from benchmarks.numba_events import Outermost

sys.path.insert(0, sys.argv[1])
mod = importlib.import_module("kernel")
x, out = np.random.rand({n_arrays}) + 1.0, np.zeros({n_out})
arg = x
if sys.argv[2] == "named_tuple":
    Arrays = namedtuple("Arrays", ["a%d" % i for i in range({n_arrays})])
    arg = Arrays(*[np.random.rand(4) + 1.0 for _ in range({n_arrays})])


@numba.njit(_nrt=False)
def tiny(x, out):  # numba's own first-use costs, paid before the timing
    out[0] += x[0] * x[1]


tiny(x, out)


llvm = Outermost()
with event.install_listener("numba:llvm_lock", llvm):
    t0 = time.perf_counter()
    mod.f(arg, out)
    wall = time.perf_counter() - t0
print(wall, llvm.seconds)
""".format(n_arrays=N_ARRAYS, n_out=N_OUT)


def compile_time(k: int, shape: str) -> tuple[float, float]:
    """(wall seconds, of them inside LLVM) of compiling K statements in `shape`, in a child process."""
    with tempfile.TemporaryDirectory() as tmp:
        Path(tmp, "kernel.py").write_text(kernel_source(k, shape))
        env = dict(os.environ, NUMBA_CACHE_DIR=str(Path(tmp, "cache")))
        done = subprocess.run([sys.executable, "-c", _CHILD, tmp, shape], env=env, check=True, capture_output=True,
                              text=True, cwd=Path(__file__).resolve().parents[1])  # where `benchmarks` imports from
    wall, llvm = map(float, done.stdout.split())
    return wall, llvm


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("k", nargs="*", type=int, default=[100, 200, 400], help="statement counts")
    args = ap.parse_args(argv)
    print(f"{'K':>5} {'shape':>16} {'compile [s]':>12} {'LLVM [s]':>9} {'Python [s]':>11}  (load average "
          f"{os.getloadavg()[0]:.2f})")
    for k in args.k:
        for shape in SHAPES:
            wall, llvm = compile_time(k, shape)
            print(f"{k:5d} {shape:>16} {wall:12.2f} {llvm:9.2f} {wall - llvm:11.2f}")


if __name__ == "__main__":
    main()
