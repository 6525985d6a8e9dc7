"""The cage crush screen (docs/model.md §10.1, M.115–M.118): closed forms for a first-harmonic
speed variation, the regime limits, and the reference bearing's regimes against moment."""

from __future__ import annotations

import math

import numpy as np
import pytest

from bearingsim.dynamics.quasistatic.crush_screen import (
    CageClearances,
    LandFilm,
    crush_screen as _screen,
    excursion_of,
    orbital_excursion,
    required_offset,
)

Z = 22
PSI = 2 * math.pi * np.arange(Z) / Z
RP = 0.079
CLEAR = CageClearances(pocket=1.18e-3, guide=0.29e-3)
KW = dict(pitch_radius=RP, pocket_clearance=CLEAR.pocket, guide_clearance=CLEAR.guide)
FILM = LandFilm(radius=0.083, length=0.0076, lands=2, eps0=0.05, viscosity=0.005)


def crush_screen(azimuth, speeds, cage_speed, clearances=CLEAR, **_):
    return _screen(excursion_of(azimuth, speeds, RP), cage_speed, clearances, FILM)


def _speeds(amplitude, phase=0.0):
    return 143.7 * (1.0 + amplitude * np.cos(PSI - phase))


def test_uniform_speed_means_no_excursion():
    s, _, grid_s = orbital_excursion(PSI, np.full(Z, 143.7), 0.079)
    assert np.abs(s).max() < 1e-15 and np.abs(grid_s).max() < 1e-15
    assert crush_screen(PSI, np.full(Z, 143.7), 143.7, **KW).regime == "free"


@pytest.mark.parametrize("phase", [0.0, 1.0, 4.0])
def test_first_harmonic_speed_gives_the_integrated_excursion(phase):
    """omega_m / omega_c - 1 = A cos(psi - phase) integrates to s = r_p A sin(psi - phase): the
    ball leads most at phase + 90 deg, lags most at phase + 270 deg, and the front-wall /
    rear-wall pair pushes the cage along e_t(phase + 90 deg), i.e. towards phase + 180 deg."""
    A, rp = 0.008, 0.079
    s, grid, sg = orbital_excursion(PSI, _speeds(A, phase), rp)
    assert s == pytest.approx(rp * A * np.sin(PSI - phase), abs=1e-12)
    r = crush_screen(PSI, _speeds(A, phase), 143.7, **KW)
    assert r.excursion_peak_to_peak == pytest.approx(2 * rp * A, rel=1e-4)
    assert r.first_harmonic == pytest.approx(rp * A, rel=1e-9)
    wrap = lambda x: (x + math.pi) % (2 * math.pi) - math.pi  # noqa: E731
    assert abs(wrap(r.front_wall_azimuth - (phase + 0.5 * math.pi))) < 0.01
    assert abs(wrap(r.rear_wall_azimuth - (phase + 1.5 * math.pi))) < 0.01
    assert abs(wrap(r.push_azimuth - (phase + math.pi))) < 1e-9


def test_the_residual_is_what_no_cage_offset_takes_up():
    """A first-harmonic speed variation leaves no residual; omega_m / omega_c - 1 =
    A cos 2(psi - phase) integrates to s = r_p A / 2 sin 2(psi - phase): no first harmonic, so
    all of it, r_p A peak to peak, is residual."""
    A, rp = 0.008, 0.079
    first = excursion_of(PSI, _speeds(A, 1.0), rp)
    assert first.residual_peak_to_peak < 1e-6 * rp * A
    second = excursion_of(PSI, 143.7 * (1.0 + A * np.cos(2.0 * (PSI - 1.0))), rp)
    assert second.first_harmonic < 1e-12
    assert second.residual_peak_to_peak == pytest.approx(rp * A, rel=1e-4)


def test_a_residual_beyond_the_pocket_clearance_is_warned():
    from bearingsim.pipeline.staging.result_checks import _screen_premise_findings

    screen = {"regime": "pressed", "crush_margin": 1.0, "pocket_clearance": 1.191e-3, "pocket_index_range": 0.0}
    beyond = _screen_premise_findings({**screen, "excursion_residual_peak_to_peak": 2.5e-3}, "load.moment", "load")
    assert len(beyond) == 1 and "no cage position gives the balls room" in beyond[0].message
    # a residual well inside the pocket clearance (case b at 430 N·m computes about 35 µm): no warning
    assert _screen_premise_findings({**screen, "excursion_residual_peak_to_peak": 35e-6}, "load.moment", "load") == []


def test_regimes_follow_the_clearances():
    """free while s_pp <= c_p; pressed while e_req = s1 - c_p/2 <= C; crushed beyond."""
    rp, cp, C = KW["pitch_radius"], KW["pocket_clearance"], KW["guide_clearance"]
    for s1, expected in ((0.9 * cp / 2, "free"), ((cp / 2 + 0.5 * C), "pressed"), ((cp / 2 + 1.1 * C), "crushed")):
        r = crush_screen(PSI, _speeds(s1 / rp), 143.7, **KW)
        assert r.regime == expected
        if expected != "free":
            assert r.required_eccentricity == pytest.approx(s1 - cp / 2, rel=1e-6)
            assert r.crush_margin == pytest.approx((C - (s1 - cp / 2)) / C, rel=1e-6)
            assert r.film_push > 0.0
        else:
            assert r.required_eccentricity == 0.0 and r.film_push == 0.0


@pytest.mark.parametrize("moment, regime", [(100.0, "free"), (430.0, "pressed"), (600.0, "crushed")])
def test_reference_bearing_regimes_against_the_outer_race_control_formula(moment, regime):
    """A second method for the excursion: Harris & Kotzalas' pure-rolling orbital speed with
    outer-race control, omega_m / omega_i = (1 - (D/d_m) cos a_i) / (1 + cos(a_i - a_o))
    (Rolling Bearing Analysis, 5th ed., ch. 8), from the solver's contact angles, integrated
    by the trapezoidal rule. It must give the screen's s_pp within 2 % and the same regime:
    pocket clearance 1.18 mm and guide clearance 0.29 mm (docs/model.md §2) put the limits at
    s_pp = 1.18 mm (pressed) and 1.76 mm (crushed)."""
    from bearingsim.pipeline.scene.load import load_scene
    from bearingsim.pipeline.stages.quasistatic import cage_screen, solve

    # at the reference temperature: the clearances are Table 1's as drawn
    scene = load_scene("helicopter-b-given-hinge", [f"load.moment={moment}", "thermal.parts_degC=20"])
    result = solve(scene)
    D, dm = scene.bearing.ball_diameter, scene.cage.mean_diameter
    ai, ao = result.inner_contact_angle, result.outer_contact_angle
    om = (1.0 - D / dm * np.cos(ai)) / (1.0 + np.cos(ai - ao))
    rel = om / om.mean() - 1.0
    s = np.cumsum(np.concatenate([[0.0], 0.5 * (rel[1:] + rel[:-1])])) * (2 * math.pi / Z) * 0.5 * dm
    screen = cage_screen(scene, result)
    assert screen.excursion_peak_to_peak == pytest.approx(s.max() - s.min(), rel=0.02)
    limit_pressed, limit_crushed = 1.18e-3, 1.18e-3 + 2 * 0.29e-3
    s_pp = s.max() - s.min()
    independent = "free" if s_pp <= limit_pressed else ("pressed" if s_pp <= limit_crushed else "crushed")
    assert screen.regime == independent == regime
