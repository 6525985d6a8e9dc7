"""Name numba's compiled functions in a `perf` profile of the compiled time loop.

    perf record -F 4000 -D 3000 -o loop.data python -m benchmarks.perf_map [SCENE] [--window 0.3] [--set KEY=VALUE ...]
    perf report -i loop.data --no-children --sort sym

perf names JIT code through /tmp/perf-<pid>.map, and numba writes none: without it every
sample in a kernel is a bare address. This runs the scene's compiled loop over `window`
seconds from its quasi-static start (after one short run that compiles or loads the kernels;
`-D` keeps that start-up out of the profile), then writes the map: the entry address of
every compiled overload of every numba dispatcher in the process and of numba's runtime
functions (`NRT_incref`, `NRT_decref`, `NRT_MemInfo_alloc...`), each reaching to the next
entry. Functions inlined into a kernel are counted as that kernel. This is how the loop's
reference counting was found (README, *Reference counting in the loop*).
"""

from __future__ import annotations

import argparse
import gc
import os
import time

_NRT_FUNCTIONS = ("NRT_incref", "NRT_decref", "NRT_MemInfo_alloc_aligned", "NRT_MemInfo_call_dtor")


def compiled_entries() -> list[tuple[int, str]]:
    """(address, name) of every compiled numba overload in this process and of the runtime's
    reference-count and allocation functions, sorted by address."""
    from numba.core.registry import CPUDispatcher
    from numba.core.runtime import rtsys

    entries = []
    for obj in gc.get_objects():
        if isinstance(obj, CPUDispatcher):
            name = f"{obj.py_func.__module__}.{obj.py_func.__qualname__}"
            for cres in obj.overloads.values():
                address = cres.library.get_pointer_to_function(cres.fndesc.llvm_func_name)
                if address:
                    entries.append((address, name))
    for fn in _NRT_FUNCTIONS:
        try:
            address = rtsys.library.get_pointer_to_function(fn)
        except (AttributeError, KeyError, RuntimeError):
            continue
        if address:
            entries.append((address, fn))
    return sorted(set(entries))


def write_perf_map(entries: list[tuple[int, str]], path: str) -> None:
    """perf's map format: `start size name` in hex, one line per function."""
    with open(path, "w") as f:
        for (address, name), nxt in zip(entries, [*entries[1:], (entries[-1][0] + 4096, "")]):
            size = min(nxt[0] - address, 1 << 20)
            if size > 0:
                f.write(f"{address:x} {size:x} {name}\n")


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scene", nargs="?", default="helicopter-b-given-hinge")
    ap.add_argument("--window", type=float, default=0.3, help="simulated seconds to profile")
    ap.add_argument("--set", action="append", default=[], dest="overrides", metavar="KEY=VALUE",
                    help="a scene override, e.g. solver.rtol=1e-7 (repeatable)")
    args = ap.parse_args(argv)

    from benchmarks.step_cost import loop_ready
    from bearingsim.dynamics.bearing import BearingModel
    from bearingsim.dynamics.multibody.compiled import integrate_compiled

    scene, params, q0, v0 = loop_ready(args.scene, args.overrides)
    t0 = time.perf_counter()
    sol, _ = integrate_compiled(BearingModel(params), 0.0, args.window, q0, v0, scene.solver)
    wall = time.perf_counter() - t0
    s = sol.stats
    path = f"/tmp/perf-{os.getpid()}.map"
    entries = compiled_entries()
    write_perf_map(entries, path)
    print(f"{args.scene}: {args.window:g} s in {wall:.2f} s, {s.steps} steps, {s.newton_iterations} Newton "
          f"iterations ({wall / s.newton_iterations * 1e6:.1f} us each); load average {os.getloadavg()[0]:.2f}")
    print(f"perf map of {len(entries)} functions: {path}")


if __name__ == "__main__":
    main()
