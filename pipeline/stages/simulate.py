"""Stage `simulate`: the HHT-alpha multibody run of the bearing (docs/model.md §4–§9).

Reads the hinge (identified or given) and starts from the quasi-static equilibrium;
writes `timeseries.h5`, `impacts.csv`, `summary.json` and the figures of docs/model.md §11.
"""

from __future__ import annotations

import dataclasses
import time

import numpy as np

from ..staging.artefacts import atomic_write_json
from ..staging.runner import Stage, StageContext
from ..scene.load import Scene
from .identify import HINGE_FILE

TIMESERIES_FILE = "timeseries.h5"
IMPACTS_FILE = "impacts.csv"
SUMMARY_FILE = "summary.json"


def simulate_inputs(scene: Scene) -> dict:
    """Everything physical and numerical; the FE inputs reach it through identify's key.
    The report's own setting (output.paraview_frames) is the report stage's input only."""
    raw = {k: v for k, v in scene.raw.items() if k not in ("name", "description", "fe")}
    if "paraview_frames" in raw.get("output", {}):
        raw["output"] = {k: v for k, v in raw["output"].items() if k != "paraview_frames"}
    return {"scene": raw, "hinge": dataclasses.asdict(scene.hinge)}


def hinge_matrices(scene: Scene, identify_dir) -> tuple | None:
    """(H_u 3x3 [N/m], H_psi (2) [N m/rad], c_G [s]) or None when the inner race is free."""
    h = scene.hinge
    if h.source == "none":
        return None
    if h.source == "given":
        return np.array(h.stiffness_matrix()), np.array(h.bending), h.damping_ratio_time
    from ...fe_model import read_hinge

    H_u, H_psi, _ = read_hinge(identify_dir / HINGE_FILE)
    return np.asarray(H_u, float), np.asarray(H_psi, float), h.damping_ratio_time


def check_dynamic_physics(scene: Scene) -> None:
    """Refuse the `[physics]` keys the dynamic run cannot honour, naming the key."""
    from ..scene.schema import SceneError

    if not scene.physics.centrifugal:
        raise SceneError("physics.centrifugal", "false acts only on the quasi-static solve: the dynamic "
                         "model's inertia always carries the balls' centrifugal force; remove the key "
                         "(or set it true) to run the dynamics")
    if scene.physics.ehd_film and scene.lubricant is None:
        raise SceneError("physics.ehd_film", "true needs a [lubricant] table (the film's viscosity); give "
                         "one, or remove the key (without a lubricant the film is off)")


def build_model(scene: Scene, identify_dir=None):
    """(model parameters, quasi-static start) for `scene` — shared with `bench`."""
    from ...dynamics.quasistatic.result import initial_state

    from .quasistatic import solve

    check_dynamic_physics(scene)
    start = initial_state(solve(scene))
    return model_params(scene, identify_dir, start["inner_race_displacement"], start["inner_race_rotation"]), start


def model_params(scene: Scene, identify_dir, static_x, static_R):
    """The dynamic model's parameters of `scene`, with the inner race's static position
    static_x [m] and rotation static_R (the quasi-static solution's)."""
    from ...dynamics.bearing import build_model_params

    from ..quasistatic.solution import operating_point

    s, p = scene, scene.operating  # the parts at their operating temperatures
    return build_model_params(
        p.bearing, p.cage, p.materials.ball, p.materials.race, p.materials.cage, s.lubricant, operating_point(s),
        hinge=hinge_matrices(s, identify_dir), static_frame=(static_x, static_R), options=s.physics,
        load_step=s.load.load_step)


