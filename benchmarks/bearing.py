"""Run time of the dynamic bearing model, and scipy's solve_ivp as a baseline.

    python -m benchmarks.bearing [SCENE] [--duration 0.8] [--baseline 0.01] [--method Radau]

HHT-alpha (the product) over `duration`, then scipy.integrate.solve_ivp (Radau or BDF, dense
finite-difference Jacobian) on the same residual as a first-order ODE over `baseline`
seconds. Reports steps, Newton iterations, factorisations, residual evaluations and time per
step; run it on a quiet machine (`taskset -c 0` pins it to one core).
"""

from __future__ import annotations

import argparse
import time

import numpy as np


def _model(scene_name: str, overrides: list[str]):
    from bearingsim.pipeline.scene.load import load_scene
    from bearingsim.pipeline.stages.simulate import build_model

    scene = load_scene(scene_name, overrides)
    params, start = build_model(scene)
    return scene, params, start, scene.solver


def run_hht(params, start, settings, duration: float) -> dict:
    from bearingsim.dynamics.bearing import simulate_bearing

    simulate_bearing(params, start, settings, min(duration, 2e-5), 1e-5)  # compile / load cache
    t0 = time.perf_counter()
    run = simulate_bearing(params, start, settings, duration, 1e-5)
    wall = time.perf_counter() - t0
    return {**run.stats, "wall": wall, "us_per_step": wall / max(run.stats["steps"], 1) * 1e6,
            "cage_speed_end": float(run.channels()["cage/speed"].data[-1]) if params.has_cage else None}




def run_solve_ivp(params, start, duration: float, method: str, rtol: float, atol: float) -> dict:
    from scipy.integrate import solve_ivp

    from bearingsim.dynamics.bearing import BearingModel, layout
    from bearingsim.dynamics.bearing.run import initial_coordinates
    from bearingsim.pipeline.studies.scipy_baseline import ode_rhs

    model = BearingModel(params)
    q0, v0 = initial_coordinates(params, start)
    rhs, counter = ode_rhs(model, model.rotation_slots, layout.spin_row(params.ball_count))
    y0 = np.concatenate([q0, v0])
    rhs(0.0, y0)  # compile / load before timing
    t0 = time.perf_counter()
    sol = solve_ivp(rhs, (0.0, duration), y0, method=method, rtol=rtol, atol=atol)
    wall = time.perf_counter() - t0
    steps = len(sol.t) - 1
    return {"success": bool(sol.success), "message": sol.message, "steps": steps, "nfev": sol.nfev,
            "njev": sol.njev, "nlu": sol.nlu, "wall": wall, "us_per_step": wall / max(steps, 1) * 1e6}


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scene", nargs="?", default="helicopter-b-given-hinge")
    ap.add_argument("--duration", type=float, default=0.8)
    ap.add_argument("--baseline", type=float, default=0.01, help="solve_ivp duration [s]; 0 skips it")
    ap.add_argument("--method", default="Radau", choices=("Radau", "BDF"))
    ap.add_argument("--set", action="append", default=[], dest="overrides")
    args = ap.parse_args(argv)
    scene, params, start, settings = _model(args.scene, args.overrides)
    hht = run_hht(params, start, settings, args.duration)
    print(f"HHT-alpha ({scene.name}, {args.duration} s simulated, alpha {settings.alpha}, "
          f"h <= {settings.max_step:g} s, rtol {settings.rtol:g}):")
    for k in ("steps", "rejected_steps", "newton_iterations", "factorizations", "residual_evaluations", "wall", "us_per_step"):
        print(f"  {k:22s} {hht[k]:.6g}")
    if args.baseline > 0:
        short = run_hht(params, start, settings, args.baseline)
        ivp = run_solve_ivp(params, start, args.baseline, args.method, settings.rtol, settings.atol)
        print(f"solve_ivp {args.method} over {args.baseline} s (rtol {settings.rtol:g}, atol {settings.atol:g}): "
              f"{ivp['message']}")
        for k in ("steps", "nfev", "njev", "nlu", "wall", "us_per_step"):
            print(f"  {k:22s} {ivp[k]:.6g}")
        print(f"  HHT-alpha over the same {args.baseline} s: {short['wall']:.3g} s wall -> "
              f"solve_ivp/HHT wall-time ratio {ivp['wall'] / short['wall']:.1f}")


if __name__ == "__main__":
    main()
