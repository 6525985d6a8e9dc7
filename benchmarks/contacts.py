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


@numba.njit
def _repeat(n, t, q, v, a, fp, ip, tab_i, tab_o, eta, rule, work, iwork, pp, jp, psi, Hu, Hpsi, Gu, Gpsi, xA, RA,
            v0, mass, want_tangent, ma, g, diag, Kd, Ke, Kf, Kb, Cd, Ce, Cf, Cb):
    s = 0.0
    for _ in range(n):
        s += evaluate_bearing(t, q, v, a, fp, ip, tab_i, tab_o, eta, rule, work, iwork, pp, jp, psi, Hu, Hpsi,
                              Gu, Gpsi, xA, RA, v0, mass, want_tangent, ma, g, diag, Kd, Ke, Kf, Kb, Cd, Ce, Cf, Cb)
    return s


def _time_kernel(model, q, v, ip, want_tangent: bool, number: int, repeat: int = 25) -> float:
    """Best mean time [s] of one kernel call over `repeat` runs of `number` calls."""
    P = model.params
    K, C = model.K, model.C
    a = np.zeros(model.n_dof)
    ma, g = np.zeros(model.n_dof), np.zeros(model.n_dof)
    args = (0.0, q, v, a, P.fp, ip, P.hertz_inner, P.hertz_outer, P.eta_table, P.traction_rule, P.traction_work,
            P.traction_iwork, P.pocket, P.journal, P.pocket_psi, P.hinge_Hu, P.hinge_Hpsi, P.hinge_Gu, P.hinge_Gpsi,
            P.static_x, P.static_R, model.impact_speeds, model.mass, want_tangent, ma, g, model.diag,
            K.D, K.E, K.F, K.B, C.D, C.E, C.F, C.B)
    _repeat(1, *args)
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        _repeat(number, *args)
        best = min(best, (time.perf_counter() - t0) / number)
    return best


MID_RUN = 0.02  # s of simulated time before the mid-run state


def main(scene_name: str = "helicopter-b-given-hinge") -> None:
    from bearingsim.dynamics.bearing import BearingModel, simulate_bearing
    from bearingsim.dynamics.bearing.params import IP_CAGE, IP_FILM, IP_GYRO, IP_HINGE, IP_JOURNAL, IP_TRACTION
    from bearingsim.dynamics.bearing.run import initial_coordinates
    from bearingsim.pipeline.scene import load_scene
    from bearingsim.pipeline.stages.simulate import build_model, hht_settings

    scene = load_scene(scene_name)
    params, start = build_model(scene)
    model = BearingModel(params)
    q, v = initial_coordinates(params, start)

    def switched(**off) -> np.ndarray:
        ip = params.ip.copy()
        for index in off.values():
            ip[index] = 0
        return ip

    contacts_only = dict(hinge=IP_HINGE, gyro=IP_GYRO)
    rows = [
        ("contacts: 44 ball-race (film, Eyring traction), 22 pocket, 1 journal",
         switched(**contacts_only), False, 400),
        ("  without traction", switched(**contacts_only, traction=IP_TRACTION), False, 400),
        ("  without traction and film", switched(**contacts_only, traction=IP_TRACTION, film=IP_FILM), False, 400),
        ("  without the journal", switched(**contacts_only, journal=IP_JOURNAL), False, 400),
        ("  ball-race only (no cage: pockets and journal off)", switched(**contacts_only, cage=IP_CAGE), False, 400),
        ("full residual (+ hinge, gyroscopic moments, loads)", params.ip, False, 400),
        ("full residual + tangent blocks (Newton matrix)", params.ip, True, 40),
    ]
    run = simulate_bearing(params, start, hht_settings(scene), MID_RUN, MID_RUN)
    q_mid, v_mid = run.q[-1], run.v[-1]
    print(f"force kernel of {scene_name} (Z = {params.ball_count}), called from a numba loop, best mean of 25 runs")
    print(f"{'':70s} {'start':>9s} {f'{MID_RUN * 1e3:g} ms':>9s}")
    for label, ip, tangent, number in rows:
        t0 = _time_kernel(model, q, v, ip, tangent, number)
        t1 = _time_kernel(model, q_mid, v_mid, ip, tangent, number)
        print(f"{label:70s} {t0 * 1e6:6.1f} us {t1 * 1e6:6.1f} us")
    print("target: contacts incl. traction <= 50 us on one core")


if __name__ == "__main__":
    main(*sys.argv[1:])
