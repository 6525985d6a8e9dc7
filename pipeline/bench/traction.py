"""Benchmark: Eyring traction per contact call, fast path vs quadrature reference.

Run: python -m pipeline.bench.traction
Prints the time per call (in a numba loop, so without Python call overhead for the fast
path) and the agreement with the converged quadrature over a random sample of the
reference scene's operating range (tests/lubrication_points.py defines the range; the
same construction is repeated here so the benchmark does not import the test suite).
"""

from __future__ import annotations

import math
import time

import numba
import numpy as np

from dynamics import film, traction
from dynamics.lubricant import load_builtin_lubricant
from dynamics.traction_fast import FastTraction, traction_fast

D, DM, E_EFF, OMEGA = 0.01905, 0.158003, 208e9 / 0.91, 320.0


def _points(n: int, lub, seed: int = 1) -> np.ndarray:
    """(a, b, p_h, h, du0, dv0, w_s) over 100..6000 N, 0.1..2x speed, SRR 1e-5..0.3, spin 0.01..0.1."""
    rng = np.random.default_rng(seed)
    logu = lambda lo, hi: math.exp(rng.uniform(math.log(lo), math.log(hi)))  # noqa: E731
    rows = []
    for _ in range(n):
        c = math.cos(math.radians(rng.uniform(25, 35)))
        inner = rng.uniform() < 0.5
        Rx = 1 / (2 / D + 2 * c / (DM - D * c)) if inner else 1 / (2 / D - 2 * c / (DM + D * c))
        Ry = 1 / (2 / D - 1 / ((0.512 if inner else 0.520) * D))
        F = logu(100, 6000)
        k, ell, R = 1.0339 * (Ry / Rx) ** 0.636, 1.0003 + 0.5968 * Rx / Ry, 1 / (1 / Rx + 1 / Ry)
        b = (6 * k * k * ell * F * R / (math.pi * E_EFF)) ** (1 / 3)
        a = (6 * ell * F * R / (math.pi * k * E_EFF)) ** (1 / 3)
        u = DM * OMEGA / 4 * (1 - (D * c / DM) ** 2) * logu(0.1, 2)
        h = film.film_central_nvm(F, Rx, Ry, E_EFF, lub.eta0, lub.alpha_star, 2 * u)
        slip, phi = logu(1e-5, 0.3) * u, rng.uniform(0, 2 * math.pi)
        w_s = math.copysign(logu(0.01, 0.1), rng.uniform(-1, 1)) * u / b
        rows.append((a, b, 3 * F / (2 * math.pi * a * b), h, slip * math.cos(phi), slip * math.sin(phi), w_s))
    return np.array(rows)


@numba.njit
def _loop_fast(P, tau0, eta_table, p_step, gl_x, gl_w, ga_x, ga_w, far_ratio, nodes, out, repeats):
    for _ in range(repeats):
        for m in range(P.shape[0]):
            traction_fast(P[m, 0], P[m, 1], P[m, 2], P[m, 3], tau0, P[m, 4], P[m, 5], P[m, 6],
                          eta_table, p_step, gl_x, gl_w, ga_x, ga_w, far_ratio, nodes, out)


def main() -> None:
    lub = load_builtin_lubricant("nato-o156")
    tau0, model, params = lub.eyring_stress, lub.model_code, lub.rheology_params()
    P = _points(200, lub)
    print("Eyring traction per contact call (nato-o156 at 100 degC, 200 random operating points)")
    print(f"{'path':<34}{'nodes':>8}{'us/call':>10}{'max dF/F':>10}{'max dM/M':>10}{'max dJ':>9}")
    ref = [traction.traction_quadrature(a, b, ph, h, tau0, model, params, du, dv, w, 128, 1024) for a, b, ph, h, du, dv, w in P[:60]]
    for n_r, n_a in [(8, 24), (8, 32), (10, 40), (12, 48)]:
        ft = FastTraction.build(lub, n_radial=n_r, n_angle=n_a)
        out = np.empty(12)
        _loop_fast(P, tau0, *ft.args(), out, 1)
        t0 = time.perf_counter()
        _loop_fast(P, tau0, *ft.args(), out, 20)
        dt = (time.perf_counter() - t0) / (20 * len(P))
        eF = eM = eJ = 0.0
        for p, r in zip(P[:60], ref):
            f, J, _ = ft.evaluate(*p)
            eF = max(eF, math.hypot(f[0] - r[0], f[1] - r[1]) / math.hypot(r[0], r[1]))
            eM = max(eM, abs(f[2] - r[2]) / abs(r[2]))
            eJ = max(eJ, np.abs(J - r[3]).max() / np.abs(r[3]).max())
        print(f"{'fast pole-centred ' + str((n_r, n_a)):<34}{n_r * n_a:>8}{dt * 1e6:>10.2f}{eF:>10.1e}{eM:>10.1e}{eJ:>9.1e}")
    for grid in [(48, 256), (128, 1024)]:
        t0 = time.perf_counter()
        for a, b, ph, h, du, dv, w in P[:20]:
            traction.traction_quadrature(a, b, ph, h, tau0, model, params, du, dv, w, *grid)
        dt = (time.perf_counter() - t0) / 20
        print(f"{'quadrature ' + str(grid):<34}{grid[0] * grid[1]:>8}{dt * 1e6:>10.1f}")
    print("errors are against the (128, 1024) quadrature, itself within ~0.3 % of converged")


if __name__ == "__main__":
    main()
