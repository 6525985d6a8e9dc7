"""The dynamic short-bearing film of the cage land (docs/model.md §8, M.94b–M.94e), against
the static Ocvirk closed form, Flores et al.'s whirl term, its quadrature twin, symmetry,
dissipation and finite-difference tangents."""

from __future__ import annotations

import math

import numpy as np
import pytest

from bearingsim.dynamics.journal.short_bearing import (
    JournalGeometry, cage_race_journal, journal_parameters, ocvirk_force, unpack_journal,
)
from bearingsim.dynamics.journal.squeeze_film import (
    N_SQUEEZE_OUT, film_moments, squeeze_film_force, squeeze_film_reference,
)

C = 1e-4
# R, L, C of the journal tests below: about the reference cage's guiding land (docs/model.md §2)
LANDS = JournalGeometry(radius=0.083, length=0.0076, clearance=2.9e-4)


def _force(ex, ey, vx, vy, omega, k=1.0, c=C):
    out = np.empty(N_SQUEEZE_OUT)
    squeeze_film_force(ex, ey, vx, vy, omega, c, k, 0.999, out)
    return out


@pytest.mark.parametrize("eps", [0.05, 0.3, 0.5, 0.8, 0.95])
def test_a_centre_at_rest_gives_ocvirk_static_force(eps):
    """v = 0: the film is Ocvirk's static short bearing (paper eq. 25), in any direction."""
    mu, omega, R, L = 0.01, 100.0, 0.05, 0.01
    k = mu * R * L**3 / C**3
    phi = 0.7
    out = _force(eps * C * math.cos(phi), eps * C * math.sin(phi), 0.0, 0.0, omega, k)
    f_n, f_t, _, _ = ocvirk_force(eps, mu, omega, R, L, C)
    er = np.array([math.cos(phi), math.sin(phi)])
    et = np.array([-er[1], er[0]])
    assert out[:2] @ er == pytest.approx(-f_n, rel=1e-12)
    assert out[:2] @ et == pytest.approx(f_t, rel=1e-12)


def test_the_hand_computed_short_bearing_example():
    """mu = 0.01 Pa s, omega = 100 rad/s, R = 0.05 m, L = 0.01 m, C = 1e-4 m, eps = 0.5:
    mu omega R L^3 / C^2 = 5 N, so F_n = 5 * 0.25 / 0.5625 = 2.2222 N and
    F_t = 5 (pi/4) 0.5 / 0.75^1.5 = 3.0230 N, attitude atan(F_t / F_n) = 53.68 degrees
    (Ocvirk's formulas evaluated by hand)."""
    k = 0.01 * 0.05 * 0.01**3 / C**3
    out = _force(0.5 * C, 0.0, 0.0, 0.0, 100.0, k)
    assert -out[0] == pytest.approx(2.2222, abs=1e-4)
    assert out[1] == pytest.approx(3.0230, abs=1e-4)
    assert math.degrees(math.atan2(out[1], -out[0])) == pytest.approx(53.68, abs=0.01)


@pytest.mark.parametrize("whirl", [-80.0, 0.0, 20.0, 45.0])
def test_a_whirling_centre_replaces_omega_by_omega_minus_twice_the_whirl(whirl):
    """Circular whirl at phi_dot with omega - 2 phi_dot > 0 keeps the static half film, so
    the force is Ocvirk's with omega -> omega - 2 phi_dot (Flores et al., Mech. Mach.
    Theory 41 (2006) 247-261, their whirl term)."""
    eps, omega = 0.6, 100.0
    e = np.array([eps * C, 0.0])
    v = whirl * np.array([-e[1], e[0]])
    out = _force(e[0], e[1], v[0], v[1], omega)
    f_n, f_t, _, _ = ocvirk_force(eps, 1.0, omega - 2.0 * whirl, 1.0, 1.0, C)
    # K = 1 means mu R L^3 = C^3: ocvirk_force with mu R L^3 = 1, scaled by C^3
    assert out[0] == pytest.approx(-f_n * C**3, rel=1e-12)
    assert out[1] == pytest.approx(f_t * C**3, rel=1e-12)


def test_pure_squeeze_is_symmetric_and_matches_the_centred_half_film():
    """omega = 0, centre moving outwards along e: the half film is centred on the thinnest
    point, so there is no side force, and the radial force is
    -K C eps_dot int_{-pi/2}^{pi/2} cos^2 / (1 - eps cos)^3 (M.94c, evaluated by quadrature)."""
    from scipy.integrate import quad

    eps, rate = 0.7, 0.05  # eps_dot C = rate [m/s]
    out = _force(eps * C, 0.0, rate, 0.0, 0.0)
    integral = quad(lambda t: math.cos(t) ** 2 / (1.0 - eps * math.cos(t)) ** 3, -0.5 * math.pi, 0.5 * math.pi)[0]
    assert out[1] == pytest.approx(0.0, abs=1e-12 * abs(out[0]))
    assert out[0] == pytest.approx(-rate * integral, rel=1e-10)


def test_closed_form_moments_equal_quadrature_on_any_interval():
    from scipy.integrate import quad

    rng = np.random.default_rng(3)
    for _ in range(20):
        eps = rng.uniform(0.0, 0.97)
        t1 = rng.uniform(-1.5 * math.pi, 0.5 * math.pi)
        t2 = t1 + math.pi
        got = film_moments(eps, t1, t2)
        monomials = [lambda t, p=p: np.cos(t) ** p[0] * np.sin(t) ** p[1] for p in
                     ((2, 0), (1, 1), (0, 2), (3, 0), (2, 1), (1, 2), (0, 3))]
        powers = (3, 3, 3, 4, 4, 4, 4)
        for g, f, n in zip(got, monomials, powers):
            ref = quad(lambda t: f(t) / (1.0 - eps * math.cos(t)) ** n, t1, t2, epsabs=1e-12, limit=200)[0]
            assert g == pytest.approx(ref, rel=1e-9, abs=1e-9)


