"""Hertz point contact (docs/model.md §6.2): elliptic integrals, ellipticity, constants, table, M.34."""

import math

import numpy as np
import pytest
from scipy.special import ellipe, ellipk

from bearingsim.dynamics.geometry import BearingGeometry, Material, effective_modulus
from bearingsim.dynamics.contact.hertz import (DEFAULT_TABLE_NODES, elliptic_km, ellipticity, hertz_exact, hertz_hamrock_brewe,
                            hertz_table_eval, max_pressure, normal_tangent, race_curvature, race_hertz_table)

STEEL = Material(208e9, 0.3, 7850)
E_EFF = effective_modulus(STEEL, STEEL)
# docs/model.md §2 reference bearing (SI)
REF = BearingGeometry(0.01905, 22, 0.1584, 0.1573, 0.009753, 0.009906)


def test_agm_elliptic_integrals_match_scipy():
    rng = np.random.default_rng(1)
    m = np.concatenate([rng.uniform(0.0, 1.0, 200), 1.0 - 10.0 ** rng.uniform(-9, -1, 50), [0.0]])
    for mi in m:
        k, e = elliptic_km(mi)
        assert k == pytest.approx(ellipk(mi), rel=1e-13)
        assert e == pytest.approx(ellipe(mi), rel=1e-13)


def test_ellipticity_solves_its_equation():
    for f in [1e-3, 0.1, 0.5, 0.9, 0.95, 0.99]:  # κ → 1 is cancellation-limited in this check
        kappa = ellipticity(f)
        m = 1.0 - 1.0 / kappa**2
        lhs = ((kappa**2 + 1) * ellipe(m) - 2 * ellipk(m)) / ((kappa**2 - 1) * ellipe(m))
        assert lhs == pytest.approx(f, rel=1e-10, abs=1e-13)


@pytest.mark.parametrize("theta_deg, m_ref, n_ref", [
    # Timoshenko & Goodier, "Theory of Elasticity", 3rd ed. (1970), §140, table of the
    # coefficients m, n of a = m(3πP(k1+k2)/(4(A+B)))^{1/3}, b = n(...), cos θ = (B−A)/(A+B)
    (30, 2.731, 0.493), (40, 2.136, 0.567), (50, 1.754, 0.641), (60, 1.486, 0.717),
    (80, 1.128, 0.893), (90, 1.000, 1.000),
])
def test_semi_axes_match_timoshenko_table(theta_deg, m_ref, n_ref):
    # In Harris' form a = (2κ²E/π)^{1/3} X^{1/3}: m = (2κ²E/π)^{1/3}, n = (2E/(πκ))^{1/3}
    # (same load group once k1+k2 = 2/(πE') and A+B = Σρ/2), and F(ρ) = cos θ.
    kappa = ellipticity(math.cos(math.radians(theta_deg)))
    _, e = elliptic_km(1.0 - 1.0 / kappa**2)
    assert (2 * kappa**2 * e / math.pi) ** (1 / 3) == pytest.approx(m_ref, abs=6e-4)
    assert (2 * e / (math.pi * kappa)) ** (1 / 3) == pytest.approx(n_ref, abs=6e-4)


def test_reference_bearing_inner_constant_at_25_degrees():
    # docs/model.md §6.2 check: exact inner-race constant ≈ 1.5266e6 N/mm^1.5 at α = 25°
    sum_rho, f_rho = race_curvature(math.radians(25.0), REF.ball_diameter, REF.pitch_diameter,
                                    REF.inner_groove_radius, False)
    k_h = hertz_exact(sum_rho, f_rho, E_EFF)[2]
    assert k_h * 1e-3**1.5 == pytest.approx(1.5266e6, rel=2e-4)


def test_sphere_on_sphere_limit_is_classical_hertz():
    # Johnson, "Contact Mechanics" (1985) eqs. 4.22–4.23: a = (3FR/(4E*))^{1/3}, δ = a²/R,
    # with 1/R = 1/R1 + 1/R2 and E* = E'/2 (E' of docs/model.md is 2/Σ((1−ν²)/E)).
    r1, r2, force = 0.01, 0.02, 500.0
    radius = 1.0 / (1 / r1 + 1 / r2)
    sum_rho = 2 / r1 + 2 / r2
    kappa, _, k_h, c_a, c_b = hertz_exact(sum_rho, 0.0, E_EFF)
    a = (3 * force * radius / (4 * 0.5 * E_EFF)) ** (1 / 3)
    assert kappa == 1.0
    assert c_a * force ** (1 / 3) == pytest.approx(a, rel=1e-12)
    assert c_b * force ** (1 / 3) == pytest.approx(a, rel=1e-12)
    assert (force / k_h) ** (2 / 3) == pytest.approx(a * a / radius, rel=1e-12)
    assert max_pressure(force, c_a, c_b) == pytest.approx(3 * force / (2 * math.pi * a * a), rel=1e-12)


