"""The film's inlet elasticity (docs/model.md §6.4, *Film elasticity*; dynamics/traction/inlet.py).

Closed forms for a Newtonian film of constant viscosity eta in pure sliding s (no spin): a fluid
element that entered the contact a time t ago carries the Maxwell stress eta (s/h) (1 - exp(-G
t/eta)) (Johnson & Tevaarwerk, Proc. R. Soc. A 356 (1977) 215-236, their linear regime). On a
strip of the ellipse at y, of length L = 2a sqrt(1 - (y/b)^2) crossed at speed u,

    integral_0^L (1 - exp(-xi/l)) d xi = L - l (1 - exp(-L/l)),    l = u eta / G,

and the elastic limit (l >> a) integrates to F = G (s/h) (8 a^2 b/3) / u over the ellipse. The
strip integral is summed over y here by scipy's quad, independently of the code under test.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import integrate

from bearingsim.dynamics.lubrication.lubricant import Lubricant, load_builtin_lubricant
from bearingsim.dynamics.traction import quadrature
from bearingsim.dynamics.traction.fast import FastTraction, traction_fast
from tests.lubrication_points import random_operating_points
from bearingsim.dynamics.lubrication.film_laws import nvm as film

NEWTONIAN_TAU0 = 1e15  # Pa: the Eyring law is linear to 1e-9 at the stresses below
A, B, P_H, H = 2.0e-4, 1.5e-3, 1.2e9, 2.0e-7  # m, m, Pa, m: a ball-race contact of the reference size
G = 1.0e9  # Pa
# the user's Barus oil of docs/model.md §6.4 (tests/test_barus_runs.py): 1e7-1e12 Pa.s over a contact
USER_BARUS = Lubricant(name="user-barus", viscosity_model="barus", temperature_degC=70.0, eyring_stress=5e6,
                       ambient_viscosity=0.020, pressure_viscosity_coefficient=2e-8)


def _constant(eta: float, shear_modulus: float = G) -> Lubricant:
    return Lubricant(name="constant", viscosity_model="barus", temperature_degC=40.0, eyring_stress=NEWTONIAN_TAU0,
                     ambient_viscosity=eta, pressure_viscosity_coefficient=0.0, elastic_shear_modulus=shear_modulus)


def _maxwell_closed_form(eta: float, s: float, u: float) -> float:
    """-F_x of the Newtonian Maxwell film in pure sliding (module docstring)."""
    ell = u * eta / G

    def strip(y):
        L = 2.0 * A * math.sqrt(max(1.0 - (y / B) ** 2, 0.0))
        return L - ell * (-math.expm1(-L / ell))
    return eta * s / H * integrate.quad(strip, -B, B, epsabs=0.0, epsrel=1e-12, limit=200)[0]


@pytest.mark.parametrize("deborah", [0.01, 1.0, 100.0])
def test_the_newtonian_maxwell_film_against_its_closed_form(deborah):
    """Deborah number eta u / (G 2a) from viscous (0.01) through the transition to elastic (100):
    the reference quadrature within 0.1 %, the fast engine within its 2 % (docs/model.md §6.4)."""
    u, s = 10.0, 1e-3
    eta = deborah * G * 2.0 * A / u
    lub = _constant(eta)
    expected = _maxwell_closed_form(eta, s, u)
    ref = quadrature.traction_quadrature(A, B, P_H, H, lub.eyring_stress, lub.model_code, lub.rheology_params(),
                                         s, 0.0, 0.0, (96, 512), (G, u))
    fast, _, _ = FastTraction.build(lub).evaluate(A, B, P_H, H, s, 0.0, 0.0, u)
    assert -ref[0] == pytest.approx(expected, rel=1e-3)
    assert -fast[0] == pytest.approx(expected, rel=0.02)
    viscous = eta * s / H * math.pi * A * B
    assert expected < viscous  # the film never carries more than its viscous stress


def test_the_elastic_limit_bounds_the_low_slip_stiffness_whatever_the_viscosity():
    """A film near the glass (5e11 Pa.s): without elasticity its low-slip stiffness is eta pi a b /
    h; with it, G (8 a^2 b / 3) / (u h), the elastic limit, within 1 %."""
    u, s = 10.0, 1e-9
    lub = _constant(5e11)
    fast = FastTraction.build(lub)
    _, J_elastic, _ = fast.evaluate(A, B, P_H, H, s, 0.0, 0.0, u)
    _, J_viscous, _ = fast.evaluate(A, B, P_H, H, s, 0.0, 0.0, 0.0)
    assert -J_elastic[0, 0] == pytest.approx(G * 8.0 * A * A * B / 3.0 / (u * H), rel=0.01)
    assert -J_viscous[0, 0] == pytest.approx(5e11 * math.pi * A * B / H, rel=0.01)


def test_no_elasticity_without_transit_or_modulus():
    """u = 0 (no fluid crosses) and G = inf give the viscous law's numbers exactly; where the film
    relaxes within its transit (nato-o156 at 100 degC, 1.2 GPa: eta u / (G 2a) ~ 1e-4) the
    elasticity moves the force by under 1e-6; in the user's Barus oil it halves it or more."""
    o156 = load_builtin_lubricant("nato-o156")
    point = (A, B, P_H, H, 0.02, 0.003, 40.0)
    viscous = FastTraction.build(o156).evaluate(*point, 0.0)
    rigid = FastTraction.build(Lubricant(**{**o156.__dict__, "elastic_shear_modulus": math.inf})).evaluate(*point, 12.0)
    for left, right in zip(viscous[:2], rigid[:2]):
        assert np.array_equal(left, right)
    elastic = FastTraction.build(o156).evaluate(*point, 12.0)[0]
    assert np.allclose(elastic, viscous[0], rtol=1e-6, atol=0.0)
    barus = FastTraction.build(USER_BARUS)
    slow = (A, B, 1.6e9, H, 1e-4, 0.0, 0.0)
    assert abs(barus.evaluate(*slow, 12.0)[0][0]) < 0.5 * abs(barus.evaluate(*slow, 0.0)[0][0])


