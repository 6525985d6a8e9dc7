"""The work-precision window of an earlier commit against this tree's, alternated in one process.

    taskset -c 1 python -m benchmarks.window_ab REV [--scene S] [--rtol 1e-7 3e-7] [--rounds 5]

What the study's HHT-α rows time (`pipeline/studies/work_precision.py`): the 15 ms window of
the scene from its quasi-static start through `instrumented.bearing_window` (compiled loop,
float32 traction passes, samples every 5 us, the step log), at each `--rtol`. REV is exported
as the package `bearingsim_ab_base` (`residual_ab.export_revision`) and the two sides run in
alternation, each first in every other round, after one warm-up window each. Prints each side's
minimum and median wall time, steps and residuals (equal steps mean the same bits), the median of
the per-round ratios and the load average. Nothing is written outside the temporary directory.

Its resolution is poor on a VM: against HEAD with an unchanged tree it gave 1.06 (2026-11-24,
AMD EPYC), and two runs against the previous commit gave 1.09 and 0.98 for the same change, so
where a process's code and data land moves the window by more than most changes do. Read it
over several runs, or time full runs alternated from separate installs.
"""

from __future__ import annotations

import argparse
import dataclasses
import importlib
import os
import sys
import tempfile
from pathlib import Path

import numpy as np

from benchmarks.residual_ab import BASE_PACKAGE, export_revision

WINDOW, SAMPLE = 0.015, 5e-6  # [s], as StudyConfig.for_mode(quick=False)


def _side(package: str, scene_name: str):
    """A function rtol -> (wall [s], steps, residuals) running one window with this package."""
    importlib.import_module(package + ".pipeline.numba_cache").configure_numba_cache()
    scene = importlib.import_module(package + ".pipeline.scene").load_scene(scene_name)
    params, start = importlib.import_module(package + ".pipeline.stages.simulate").build_model(scene, None)
    window = importlib.import_module(package + ".pipeline.studies.instrumented").bearing_window

    def run(rtol: float):
        r, _ = window(params, start, dataclasses.replace(scene.solver, rtol=rtol), WINDOW, SAMPLE)
        if r.error:
            raise RuntimeError(f"{package}: {r.error}")
        return r.wall, r.stats["steps"], r.stats["residual_evaluations"]

    return run


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("rev", help="git revision to compare against (e.g. HEAD)")
    ap.add_argument("--scene", default="helicopter-b-given-hinge")
    ap.add_argument("--rtol", type=float, nargs="+", default=[1e-7, 3e-7])
    ap.add_argument("--rounds", type=int, default=5)
    args = ap.parse_args(argv)
    repo = Path(__file__).resolve().parents[1]
    with tempfile.TemporaryDirectory(prefix="window_ab_") as tmp:
        export_revision(args.rev, repo, Path(tmp))
        sys.path.insert(0, tmp)
        sides = [(f"{args.rev} (base)", _side(BASE_PACKAGE, args.scene)), ("this tree", _side("bearingsim", args.scene))]
        for rtol in args.rtol:
            counts = {label: run(rtol)[1:] for label, run in sides}  # warm-up: compile or load, first touch
            walls: dict[str, list[float]] = {label: [] for label, _ in sides}
            for round_ in range(args.rounds):
                for label, run in (sides if round_ % 2 == 0 else sides[::-1]):
                    walls[label].append(run(rtol)[0])
            print(f"{args.scene}, {WINDOW * 1e3:g} ms window, rtol {rtol:g}, {args.rounds} alternated rounds, "
                  f"load average {os.getloadavg()[0]:.2f}")
            for label, _ in sides:
                w = np.array(walls[label])
                steps, residuals = counts[label]
                print(f"  {label:16s} min {w.min():.3f} s  median {np.median(w):.3f} s  {steps} steps, "
                      f"{residuals} residuals")
            ratio = np.array(walls["this tree"]) / np.array(walls[sides[0][0]])
            print(f"  median of the per-round ratios {np.median(ratio):.3f} (range {ratio.min():.3f}-{ratio.max():.3f})")


if __name__ == "__main__":
    main()
