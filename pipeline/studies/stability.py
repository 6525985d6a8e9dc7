"""Stability suite: stiff and extreme cases of the bearing model.

    python -m bearingsim.pipeline.studies.stability [CASE ...] [--window 0.01] [--out DIR]
    bearingsim stability [CASE ...]

One scene per case in `pipeline/scenes/stability/` (a subfolder, so `bearingsim scenes`
does not list them; each is a complete scene: `bearingsim simulate <path>` runs it). Every
case is run over a fixed window from its quasi-static start with the scene's own solver
settings and must end in one of two ways:

* **pass** — the window completes, every sample is finite, and the state is physical:
  kinetic energy bounded (`MAX_KINETIC_RATIO` times the start), the cage no deeper into
  its guide land than `MAX_LAND_PENETRATION`, every ball within `MAX_BALL_DRIFT` of its
  pitch circle;
* **refused** — the run stops with a specific error that says when, why and what to try
  (IntegrationError of the integrator, the scene validation, or the wall-clock budget:
  no case can hang).

Anything else — a finished run that fails a physical check — is **garbage** and a defect.
The case "far-from-equilibrium" is the base scene started away from equilibrium by this
harness (`PERTURBATIONS`): cage at rest and off centre, inner race displaced.
"""

from __future__ import annotations

import argparse
import math
import os
import time
from dataclasses import dataclass
from importlib import resources
from pathlib import Path

import numpy as np

MAX_KINETIC_RATIO = 1.5        # max T(t) / T(0): the inner race's prescribed spin dominates T
MAX_LAND_PENETRATION = 100e-6  # [m] e - C at the guide land: Lundberg gives ~5 um at 1 kN, ~30 um
                               # at 7 kN; 100 um (~30 kN) means the cage went through the land
MAX_BALL_DRIFT = 0.5           # [ball diameters] ball centre from its pitch circle / axial plane
DEFAULT_WINDOW = 0.010         # [s] ~ 0.5 inner-race revolution at 3060 rev/min
DEFAULT_WALL_BUDGET = 180.0    # [s] per case
SAMPLE_INTERVAL = 1e-5         # [s] of the recorded history
# the physical checks read the sampled history (energy against the start, drift of the balls):
# a window holds at least the start and one sample after it
MIN_SAMPLES = 2
MIN_WINDOW = MIN_SAMPLES * SAMPLE_INTERVAL

# Start "far from equilibrium": cage at rest, 80 % of the guide clearance off centre along
# +x, inner race 5 um off its equilibrium along +x (5 kN in the 1e9 N/m hinge).
PERTURBATIONS = {"far-from-equilibrium": {"cage_offset_fraction": 0.8, "cage_speed_factor": 0.0,
                                          "inner_offset": 5e-6}}


@dataclass(frozen=True)
class CaseResult:
    case: str
    status: str            # "pass" | "refused" | "garbage"
    message: str
    wall: float
    window: float
    stats: dict
    checks: dict
    history: np.ndarray    # (t, h, evaluations, matrix builds) per accepted step

    def as_row(self) -> dict:
        return {k: v for k, v in self.__dict__.items() if k != "history"}


def case_names() -> list[str]:
    files = resources.files("bearingsim.pipeline") / "scenes" / "stability"
    return sorted(p.name[:-5] for p in files.iterdir() if p.name.endswith(".toml"))


def case_path(name: str) -> Path:
    if name not in case_names():
        raise ValueError(f"unknown stability case {name!r}; cases: {', '.join(case_names())}")
    return Path(str(resources.files("bearingsim.pipeline") / "scenes" / "stability" / f"{name}.toml"))


def perturbed_start(params, start: dict, perturbation: dict) -> tuple[np.ndarray, np.ndarray]:
    """(q0, v0) of the quasi-static start moved away from equilibrium (see PERTURBATIONS)."""
    from ...dynamics.bearing import layout
    from ...dynamics.bearing.run import initial_coordinates

    q0, v0 = initial_coordinates(params, start)
    Z = params.ball_count
    q0[layout.inner_offset(Z)] += perturbation.get("inner_offset", 0.0)
    if params.has_cage:
        c = layout.cage_offset(Z, True)
        q0[c] += perturbation.get("cage_offset_fraction", 0.0) * params.guide_clearance
        v0[c + 5] *= perturbation.get("cage_speed_factor", 1.0)
    return q0, v0


def physical_checks(params, run, q0, v0) -> dict:
    """The checks that tell a physical result from garbage; values and whether each holds."""
    from ...dynamics.bearing import BearingModel, layout

    model = BearingModel(params)
    q, v = run.q, run.v
    finite = bool(np.all(np.isfinite(q)) and np.all(np.isfinite(v)))
    out = {"finite": finite}
    if not finite:
        return out
    T0 = model.kinetic_energy(v0)
    T = 0.5 * np.sum(model.mass * v * v, axis=1)
    out["kinetic_ratio_max"] = float(T.max() / T0)
    Z = params.ball_count
    if params.has_cage:
        eps, force = _land_contact(model, run)
        out["land_penetration_max"] = float(max(0.0, (eps.max() - 1.0) * params.guide_clearance))
        out["land_metal_force_max"] = float(force.max())
    D, r_pitch = params.ball_diameter, 0.5 * params.pitch_diameter
    balls = layout.ball_states(q, Z)[:, :, :3]
    radial = np.hypot(balls[..., 0], balls[..., 1]) - r_pitch
    out["ball_drift_max"] = float(max(np.abs(radial).max(), np.abs(balls[..., 2]).max()) / D)
    out["ok"] = (out["kinetic_ratio_max"] <= MAX_KINETIC_RATIO
                 and out.get("land_penetration_max", 0.0) <= MAX_LAND_PENETRATION
                 and out["ball_drift_max"] <= MAX_BALL_DRIFT)
    return out