def test_fast_engine_against_the_reference_with_elasticity():
    """Random operating points of the reference scene (tests/lubrication_points.py), at the mean
    speeds of its contacts (5-30 m/s), the user's Barus oil with G = 1 GPa (where the elasticity
    bites): force, moment and Jacobian of the fast engine within the engine's 2 % of the (128,
    1024) reference quadrature, and the Jacobian within 1e-4 of central differences of the
    engine's own force."""
    o156 = USER_BARUS
    fast = FastTraction.build(o156)
    rng = np.random.default_rng(5)
    points = random_operating_points(24, seed=41, lubricant=o156, film=film.film_central_nvm)
    worst = np.zeros(3)
    for point in points:
        u = rng.uniform(5.0, 30.0)
        F, J, _ = fast.evaluate(*point, u)
        Fx, Fy, Mz, Jr = quadrature.traction_quadrature(*point[:4], o156.eyring_stress, o156.model_code,
                                                        o156.rheology_params(), *point[4:], (128, 1024),
                                                        (o156.elastic_shear_modulus, u))
        scale = math.hypot(Fx, Fy)
        worst = np.maximum(worst, (math.hypot(F[0] - Fx, F[1] - Fy) / scale,
                                   abs(F[2] - Mz) / max(abs(Mz), scale * point[1]),
                                   np.abs(J - Jr).max() / np.abs(Jr).max()))
    print(f"fast against reference with elasticity: F {worst[0]:.2%}, M {worst[1]:.2%}, J {worst[2]:.2%}")
    assert worst[0] < 0.02 and worst[1] < 0.02 and worst[2] < 0.03
    # the Jacobian against central differences at one point
    a, b, p_h, h, du0, dv0, w_s = points[0]
    _, J, _ = fast.evaluate(*points[0], 12.0)
    steps = (1e-6 * max(abs(du0), 1e-3), 1e-6 * max(abs(dv0), 1e-3), 1e-6 * max(abs(w_s), 1.0))
    for col, step in enumerate(steps):
        plus, minus = list(points[0][4:]), list(points[0][4:])
        plus[col] += step
        minus[col] -= step
        column = (fast.evaluate(a, b, p_h, h, *plus, 12.0)[0] - fast.evaluate(a, b, p_h, h, *minus, 12.0)[0]) / (2 * step)
        assert np.allclose(J[:, col], column, rtol=1e-4, atol=1e-5 * np.abs(J).max())


def test_the_float32_residual_carries_the_elasticity():
    """The time loop's float32 residual-only call (docs/model.md §6.4) applies the same factor:
    within 1e-6 of the float64 call's force (or of tau0 pi a b, where that is larger), on the reference scene's operating range, in
    the user's Barus oil (where the factor moves the force)."""
    o156 = USER_BARUS
    fast = FastTraction.build(o156)
    rule64, rule32 = fast.traction_rule(), fast.traction_rule(float32_residual=True)
    f64, f32, viscous = np.empty(12), np.empty(12), np.empty(12)
    worst, moved = 0.0, 0.0
    for a, b, p_h, h, du0, dv0, w_s in random_operating_points(100, seed=43, lubricant=o156, film=film.film_central_nvm):
        traction_fast(a, b, p_h, h, du0, dv0, w_s, 15.0, rule64, f64, False)
        traction_fast(a, b, p_h, h, du0, dv0, w_s, 15.0, rule32, f32, False)
        traction_fast(a, b, p_h, h, du0, dv0, w_s, 0.0, rule64, viscous, False)
        unit = o156.eyring_stress * math.pi * a * b
        worst = max(worst, math.hypot(f32[0] - f64[0], f32[1] - f64[1]) / max(unit, math.hypot(f64[0], f64[1])))
        moved = max(moved, math.hypot(viscous[0] - f64[0], viscous[1] - f64[1]) / unit)
    assert worst < 1e-6 < moved
