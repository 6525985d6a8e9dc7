"""The film's elasticity at the inlet (docs/model.md §6.4, *Film elasticity*): the bound on a
film's low-slip stiffness that a limiting elastic shear modulus G sets.

A fluid element enters the contact unstressed and crosses it in a time of order 2a/u; in the
Maxwell model of Johnson & Tevaarwerk its stress obeys d tau/dt = G (gamma_dot - F(tau)), F the
viscous law's strain rate at stress tau. Held at the local steady stress tau_v of the viscous law
(`traction.laws`), the element's stress after a time t in the contact is taken as

    tau = tau_v (1 - exp(-y)),    y = G gamma_dot t / |tau_v|,    gamma_dot = |s| / h,

which is the Maxwell model's exact solution for a Newtonian film (tau_v = eta gamma_dot: y = G t
/ eta) and keeps its two limits for any law: elastic, tau = G gamma_dot t, where the film is too
viscous to relax within the transit (large eta, small slip); the viscous law where it relaxes at
once. In the form the traction integrals take (tau = tau_s g s, `laws.eyring`) with t = (x +
a sqrt(1 - (y/b)^2)) / u from the inlet edge at the node's y:

    y = inlet (X + sqrt(1 - Y^2)) / g,     inlet = G a / (u tau_s h)   [s/m]

and g, c become g (1 - e^-y) and c (1 - (1 + y) e^-y) (d tau/d s = tau_s (g I + c s s^T), the
y of g's own slip dependence included). u: the mean surface speed along the entrainment. With
u = 0 (the fluid does not cross) or G = inf the film is the viscous law's: `inlet_scale` is inf.
"""

from __future__ import annotations

import math

import numba

from .._speed.compile_policy import VEC

# below this y the factors are their series, where 1 - (1 + y) e^-y would cancel to a few digits:
# 1 - e^-y = y (1 - y/2 + y^2/6 - y^3/24), 1 - (1 + y) e^-y = y^2 (1/2 - y/3 + y^2/8 - y^3/30)
# (next terms y^5/120 and y^6/144: < 1e-12 relative here)
SERIES_Y = 1e-3
# the smallest g the exponent divides by (g > 0 for every film law; a guard against 0 only)
G_FLOOR = 1e-300


@numba.njit(cache=True)
def inlet_scale(shear_modulus, a, u, stress, h):
    """G a / (u tau_s h) [s/m] (module docstring): shear_modulus G [Pa], a [m] the semi-axis
    along the entrainment, u [m/s] the mean surface speed, stress tau_s [Pa] the law's stress
    scale, h [m] the film. inf (the viscous law) for u <= 0 or G = inf."""
    if not (u > 0.0) or not (shear_modulus < math.inf):
        return math.inf
    return shear_modulus * a / (u * stress * h)


@numba.njit(cache=True, inline="always")
def travel(X, Y):
    """A node's distance from the inlet edge in semi-axes a: X + sqrt(1 - Y^2) (X = x/a along
    the entrainment, Y = y/b; the fluid enters at X = -sqrt(1 - Y^2))."""
    return X + math.sqrt(max(1.0 - Y * Y, 0.0))


@numba.njit(cache=True, inline="always")
def factors(y, e):
    """(1 - e^-y, 1 - (1 + y) e^-y), the factors of g and c, from y >= 0 and e = exp(-y); their
    series below SERIES_Y."""
    small = y < SERIES_Y
    series_g = y * (1.0 - y * (0.5 - y * (1.0 / 6.0 - y / 24.0)))
    series_c = y * y * (0.5 - y * (1.0 / 3.0 - y * (0.125 - y / 30.0)))
    return (series_g if small else 1.0 - e), (series_c if small else 1.0 - (1.0 + y) * e)


@numba.njit(**VEC)
def exponents(X, Y, g, n, scale, minus_y):
    """minus_y[m] = -y = -scale travel(X, Y) / g per node (the argument of exp; g of any width)."""
    for m in range(n):
        minus_y[m] = -scale * travel(X[m], Y[m]) / max(float(g[m]), G_FLOOR)


@numba.njit(**VEC)
def apply(minus_y, e, n, jacobian, g, c):
    """g[m] *= 1 - e^-y and, when jacobian, c[m] *= 1 - (1 + y) e^-y, from minus_y = -y and e =
    exp(-y) per node (`factors`); g may be float32 (the residual-only passes)."""
    if jacobian:
        for m in range(n):
            fg, fc = factors(-minus_y[m], e[m])
            g[m] = g[m] * fg
            c[m] = c[m] * fc
        return
    for m in range(n):
        g[m] = g[m] * factors(-minus_y[m], e[m])[0]
