"""Time to evaluate every contact of the reference bearing once (target <= 50 us).

    python -m benchmarks.contacts [SCENE]
    taskset -c 1 python -m benchmarks.contacts     # steadier on a shared machine

Times the bearing model's force kernel (dynamics/bearing/assembly.py) on the quasi-static
start state and on the state reached after MID_RUN seconds of simulation, called from a
numba loop (no Python dispatch in the figure), minimum over repeats (other work on the
machine only makes times longer). The start state rolls purely: the inner-race contacts
have no spin there, so their traction uses the cheaper far rule; mid-run every contact
slips and spins, which is what the time loop sees.

- "contacts": what the issue counts -- 44 ball–race contacts with film and Eyring traction,
  22 ball–pocket contacts, 1 cage–race journal (hinge and gyroscopic terms switched off);
- the full residual (plus hinge, gyroscopic moments, loads), and the same with the tangent
  blocks the Newton matrix needs;
- a breakdown by switching parts off (differences of these rows).
"""

from __future__ import annotations

import sys
import time
import numba
import numpy as np

from bearingsim.dynamics.bearing.assembly import evaluate_bearing


def repeat_loop(evaluate):
    """A numba loop calling the force kernel `evaluate` (`evaluate_bearing` of one version of
    the package) n times: no Python dispatch in the figure."""
    @numba.njit
    def repeat(n, t, q, v, a, data, want_tangent, ma, g, diag, K, C):
        s = 0.0
        for _ in range(n):
            s += evaluate(t, q, v, a, data, want_tangent, ma, g, diag, K, C)
        return s
    return repeat


_repeat = repeat_loop(evaluate_bearing)


def _time_kernel(model, q, v, want_tangent: bool, number: int, repeat: int = 25, loop=None) -> float:
    """Best mean time [s] of one `evaluate_bearing` call over `repeat` runs of `number` calls,
    residual-only (the time loop's Newton iterations) or with want_tangent (`loop` overrides
    the kernel loop)."""
    loop = loop or _repeat
    a = np.zeros(model.n_dof)
    ma, g = np.zeros(model.n_dof), np.zeros(model.n_dof)
    args = (0.0, q, v, a, model.kernel_data(), want_tangent, ma, g, model.diag, model.K.blocks(), model.C.blocks())
    loop(1, *args)
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        loop(number, *args)
        best = min(best, (time.perf_counter() - t0) / number)
    return best


MID_RUN = 0.02  # s of simulated time before the mid-run state


def main(scene_name: str = "helicopter-b-given-hinge") -> None:
    from bearingsim.dynamics.bearing import BearingModel, simulate_bearing
    from bearingsim.dynamics.bearing.run import initial_coordinates
    from bearingsim.pipeline.scene.load import load_scene
    from bearingsim.pipeline.stages.simulate import build_model

    scene = load_scene(scene_name)
    params, start = build_model(scene)
    q, v = initial_coordinates(params, start)
    contacts_only = ("hinge", "gyroscopic")
    rows = [
        ("contacts: 44 ball-race (film, Eyring traction), 22 pocket, 1 journal", contacts_only, False, 400),
        ("  without traction", (*contacts_only, "traction"), False, 400),
        ("  without traction and film", (*contacts_only, "traction", "film"), False, 400),
        ("  without the journal", (*contacts_only, "journal"), False, 400),
        ("  ball-race only (no cage: pockets and journal off)", (*contacts_only, "cage"), False, 400),
        ("full residual (+ hinge, gyroscopic moments, loads)", (), False, 400),
        ("  the same through evaluate_bearing (reference counting)", (), _repeat, 400),
        ("full residual + tangent blocks (Newton matrix)", (), True, 40),
    ]
    run = simulate_bearing(params, start, scene.solver, MID_RUN, MID_RUN)
    q_mid, v_mid = run.q[-1], run.v[-1]
    print(f"force kernel of {scene_name} (Z = {params.ball_count}), called from a numba loop, best mean of 25 runs")
    print(f"{'':70s} {'start':>9s} {f'{MID_RUN * 1e3:g} ms':>9s}")
    for label, off, tangent, number in rows:
        model = BearingModel(params.with_float32_residual().without(*off))  # as the time loop runs it
        loop = tangent if callable(tangent) else None
        tangent = tangent is True
        t0 = _time_kernel(model, q, v, tangent, number, loop=loop)
        t1 = _time_kernel(model, q_mid, v_mid, tangent, number, loop=loop)
        print(f"{label:70s} {t0 * 1e6:6.1f} us {t1 * 1e6:6.1f} us")
    print("target: contacts incl. traction <= 50 us on one core")


if __name__ == "__main__":
    main(*sys.argv[1:])
