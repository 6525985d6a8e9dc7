"""Physical sanity of the dynamic bearing model on short runs: a few hundred to a
few thousand steps of the reference bearing (docs/model.md §2) with Eyring traction."""

from __future__ import annotations

import math

import numpy as np
import pytest

from bearingsim.dynamics.bearing import ModelOptions, simulate_bearing
from bearingsim.dynamics.lubrication.lubricant import load_builtin_lubricant
from bearingsim.dynamics.multibody.settings import HHTSettings

from .bearing_fixtures import INNER_SPEED, REFERENCE, reference_model

SETTINGS = HHTSettings(alpha=0.1, first_step=1e-6, min_step=1e-8, max_step=2e-6, rtol=1e-4, atol=1e-9)
NATO = load_builtin_lubricant("nato-o156")


def run(moment=430.0, duration=0.01, **options):
    params, start = reference_model(moment=moment, lubricant=NATO, options=ModelOptions(**options))
    return params, start, simulate_bearing(params, start, SETTINGS, duration, 2e-5)


@pytest.fixture(scope="module")
def case_b():
    return run()


def cage_speed(params, r):
    return r.channels()["cage/speed"].data


def test_cage_speed_near_epicyclic(case_b):
    """Pure rolling on a fixed outer race: omega_c = Omega_i/2 (1 - D cos(alpha)/d_m)
    (Harris & Kotzalas, Rolling Bearing Analysis, 5th ed., vol. 1, §8.2, eq. 8.x for the cage
    speed with a stationary outer ring), evaluated at the mean quasi-static contact angle.
    Traction makes balls creep, so the cage runs a little slower, not faster; 2 % bounds it."""
    params, start, r = case_b
    from bearingsim.dynamics.operating_point import OperatingPoint
    from bearingsim.dynamics.quasistatic.options import QuasiStaticOptions
    from bearingsim.dynamics.quasistatic.solver import solve_quasistatic

    from .bearing_fixtures import STEEL
    qs = solve_quasistatic(REFERENCE, STEEL, STEEL, OperatingPoint(axial=34000.0, moment=430.0, inner_speed=INNER_SPEED),
                           QuasiStaticOptions(gyroscopic=True))
    alpha = float(np.mean(np.abs(qs.inner_contact_angle)))
    epicyclic = 0.5 * INNER_SPEED * (1.0 - REFERENCE.ball_diameter * math.cos(alpha) / REFERENCE.pitch_diameter)
    late = r.t >= 0.5 * r.t[-1]
    mean = float(np.mean(cage_speed(params, r)[late]))
    assert mean == pytest.approx(epicyclic, rel=0.02)
    assert mean <= epicyclic * 1.001


def test_energy_balance(case_b):
    """Work of the drive and of the applied loads = dissipation + change of kinetic and
    elastic (Hertz, hinge) energy, integrated step by step (trapezoid on accepted steps)."""
    params, start, r = case_b
    series = r.channels()
    stored = sum(series[name].data[-1] - series[name].data[0]
                 for name in ("energy/kinetic", "energy/hertz", "energy/hinge"))
    supplied = r.energy["drive"] + r.energy["external"] - r.energy["dissipated"]
    # the drive delivers ~2 J in 10 ms; the balance must close to 1 % of that
    assert abs(supplied - stored) < 0.01 * abs(r.energy["drive"])
    assert r.energy["dissipated"] > 0.0


def test_no_nan_and_counters(case_b):
    params, start, r = case_b
    assert np.all(np.isfinite(r.q)) and np.all(np.isfinite(r.v))
    assert r.stats["steps"] > 0 and r.stats["factorizations"] >= 1


def test_cage_stays_in_clearance_without_moment_and_cage_race_physics():
    """No moment, no cage–race model: nothing pushes the cage sideways, so its centre must
    stay well inside the guide clearance (it is held by the balls through the pockets)."""
    params, start, r = run(moment=0.0, duration=0.006, cage_race="none")
    centre = r.channels()["cage/position"].data
    offset = np.hypot(centre[:, 0], centre[:, 1])
    assert offset.max() < 0.5 * params.guide_clearance


def _contact_direction(params, r):
    """Circular mean of the land contact azimuth, weighted by the metal normal force."""
    series = r.channels()
    w = series["cage_race/metal_force"].data
    az = series["cage_race/contact_azimuth"].data
    if w.sum() <= 0.0:  # no metal contact yet: use the direction the cage centre sits in
        centre = series["cage/position"].data
        w = np.hypot(centre[:, 0], centre[:, 1])
        az = np.arctan2(centre[:, 1], centre[:, 0])
    return math.atan2(np.sum(w * np.sin(az)), np.sum(w * np.cos(az)))


def test_reversing_the_moment_turns_the_contact_location_by_pi(case_b):
    """M_y -> -M_y is the bearing turned by pi about its axis (the speed sense is kept), so
    where the cage meets its land must turn by pi as well."""
    params, _, r_pos = case_b
    _, _, r_neg = run(moment=-430.0)
    a_pos, a_neg = _contact_direction(params, r_pos), _contact_direction(params, r_neg)
    turned = (a_neg - a_pos) % (2 * math.pi)
    assert turned == pytest.approx(math.pi, abs=math.radians(15))
