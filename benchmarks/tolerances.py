"""Time the crush-probability analysis (docs/model.md §10.2) on one warm core:

    python -m benchmarks.tolerances [--samples 10000] [--repeat 3]

Prints the wall time of `pipeline.quasistatic.tolerances.analyse` for the validation study's tolerance set
(benchmarks/cage_verdict/data/tolerances_b.toml: dimensions, run-out and temperatures, so the excursion is
interpolated over the internal clearance) and for the same set with the moment varied too (a
two-variable grid), after one warm-up call that loads the quasi-static kernels.
"""

from __future__ import annotations

import argparse
import os
import statistics
import time
import tomllib
from pathlib import Path

TOLERANCES = Path(__file__).resolve().parent / "cage_verdict" / "data"  # the validation study's sets
SETS = {
    "validation set (internal clearance grid, 17 solutions)": {},
    "validation set + moment sd 20 N m (7 x 7 grid, 49 solutions)": {"moment": {"sd": 20.0}},
}


def main(argv=None) -> None:
    from bearingsim.pipeline.machine.numba_cache import configure_numba_cache

    configure_numba_cache()
    from bearingsim.pipeline.quasistatic import tolerances as tol
    from bearingsim.pipeline.scene.load import load_scene

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--samples", type=int, default=10_000)
    ap.add_argument("--repeat", type=int, default=3)
    a = ap.parse_args(argv)
    base = tomllib.loads((TOLERANCES / "tolerances_b.toml").read_text())["tolerances"]
    scene = load_scene("helicopter-b-given-hinge")
    print(f"load average {os.getloadavg()[0]:.2f}; {a.samples} stacks; median of {a.repeat}")
    for name, extra in SETS.items():
        spec = tol.build_tolerance_spec(base | extra | {"samples": a.samples}, scene)
        tol.analyse(scene, spec)  # warm: kernels loaded
        times = []
        for _ in range(a.repeat):
            t0 = time.perf_counter()
            tol.analyse(scene, spec)
            times.append(time.perf_counter() - t0)
        print(f"  {name}: {statistics.median(times):.2f} s (runs {', '.join(f'{t:.2f}' for t in times)})")


if __name__ == "__main__":
    main()
