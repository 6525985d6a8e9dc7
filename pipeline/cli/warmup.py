"""`bearingsim warmup`: compile the force kernels of scenes ahead of their first run, for
container images and cluster nodes (the lock and marker of pipeline.machine.kernel_cache make it once
per machine and kernel configuration)."""

from __future__ import annotations

import dataclasses
import time

from ..machine.kernel_cache import ensure_compiled, kernel_configuration


def _without_fe_hinge(scene):
    """`scene` with an identified hinge replaced by a given one: the hinge's values do not select
    kernels, and the FE stage need not run to compile them."""
    from ..scene.load import variant
    from ..scene.sections import Hinge

    if scene.hinge.source != "fe":
        return scene
    return variant(scene, hinge=Hinge(source="given", translational=(1e9, 1e9, 1e9), bending=(1e5, 1e5),
                                                  damping_ratio_time=scene.hinge.damping_ratio_time))


def compile_force_and_loop(scene) -> None:
    """Compile (or load) the force kernel of `scene`'s dynamic run, without its tangent kernel,
    and the time loop: they need no quasi-static solution (the inner race at its nominal
    position; only the argument types matter)."""
    import numpy as np

    from ...dynamics.bearing.run import compile_force_kernel_and_loop

    from ..stages.simulate import check_dynamic_physics, model_params

    scene = _without_fe_hinge(scene)
    check_dynamic_physics(scene)
    compile_force_kernel_and_loop(model_params(scene, None, np.zeros(3), np.eye(3)), scene.solver)


def compile_scene_kernels(scene) -> None:
    """Compile (or load) every kernel `scene`'s dynamic run calls, without writing results:
    the quasi-static start and the first two steps (an identified hinge is replaced by a given
    one: the hinge's values do not select kernels)."""
    from ...dynamics.bearing.run import load_kernels

    from ..stages.simulate import build_model

    scene = _without_fe_hinge(scene)
    params, start = build_model(scene)
    load_kernels(params, start, scene.solver)


def warm_up(scene_names: list[str] | None = None, report=None) -> list[dict]:
    """Compile the kernels of the built-in scenes (or of `scene_names`: names or files), one
    compile per kernel configuration; `report(row)` is called after each scene. For container
    images and cluster nodes: run once, and every later run on the machine starts warm."""
    from ..machine.numba_cache import configure_numba_cache
    from ..scene.load import builtin_scene_names, load_scene

    from ..stages.quasistatic import solve
    from ..scene.validity import run_findings

    configure_numba_cache()
    rows, done = [], set()
    for name in scene_names or builtin_scene_names():
        scene = load_scene(name)
        key = kernel_configuration(scene)
        if any(f.level == "error" for f in run_findings(scene, {"simulate"})):
            t0 = time.perf_counter()
            solve(scene)
            row = {"scene": name, "configuration": key, "seconds": time.perf_counter() - t0,
                   "status": "quasi-static kernels (the scene does not run the dynamics)"}
        elif key in done:
            row = {"scene": name, "configuration": key, "status": "same kernels as above", "seconds": 0.0}
        else:
            seconds = ensure_compiled(scene, lambda: compile_scene_kernels(scene))
            row = {"scene": name, "configuration": key, "seconds": seconds,
                   "status": "compiled or loaded" if seconds > 0 else "already compiled on this machine"}
            done.add(key)
        rows.append(row)
        if report is not None:
            report(row)
    return rows
