"""Benchmark: the NVM film of 44 contacts, one libm call after another vs the vectorised batch.

Run: python -m benchmarks.film
Times the law's `nvm.central_film_from_terms` called contact by contact against
`film.film_central_nvm_batch` (what the time loop does: each of the formula's 16 exp and log
over all contacts in one pass, `dynamics._speed.simd_math`), on 44
contacts of the reference bearing (22 balls x inner and outer race) at random contact
angles, loads and speeds; both inside a numba loop, minimum over 7 repeats. Prints the
largest relative difference of the two as well. Pin to one core for steadier numbers:
taskset -c 1 python -m benchmarks.film
"""

from __future__ import annotations

import math
import time

import numba
import numpy as np

from bearingsim.dynamics.lubrication import film
from bearingsim.dynamics.lubrication.film_laws import nvm
from bearingsim.dynamics.lubrication.lubricant import load_builtin_lubricant

D, DM, E_EFF, OMEGA = 0.01905, 0.158003, 208e9 / 0.91, 320.0  # benchmarks/traction.py's bearing
N_CONTACTS = 44


def contacts(seed: int = 1) -> tuple[np.ndarray, ...]:
    """(F [N], R_x [m], u_s [m/s], the five `nvm.geometry_terms` as rows) of N_CONTACTS contacts:
    contact angle 25..35 deg, load 100..6000 N, 0.5..1.5 x the nominal entrainment speed."""
    rng = np.random.default_rng(seed)
    F, Rx, u, terms = [], [], [], []
    for i in range(N_CONTACTS):
        inner, c = i % 2 == 0, math.cos(math.radians(rng.uniform(25, 35)))
        rx = 1 / (2 / D + 2 * c / (DM - D * c)) if inner else 1 / (2 / D - 2 * c / (DM + D * c))
        ry = 1 / (2 / D - 1 / ((0.512 if inner else 0.520) * D))
        F.append(math.exp(rng.uniform(math.log(100), math.log(6000))))
        Rx.append(rx)
        u.append(DM * OMEGA / 2 * (1 - (D * c / DM) ** 2) * rng.uniform(0.5, 1.5))
        terms.append(nvm.geometry_terms(rx, ry))
    return np.array(F), np.array(Rx), np.array(u), *np.ascontiguousarray(np.array(terms).T)


@numba.njit
def _one_by_one(repeats, F, Rx, u, ri, ei, h00, rp, ep, E, eta0, alpha_p, h):
    for _ in range(repeats):
        for i in range(F.shape[0]):
            h[i] = nvm.central_film_from_terms(F[i], Rx[i], E, eta0, alpha_p, u[i], (ri[i], ei[i], h00[i], rp[i], ep[i]))


@numba.njit
def _batch(repeats, film_in, E, eta0, alpha_p, h, work, iwork):
    for _ in range(repeats):
        film.film_central_nvm_batch(film_in, film_in.shape[1], E, eta0, alpha_p, h, work, iwork)


def _best(run, args, repeats: int = 2000) -> float:
    run(1, *args)
    best = math.inf
    for _ in range(7):
        t0 = time.perf_counter()
        run(repeats, *args)
        best = min(best, (time.perf_counter() - t0) / repeats)
    return best


def main() -> None:
    lub = load_builtin_lubricant("nato-o156")
    cols = contacts()
    n = cols[0].shape[0]
    h1, h2 = np.empty(n), np.empty(n)
    common = (*cols, E_EFF, lub.eta0, lub.alpha_star)
    t1 = _best(_one_by_one, (*common, h1))
    t2 = _best(_batch, (np.array(cols), E_EFF, lub.eta0, lub.alpha_star, h2, np.empty((film.FILM_BATCH_ROWS, 5 * n)),
                        np.empty(5 * n, dtype=np.int64)))
    print(f"NVM central film of {n} contacts (nato-o156 at its scene temperature), minimum of 7 runs")
    print(f"  one contact at a time (libm exp/log): {t1 * 1e6:6.2f} us")
    print(f"  batch (vectorised exp/log):           {t2 * 1e6:6.2f} us   ratio {t2 / t1:.2f}")
    print(f"  largest relative difference: {np.max(np.abs(h2 / h1 - 1.0)):.1e}")


if __name__ == "__main__":
    main()