def test_force_equals_its_quadrature_twin_at_random_states():
    rng = np.random.default_rng(7)
    for _ in range(25):
        eps, phi = rng.uniform(0.0, 0.9), rng.uniform(0, 2 * math.pi)
        ex, ey = eps * C * math.cos(phi), eps * C * math.sin(phi)
        vx, vy = rng.normal(0.0, 0.02, 2)
        omega = rng.uniform(-200.0, 200.0)
        ref = squeeze_film_reference(ex, ey, vx, vy, omega, C, 1.0, nodes=200000)
        assert _force(ex, ey, vx, vy, omega)[:2] == pytest.approx(ref, rel=2e-4, abs=1e-9 * np.abs(ref).max())


def test_the_film_only_dissipates_in_the_frame_turning_at_half_speed():
    """F = -K A V with A = int n n^T / h^3 >= 0, so F . V <= 0 for every state: relative to
    the frame turning at omega/2 the film is a pure damper (it can feed a whirl only through
    the omega/2 e_z x e part of V)."""
    rng = np.random.default_rng(11)
    for _ in range(200):
        eps, phi = rng.uniform(0.0, 0.95), rng.uniform(0, 2 * math.pi)
        ex, ey = eps * C * math.cos(phi), eps * C * math.sin(phi)
        vx, vy = rng.normal(0.0, 0.05, 2)
        omega = rng.uniform(-300.0, 300.0)
        f = _force(ex, ey, vx, vy, omega)[:2]
        V = np.array([vx + 0.5 * omega * ey, vy - 0.5 * omega * ex])
        assert f @ V <= 1e-15 * np.abs(f).sum() * np.abs(V).sum()


def test_half_speed_whirl_carries_no_load():
    """V = 0 (the centre whirls at omega/2, oil whirl): no pressure, no force."""
    e = np.array([0.5 * C, 0.2 * C])
    omega = 150.0
    v = 0.5 * omega * np.array([-e[1], e[0]])
    assert np.all(_force(e[0], e[1], v[0], v[1], omega)[:2] == 0.0)


@pytest.mark.parametrize("mode", ["hybrid", "hydrodynamic"])
def test_journal_tangents_with_the_dynamic_film_equal_finite_differences(mode):
    p = journal_parameters(LANDS, viscosity=0.005, effective_modulus=1.2e11, friction_coefficient=0.1,
                           film="dynamic", mode=mode)
    states = [((0.6e-4, 1.7e-4), (0.02, -0.05)), ((2.3e-4, 0.4e-4), (0.0, 0.0)),
              ((0.5e-5, 0.0), (0.01, 0.01))]
    if mode == "hybrid":
        states += [((2.96e-4, 0.0), (0.01, 0.03)), ((3.0e-4, 0.2e-5), (-0.02, 0.01))]
    for off, vel in states:
        off, vel = np.array(off), np.array(vel)
        wc, wr = 143.7, -3.0
        u = unpack_journal(cage_race_journal(off, vel, wc, wr, p))
        jp, jv = np.zeros((2, 2)), np.zeros((2, 2))
        for k in range(2):
            d = np.zeros(2)
            d[k] = 1e-11
            jp[:, k] = (cage_race_journal(off + d, vel, wc, wr, p)[:2] - cage_race_journal(off - d, vel, wc, wr, p)[:2]) / 2e-11
            d[k] = 1e-7
            jv[:, k] = (cage_race_journal(off, vel + d, wc, wr, p)[:2] - cage_race_journal(off, vel - d, wc, wr, p)[:2]) / 2e-7
        jw = (cage_race_journal(off, vel, wc + 1e-4, wr, p)[:2] - cage_race_journal(off, vel, wc - 1e-4, wr, p)[:2]) / 2e-4
        jr = (cage_race_journal(off, vel, wc, wr + 1e-4, p)[:2] - cage_race_journal(off, vel, wc, wr - 1e-4, p)[:2]) / 2e-4
        scale = np.abs(jp).max()
        assert np.abs(u["dforce_dposition"] - jp).max() <= 1e-5 * scale
        assert np.abs(u["dforce_dvelocity"] - jv).max() <= 1e-5 * max(np.abs(jv).max(), 1e-12)
        assert u["dforce_domega_cage"] == pytest.approx(jw, rel=1e-5, abs=1e-9)
        assert u["dforce_domega_race"] == pytest.approx(jr, rel=1e-5, abs=1e-9)


def test_static_and_dynamic_films_agree_for_a_centre_at_rest():
    kw = dict(viscosity=0.005, effective_modulus=1.2e11, friction_coefficient=0.1)
    ps, pd = journal_parameters(LANDS, **kw, film="static"), journal_parameters(LANDS, **kw, film="dynamic")
    for eps in (0.2, 0.8, 1.01, 1.04):
        off = np.array([eps * 2.9e-4 * 0.6, eps * 2.9e-4 * 0.8])
        a = cage_race_journal(off, np.zeros(2), 143.7, 0.0, ps)
        b = cage_race_journal(off, np.zeros(2), 143.7, 0.0, pd)
        assert b[:4] == pytest.approx(a[:4], rel=1e-10, abs=1e-12)


def test_unknown_film_is_a_clear_error():
    with pytest.raises(ValueError, match="film = 'wet'"):
        journal_parameters(LANDS, viscosity=0.005, effective_modulus=1.2e11, friction_coefficient=0.1, film="wet")