def _land_contact(model, run) -> tuple[np.ndarray, np.ndarray]:
    """Eccentricity ratio e/C at the guide land and metal-contact force [N] at every sample,
    from the model's own journal diagnostics (docs/model.md §8)."""
    n = model.n_dof
    ma, g, a = np.zeros(n), np.zeros(n), np.zeros(n)
    eps, force = np.zeros(run.t.size), np.zeros(run.t.size)
    for i in range(run.t.size):
        model.evaluate(float(run.t[i]), run.q[i], run.v[i], a, ma, g)
        eps[i] = model.channel("cage_race/eccentricity_ratio")
        force[i] = model.channel("cage_race/metal_force")
    return eps, force


def _diagnosis(history: np.ndarray) -> str:
    """What the step history says about a stopped run: step sizes and Newton work."""
    if history.shape[0] < 2:
        return ""
    h = history[1:, 1]
    per_step = history[:, 2].mean()
    return (f"[{history.shape[0]} accepted steps, h median {np.median(h):.2g} s (min {h.min():.2g} s), "
            f"{per_step:.1f} residual evaluations and {history[:, 3].mean():.2f} matrix builds per "
            "accepted step]")


def run_case(name: str, window: float = DEFAULT_WINDOW, wall_budget: float = DEFAULT_WALL_BUDGET,
             sample_interval: float = SAMPLE_INTERVAL, scene_path: Path | None = None) -> CaseResult:
    """Run one case; every failure becomes a 'refused' result with its message."""
    from ..scene.load import load_scene
    from ..scene.schema import SceneError
    from ..stages.simulate import build_model

    from .instrumented import bearing_window

    t0 = time.perf_counter()
    empty = np.zeros((0, 4))
    try:
        scene = load_scene(scene_path or case_path(name))
        params, start = build_model(scene, None)
        settings = scene.solver
    except (SceneError, ValueError, RuntimeError, ArithmeticError) as exc:
        return CaseResult(name, "refused", f"set-up: {type(exc).__name__}: {exc}",
                          time.perf_counter() - t0, window, {}, {}, empty)
    q0, v0 = perturbed_start(params, start, PERTURBATIONS.get(name, {}))
    budget = max(wall_budget - (time.perf_counter() - t0), 0.0)
    run, _ = bearing_window(params, start, settings, window, sample_interval, wall_budget=budget,
                            q0=q0, v0=v0)
    wall = time.perf_counter() - t0
    if not run.completed:
        return CaseResult(name, "refused", f"{run.error_kind}: {run.error} {_diagnosis(run.history)}",
                          wall, window, run.stats, {}, run.history)
    checks = physical_checks(params, run, q0, v0)
    if checks["finite"] and checks["ok"]:
        return CaseResult(name, "pass", "completed; finite, bounded energy, physical positions",
                          wall, window, run.stats, checks, run.history)
    return CaseResult(name, "garbage", f"completed but failed a physical check: {checks}", wall,
                      window, run.stats, checks, run.history)


def markdown_table(results: list[CaseResult]) -> str:
    lines = ["| case | status | wall [s] | steps | rejected | Newton it. | LU | min h [s] | T_max/T_0 | "
             "land pen. [um] | land force [N] | message |", "|" + "---|" * 12]
    for r in results:
        s, c = r.stats, r.checks
        h = r.history[1:, 1] if r.history.shape[0] > 1 else np.array([math.nan])
        lines.append(f"| {r.case} | {r.status} | {r.wall:.1f} | {s.get('steps', '-')} | "
                     f"{s.get('rejected_steps', '-')} | {s.get('newton_iterations', '-')} | "
                     f"{s.get('factorizations', '-')} | {h.min():.2g} | "
                     f"{c.get('kinetic_ratio_max', math.nan):.3f} | "
                     f"{c.get('land_penetration_max', math.nan) * 1e6:.2f} | "
                     f"{c.get('land_metal_force_max', math.nan):.0f} | {r.message[:300]} |")
    return "\n".join(lines)


def write_suite(results: list[CaseResult], out_dir: Path) -> list[Path]:
    """stability.json, .md and .png in `out_dir` (atomic writes)."""
    from . import write_study_files
    from .wp_plots import plot_stability

    rows = [{**r.as_row(), "history": r.history} for r in results]
    return write_study_files([r.as_row() for r in results], out_dir, "stability",
                             markdown_table(results) + f"\n\nLoad average {os.getloadavg()[0]:.1f}.",
                             lambda path: plot_stability(rows, path))


def run_suite(names: list[str] | None = None, window: float = DEFAULT_WINDOW,
              wall_budget: float = DEFAULT_WALL_BUDGET, progress=print) -> list[CaseResult]:
    results = []
    for name in names or case_names():
        progress(f"{name} ...")
        r = run_case(name, window, wall_budget)
        progress(f"{name}: {r.status} in {r.wall:.1f} s — {r.message[:200]}")
        results.append(r)
    return results


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("cases", nargs="*", help=f"default: all ({', '.join(case_names())})")
    ap.add_argument("--window", type=float, default=DEFAULT_WINDOW)
    ap.add_argument("--wall-budget", type=float, default=DEFAULT_WALL_BUDGET)
    ap.add_argument("--out", type=Path, default=Path("runs/stability"))
    args = ap.parse_args(argv)
    results = run_suite(args.cases or None, args.window, args.wall_budget)
    write_suite(results, args.out)
    print(markdown_table(results))


if __name__ == "__main__":
    main()
