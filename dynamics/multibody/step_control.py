"""Local-error norm and step-size proposal (docs/model.md §9, M.99–M.101).

Error estimate of HHT-α/Newmark: e = (beta - 1/6) h^2 (a_{n+1} - a_n) — the difference between
the Newmark displacement and the cubic Taylor term (Zienkiewicz & Xie, Earthq. Eng. Struct.
Dyn. 20 (1991) 871–887). Each coordinate's error is divided by its own scale

    s_i = atol + rtol L_i,     L_i = the coordinate's physical scale (problem.error_scales),
                               or, for a problem without one, w_i max(|q_n,i|, |q_n+1,i|)

and the norm is the largest of these ratios ("max", each coordinate on its own scale, so one
impacting ball shortens the step however many others move smoothly) or their RMS over the
weighted coordinates ("rms", Hairer, Nørsett & Wanner, "Solving ODE I", eq. II.4.11).
w_i >= 0 converts coordinate i into the unit of atol (1 for a position in m; a length in
m/rad for a rotation, so that an angle error reads as an arc length); w_i = 0 excludes the
coordinate (dummy rotations of balls, prescribed rows). Accept when ||e|| <= 1.
"""

from __future__ import annotations

import math

import numba

from .._speed.compile_policy import KERNEL

from .settings import HHTSettings

# Shared by both time loops (time_loop.py, compiled.py), so that they take the same steps:
LAST_STEP_STRETCH = 1.05  # a step that would end within 5 % of t1 is stretched to land on it
AT_MIN_STEP = 1.0 + 1e-9  # h <= min_step * AT_MIN_STEP counts as the minimum step (its rounding)
MACHINE_EPSILON = 2.2e-16  # float64 rounding, relative
NEWTON_FLOOR = 100.0  # Newton's corrections below NEWTON_FLOOR x the round-off of q have converged


@numba.njit(**KERNEL)
def scaled_difference_norm(x, y, coef, q_a, q_b, weights, scales, atol, rtol, use_max):
    """Norm of coef (x - y) on the scales of the module docstring (dimensionless).

    `scales` (n,): the physical scales L_i, or an empty array to scale by |q| instead.
    Returns inf if any weighted entry is not finite.
    """
    physical = scales.shape[0] == x.shape[0]
    s = 0.0
    count = 0
    for i in range(x.shape[0]):
        w = weights[i]
        if w == 0.0:
            continue
        ref = scales[i] if physical else w * max(abs(q_a[i]), abs(q_b[i]))
        d = w * coef * (x[i] - y[i]) / (atol + rtol * ref)
        if not math.isfinite(d):
            return math.inf
        if use_max:
            s = max(s, abs(d))
        else:
            s += d * d
        count += 1
    if count == 0:
        return 0.0
    return s if use_max else math.sqrt(s / count)


@numba.njit(**KERNEL)
def proposed_step(h, err, safety, min_factor, max_factor, min_step, max_step):
    """h clip(safety ||e||^(-1/3), min_factor, max_factor) (local error O(h^3)), bounded to
    [min_step, max_step] [s]."""
    if err <= 0.0:
        f = max_factor
    else:
        f = min(max_factor, max(min_factor, safety * err ** (-1.0 / 3.0)))
    return min(max_step, max(min_step, h * f))


def next_step(h: float, err: float, settings: HHTSettings) -> float:
    """Proposed next step, bounded to [min_step, max_step] [s] (`proposed_step`)."""
    s = settings
    return proposed_step(h, err, s.safety, s.min_factor, s.max_factor, s.min_step, s.max_step)
