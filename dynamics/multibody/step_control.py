"""Local-error norm and step-size proposal (docs/model.md §9).

Error estimate of HHT-α/Newmark: e = (beta - 1/6) h^2 (a_{n+1} - a_n) — the difference between
the Newmark displacement and the cubic Taylor term (Zienkiewicz & Xie, Earthq. Eng. Struct.
Dyn. 20 (1991) 871–887). Its weighted RMS norm (Hairer, Nørsett & Wanner, "Solving ODE I",
eq. II.4.11) with per-coordinate weights w_i >= 0:

    ||e|| = sqrt( mean_{i: w_i > 0} ( w_i e_i / (atol + rtol w_i max(|q_n,i|, |q_n+1,i|)) )^2 )

w_i converts coordinate i into the unit of atol (1 for a position in m; a length in m/rad for
a rotation, e.g. the body radius, so that an angle error reads as an arc length); w_i = 0
excludes the coordinate (dummy rotations of balls, prescribed rows). Accept when ||e|| <= 1.
"""

from __future__ import annotations

import math

import numba

from .settings import HHTSettings


@numba.njit(cache=True)
def scaled_difference_norm(x, y, coef, q_a, q_b, weights, atol, rtol):
    """Weighted RMS of coef (x - y) with the scale of the module docstring (dimensionless).

    Returns inf if any weighted entry is not finite.
    """
    s = 0.0
    count = 0
    for i in range(x.shape[0]):
        w = weights[i]
        if w == 0.0:
            continue
        sc = atol + rtol * w * max(abs(q_a[i]), abs(q_b[i]))
        d = w * coef * (x[i] - y[i]) / sc
        s += d * d
        count += 1
    if count == 0:
        return 0.0
    val = math.sqrt(s / count)
    return val if math.isfinite(val) else math.inf


def step_factor(err: float, settings: HHTSettings) -> float:
    """h_new / h = clip(safety ||e||^(-1/3), min_factor, max_factor) (local error O(h^3))."""
    if err <= 0.0:
        return settings.max_factor
    f = settings.safety * err ** (-1.0 / 3.0)
    return min(settings.max_factor, max(settings.min_factor, f))


def next_step(h: float, err: float, settings: HHTSettings) -> float:
    """Proposed next step, bounded to [min_step, max_step] [s]."""
    return min(settings.max_step, max(settings.min_step, h * step_factor(err, settings)))