def test_hamrock_brewe_is_a_few_percent_from_exact():
    # docs/model.md §6.2: the closed forms are ~3 % off at these conformities; check they are
    # close but measurably different (the test would fail if the two paths were the same).
    for alpha in np.radians([0.0, 25.0, 45.0]):
        for outer in (False, True):
            r = REF.outer_groove_radius if outer else REF.inner_groove_radius
            sr, f = race_curvature(alpha, REF.ball_diameter, REF.pitch_diameter, r, outer)
            exact, approx = hertz_exact(sr, f, E_EFF), hertz_hamrock_brewe(sr, f, E_EFF)
            rel = abs(approx[2] / exact[2] - 1)
            assert 1e-4 < rel < 0.05
            assert approx[0] == pytest.approx(exact[0], rel=0.05)


def test_table_interpolation_error_below_1e_4():
    rng = np.random.default_rng(2)
    alphas = rng.uniform(-0.5 * math.pi, 0.5 * math.pi, 400)
    worst = 0.0
    for outer in (False, True):
        table = race_hertz_table(REF, E_EFF, outer=outer)
        r = REF.outer_groove_radius if outer else REF.inner_groove_radius
        for alpha in alphas:
            sr, f = race_curvature(alpha, REF.ball_diameter, REF.pitch_diameter, r, outer)
            kappa, _, k_h, c_a, c_b = hertz_exact(sr, f, E_EFF)
            got = hertz_table_eval(table, alpha)
            for value, ref in zip((got[0], got[2], got[3], got[4]), (k_h, kappa, c_a, c_b)):
                worst = max(worst, abs(value / ref - 1))
    assert worst <= 1e-4
    assert DEFAULT_TABLE_NODES == 181  # the measured error (~1e-9) is for this spacing


def test_table_slope_matches_finite_difference_and_py_func():
    table = race_hertz_table(REF, E_EFF, outer=False)
    for alpha in (0.1, 0.44, 0.9, -0.44):
        h = 1e-6
        k_plus, k_minus = hertz_table_eval(table, alpha + h)[0], hertz_table_eval(table, alpha - h)[0]
        slope = hertz_table_eval(table, alpha)[1]
        assert slope == pytest.approx((k_plus - k_minus) / (2 * h), rel=1e-5)
        assert hertz_table_eval(table, alpha) == pytest.approx(hertz_table_eval.py_func(table, alpha), rel=1e-14)
    sr, f = race_curvature(0.3, REF.ball_diameter, REF.pitch_diameter, REF.inner_groove_radius, False)
    assert hertz_exact(sr, f, E_EFF) == pytest.approx(hertz_exact.py_func(sr, f, E_EFF), rel=1e-14)


def test_normal_tangent_matches_finite_difference():
    # M.34 against a finite difference of F(w) = k δ^{3/2} w/|w|, δ = |w| − gap (constant k)
    rng = np.random.default_rng(3)
    k_h, gap = 4.8e10, 2.3e-4
    for _ in range(20):
        direction = rng.normal(size=3)
        w = direction / np.linalg.norm(direction) * (gap + rng.uniform(1e-6, 5e-5))

        def force(wv):
            s = np.linalg.norm(wv)
            return k_h * (s - gap) ** 1.5 * wv / s

        s = np.linalg.norm(w)
        out = np.empty((3, 3))
        normal_tangent(k_h, s - gap, w / s, s, out)
        h = 1e-10
        fd = np.column_stack([(force(w + h * e) - force(w - h * e)) / (2 * h) for e in np.eye(3)])
        assert np.allclose(out, fd, rtol=1e-6, atol=1e-6 * np.abs(fd).max())
    normal_tangent(k_h, -1e-6, w / s, s, out)
    assert not out.any()


def test_semi_axis_coefficients_equal_the_table_evaluation_at_each_angle():
    """The array form used by the burn-zone render equals `hertz_table_eval` angle by angle."""
    from bearingsim.dynamics.contact.hertz import hertz_table_eval, race_hertz_table, semi_axis_coefficients
    from bearingsim.dynamics.geometry import effective_modulus
    from bearingsim.pipeline.scene.load import load_scene

    scene = load_scene("helicopter-b-given-hinge")
    table = race_hertz_table(scene.bearing, effective_modulus(scene.materials.ball, scene.materials.race), outer=True)
    alpha = np.linspace(-0.8, 0.8, 33).reshape(3, 11)
    c_a, c_b = semi_axis_coefficients(table, alpha)
    for a, ca, cb in zip(alpha.ravel(), c_a.ravel(), c_b.ravel()):
        _, _, _, ca_ref, cb_ref = hertz_table_eval(table, a)
        assert (ca, cb) == (ca_ref, cb_ref)
