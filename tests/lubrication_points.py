"""Operating points of the reference bearing's ball-race contacts (docs/model.md §2), for tests.

Semi-axes from the Hamrock-Brewe closed forms (Hamrock, Fundamentals of Fluid Film
Lubrication, NASA RP-1255, 1991, eqs. 3.40-3.42: k = 1.0339 (Ry/Rx)^0.636,
E(m) ~ 1.0003 + 0.5968 Rx/Ry) -- used only to pick realistic (a, b, p_h), never as a
reference value. Conformities 0.512 / 0.520, D = 19.05 mm, d_m = 158.003 mm, steel
E = 208 GPa, nu = 0.3, inner race 320 rad/s (3060 rpm), outer fixed, pure-rolling
entrainment speed u = (d_m omega_i / 4)(1 - gamma^2), gamma = D cos(alpha)/d_m.
"""

from __future__ import annotations

import math

import numpy as np

BALL_D = 0.01905
PITCH_D = 0.158003
E_EFF = 208e9 / (1.0 - 0.3**2)
OMEGA_INNER = 320.0


def curvature_radii(race: str, contact_angle_deg: float) -> tuple[float, float]:
    """(R_x, R_y) [m]: x = rolling direction, y = across the groove."""
    c = math.cos(math.radians(contact_angle_deg))
    D, dm = BALL_D, PITCH_D
    if race == "inner":
        return 1.0 / (2.0 / D + 2.0 * c / (dm - D * c)), 1.0 / (2.0 / D - 1.0 / (0.512 * D))
    return 1.0 / (2.0 / D - 2.0 * c / (dm + D * c)), 1.0 / (2.0 / D - 1.0 / (0.520 * D))


def hertz_ellipse(F: float, Rx: float, Ry: float) -> tuple[float, float, float]:
    """(a along x, b along y, p_h) [m, m, Pa] by Hamrock-Brewe; here b > a (Ry > Rx)."""
    k = 1.0339 * (Ry / Rx) ** 0.636
    ell = 1.0003 + 0.5968 * Rx / Ry
    R = 1.0 / (1.0 / Rx + 1.0 / Ry)
    major = (6.0 * k * k * ell * F * R / (math.pi * E_EFF)) ** (1.0 / 3.0)
    minor = (6.0 * ell * F * R / (math.pi * k * E_EFF)) ** (1.0 / 3.0)
    return minor, major, 3.0 * F / (2.0 * math.pi * minor * major)


def rolling_speed(contact_angle_deg: float, speed_factor: float = 1.0) -> float:
    """Mean entrainment speed u [m/s] (u_s = 2u) at speed_factor x nominal."""
    g = BALL_D * math.cos(math.radians(contact_angle_deg)) / PITCH_D
    return PITCH_D * OMEGA_INNER / 4.0 * (1.0 - g * g) * speed_factor


def random_operating_points(n: int, seed: int, lubricant, film) -> list[tuple]:
    """n points (a, b, p_h, h, du0, dv0, w_s) over the reference-scene range.

    Loads 100..6000 N, speed 0.1..2 x nominal, slide-to-roll 1e-5..0.3 (log-uniform, random
    direction), spin-to-roll w_s b/u = +-(0.01..0.1), contact angle 25..35 deg, either race;
    h = central film by `film(F, Rx, Ry, E', eta0, alpha*, u_s)`.
    """
    rng = np.random.default_rng(seed)
    eta0, alpha = lubricant.eta0, lubricant.alpha_star
    logu = lambda lo, hi: math.exp(rng.uniform(math.log(lo), math.log(hi)))  # noqa: E731
    points = []
    for _ in range(n):
        race = "inner" if rng.uniform() < 0.5 else "outer"
        angle = rng.uniform(25.0, 35.0)
        F = logu(100.0, 6000.0)
        Rx, Ry = curvature_radii(race, angle)
        a, b, p_h = hertz_ellipse(F, Rx, Ry)
        u = rolling_speed(angle, logu(0.1, 2.0))
        h = film(F, Rx, Ry, E_EFF, eta0, alpha, 2.0 * u)
        slip = logu(1e-5, 0.3) * u
        phi = rng.uniform(0.0, 2.0 * math.pi)
        w_s = math.copysign(logu(0.01, 0.1), rng.uniform(-1, 1)) * u / b
        points.append((a, b, p_h, h, slip * math.cos(phi), slip * math.sin(phi), w_s))
    return points