def _quasistatic_result(stage_dir) -> dict | None:
    """The quasi-static stage's result file, for the crush screen the summary repeats."""
    import json

    from .quasistatic import RESULT_FILE

    if stage_dir is None:
        return None
    try:
        return json.loads((stage_dir / RESULT_FILE).read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None


def compile_dynamic_kernels(scene: Scene, params, start) -> None:
    """Compile (or load) the kernels of the dynamic run: the tangent kernel first, then the force
    kernel and the time loop under their own lock (which a `compile_ahead` child may hold,
    compiling them meanwhile), then the first steps of the run, with everything compiled. Each
    of the three compiles apart from the others: they call each other as first-class functions."""
    from ...dynamics.bearing.run import compile_force_kernel_and_loop, compile_tangent_kernel, load_kernels

    from ..machine.kernel_cache import ensure_compiled, force_configuration, tangent_configuration

    ensure_compiled(scene, lambda: compile_tangent_kernel(params), tangent_configuration(scene))
    ensure_compiled(scene, lambda: compile_force_kernel_and_loop(params, scene.solver), force_configuration(scene))
    load_kernels(params, start, scene.solver)


# Pa: ten times the largest elastic shear modulus measured for an oil film (docs/model.md §6.4)
STIFF_FILM = 1.0e10


def _lubricant_cause(scene: Scene, exc: RuntimeError) -> RuntimeError:
    """A Newton failure of a run whose film is stiffer than any measured one
    (`lubricant.elastic_shear_modulus` above STIFF_FILM), told as the lubricant's (docs/model.md
    §6.4, *Film elasticity*): a film of 1e7-1e12 Pa.s (Barus or any law above about 1.5 GPa) then
    resists slip as dry friction with no slip scale, which Newton cannot follow, and the solver
    keys do not help; a measured elastic modulus bounds that stiffness."""
    from ...dynamics.multibody import IntegrationError

    lub = scene.lubricant
    if not isinstance(exc, IntegrationError) or lub is None or lub.elastic_shear_modulus <= STIFF_FILM \
            or not exc.reason.startswith("Newton"):
        return exc
    # a reason of its own, so that `console.explain` keeps this hint instead of the solver's
    return IntegrationError(exc.t, exc.h, f"with a film that stiff, {exc.reason[:1].lower()}{exc.reason[1:]}", (
        f"the lubricant first: lubricant.elastic_shear_modulus = {lub.elastic_shear_modulus:.3g} Pa leaves the "
        f"film's low-slip stiffness as its viscosity makes it ({lub.viscosity(1.5e9):.3g} Pa.s at 1.5 GPa), "
        f"and near-pure rolling then acts as dry friction that Newton cannot follow; the solver keys do not "
        f"help. Give lubricant.elastic_shear_modulus a measured value (1e8 .. 1e9 Pa; the default is 1e9), or "
        f"physics.traction = 'coulomb' (docs/model.md §6.4)"))


def compute(ctx: StageContext) -> dict:
    from ...dynamics.bearing import simulate_bearing

    from ..results.simulation_output import write_simulation_results

    from ..machine.kernel_cache import ensure_compiled

    scene = ctx.scene
    ctx.progress("quasi-static start", 0.0)
    params, start = build_model(scene, ctx.upstream.get("identify"))
    # on a cold cache: compile once per machine, other processes wait and load (pipeline.machine.kernel_cache)
    ctx.progress("loading the force kernels", 0.0)
    compile_seconds = ensure_compiled(scene, lambda: compile_dynamic_kernels(scene, params, start))
    wall0 = time.perf_counter()

    def progress(t: float, t_end: float, h: float) -> None:
        ctx.progress(f"t = {t * 1e3:7.2f} / {t_end * 1e3:.1f} ms, h = {h:.2e} s", t / t_end)

    # scene.solver is the integrator's own settings (HHTSettings) plus the run's duration
    try:
        run = simulate_bearing(params, start, scene.solver, scene.solver.duration,
                               scene.output.sample_interval, progress=progress)
    except RuntimeError as exc:
        raise _lubricant_cause(scene, exc) from exc
    run.stats["kernel_load_time"] += compile_seconds
    ctx.progress("writing results", 0.99)
    summary = write_simulation_results(ctx.out_dir, scene, params, start, run,
                                       wall_time=time.perf_counter() - wall0,
                                       quasistatic=_quasistatic_result(ctx.upstream.get("quasistatic")))
    atomic_write_json(ctx.out_dir / SUMMARY_FILE, summary)
    return {k: summary[k] for k in ("steps", "wall_time", "integration_wall_time", "kernel_load_time",
                                    "cage_speed_mean", "cage_metal_contact_fraction")}


STAGE = Stage(
    name="simulate",
    depends=("identify", "quasistatic"),
    needed=lambda scene: True,
    inputs=simulate_inputs,
    compute=compute,
    summary="dynamic run: cage orbit, speed, impacts, contact forces",
)
