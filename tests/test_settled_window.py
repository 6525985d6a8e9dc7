"""The settled window of a run (pipeline/results/settled_window.py) and the summary over it
(pipeline/results/cage_metrics.py), on synthetic series whose answers are known by
construction: a start-up crash then a quiet regime, a run steady from the start, a regime
that changes at half the run, a slow drift, a run too short to settle."""

from __future__ import annotations

import math

import numpy as np
import pytest

from bearingsim.pipeline.results.cage_metrics import (
    CageSeries, GuideLand, PocketImpacts, cage_summary, split_weights, time_weights,
)
from bearingsim.pipeline.results.settled_window import detect_settled_window

C, EPS0, OMEGA = 2.9e-4, 0.05, 100.0  # m, -, rad/s: one cage revolution = 62.83 ms
REV = 2 * math.pi / OMEGA


def synthetic_run(eps, direction, t, friction=None, film_power=5.0, omega=OMEGA):
    """Series of cage_summary's arguments for a cage at eccentricity ratio eps(t) towards
    azimuth direction(t) [rad]; the land film is the hybrid model's C (1 + eps0) - e."""
    eps = np.asarray(eps, dtype=float) * np.ones_like(t)
    direction = np.asarray(direction, dtype=float) * np.ones_like(t)
    xy = np.c_[eps * C * np.cos(direction), eps * C * np.sin(direction)]
    metal = np.where(eps > 1.0, 2e4 * (eps - 1.0), 0.0)
    return {
        "t": t, "cage_xy": xy, "cage_speed": np.full_like(t, omega), "eccentricity_ratio": eps,
        "contact_azimuth": np.mod(direction, 2 * math.pi),
        "friction_power": np.zeros_like(t) if friction is None else friction,
        "inner_race_z": np.zeros_like(t), "impact_peak_forces": np.zeros(0),
        "film_power": np.full_like(t, film_power), "min_film": np.maximum(C * (1 + EPS0 - eps), 0.0),
        "land_force": np.c_[-50 * np.cos(direction), -50 * np.sin(direction)], "metal_force": metal,
        "guide_clearance": C, "land_boundary": EPS0,
    }


_SERIES = ("t", "cage_xy", "cage_speed", "eccentricity_ratio", "contact_azimuth", "friction_power", "inner_race_z",
           "film_power", "min_film", "land_force", "metal_force")
_LAND = {"guide_clearance": "clearance", "land_boundary": "boundary", "land_roughness": "roughness",
         "land_film": "film", "land_speed": "speed"}


def summary_of(run, **kw):
    """`cage_summary` of a run given as flat keywords (the series' names, impact_*, the land's
    guide_clearance / land_*), as the synthetic runs here write them."""
    flat = {**run, **kw}
    series = CageSeries(**{k: flat.pop(k) for k in _SERIES if k in flat})
    impacts = PocketImpacts(flat.pop("impact_peak_forces"), flat.pop("impact_times", None),
                            flat.pop("impact_orbital_positions", None))
    land = GuideLand(**{_LAND[k]: flat.pop(k) for k in list(flat) if k in _LAND})
    return cage_summary(series, impacts, land, **flat)


def crash_then_pressed(t, crash_end=0.08):
    """Start-up crash (eps swinging 0.72-1.32 towards ~300°, 400 W of metal friction in
    contact) until `crash_end`, then pressed at 30° with eps 0.85 ± 0.02."""
    crash = t < crash_end
    eps = np.where(crash, 1.02 + 0.3 * np.sin(2 * math.pi * 60 * t), 0.85 + 0.02 * np.sin(2 * math.pi * 23 * t))
    direction = np.radians(np.where(crash, 300.0 + 20.0 * np.sin(2 * math.pi * 40 * t),
                                    30.0 + 3.0 * np.sin(2 * math.pi * 7 * t)))
    friction = np.where(crash & (eps > 1.0), 400.0, 0.0)
    return synthetic_run(eps, direction, t, friction)


def test_startup_spike_then_quiet_settles_after_the_spike():
    t = np.linspace(0.0, 1.0, 20001)
    run = crash_then_pressed(t)
    s = summary_of(run)
    end = s["startup"]["end_time"]
    # blocks of half a revolution (31.4 ms): the block holding the crash's end is still
    # transient, the next one is the regime
    assert 0.08 < end <= 0.08 + 2 * 0.5 * REV
    assert s["settled_window"] == [end, 1.0]
    assert s["settled_revolutions"] == pytest.approx((1.0 - end) / REV)
    assert s["warnings"] == []  # ~14.5 revolutions settled, every series present
    # the crash's metal energy is the start-up's, none of it is in the settled burn zone
    total_metal = float(np.sum(run["friction_power"] * time_weights(t)))
    assert total_metal > 1.0
    assert s["startup"]["metal_energy"] == pytest.approx(total_metal, rel=1e-12)
    assert s["burn_zone_energy_metal"] == 0.0
    assert s["startup"]["max_metal_force"] == pytest.approx(2e4 * 0.32, rel=1e-3)
    assert s["startup"]["land_force_peak"] == pytest.approx(50.0)
    assert s["startup"]["metal_contact_fraction"] > 0.3
    # film heat of the settled window: 5 W constant over [t_i, 1 s], t_i its first sample
    t_i = t[np.searchsorted(t, end)]
    assert s["burn_zone_energy_film"] == pytest.approx(5.0 * (1.0 - t_i), rel=1e-12)
    assert s["burn_zone_energy_total"] == pytest.approx(s["burn_zone_energy_film"], rel=1e-12)
    # start-up + settled film energy = the whole run's (the windows share one sample)
    assert s["startup"]["film_energy"] + s["burn_zone_energy_film"] == pytest.approx(5.0, rel=1e-12)
    # the regime's statistics, not the crash's
    assert s["cage_metal_contact_fraction"] == 0.0
    assert s["cage_eps_mean"] == pytest.approx(0.85, abs=2e-3)
    assert math.degrees(s["cage_offset_azimuth_mean"]) == pytest.approx(30.0, abs=0.3)
    late = t >= end
    assert s["land_film_min"] == pytest.approx(float(np.min(run["min_film"][late])), rel=1e-12)


def test_a_late_touch_of_the_land_in_a_wandering_regime_is_still_startup():
    """A touch of the land (eps 0.85 -> 1.0 for 0.5 ms) at 0.30 s, after the crash, in a regime
    whose block means wander (eps 0.85 +- 0.02 at 5 Hz). The touch moves its block's mean by
    0.002 and its spread by 0.013, both inside the band of the wandering reference, but not
    its largest eps: the touch is start-up, and the window starts after it. Made up to show the
    case found in case b (settled_window.py, rule 2)."""
    t = np.linspace(0.0, 1.2, 120001)
    run = crash_then_pressed(t)
    regime = 0.85 + 0.02 * np.sin(2 * math.pi * 5 * t) + 0.01 * np.sin(2 * math.pi * 23 * t)
    calm_eps = np.where(t < 0.08, run["eccentricity_ratio"], regime)
    touch = (t >= 0.3000) & (t < 0.3005)
    eps = np.where(touch, 1.0, calm_eps)
    xy = run["cage_xy"] / run["eccentricity_ratio"][:, None]  # unit direction * C
    window = detect_settled_window(t, eps, xy * eps[:, None], run["cage_speed"], C)
    assert window.limited_by == ("eps max",)
    assert 0.3005 < window.start <= 0.3005 + 0.5 * REV + 1e-9
    # the same run without the touch settles after the crash
    calm = detect_settled_window(t, calm_eps, xy * calm_eps[:, None], run["cage_speed"], C)
    assert calm.start < 0.2


def test_split_weights_add_up_to_the_whole_run():
    t = np.sort(np.random.default_rng(3).uniform(0.0, 1.0, 500))
    early, late = split_weights(t, 0.4)
    np.testing.assert_allclose(early + late, time_weights(t), rtol=0, atol=1e-15)
    i = np.searchsorted(t, 0.4)
    assert early.sum() == pytest.approx(t[i] - t[0]) and late.sum() == pytest.approx(t[-1] - t[i])


def test_a_run_steady_from_the_start_ends_its_startup_at_the_floor():
    t = np.linspace(0.0, 1.0, 10001)
    w = detect_settled_window(t, np.full_like(t, 0.5), np.tile([0.5 * C, 0.0], (t.size, 1)),
                              np.full_like(t, OMEGA), C)
    assert w.start == pytest.approx(REV)  # one cage revolution: the floor
    assert w.limited_by == ("floor",) and w.warnings == ()
    assert w.block == pytest.approx(0.5 * REV)


def test_a_regime_change_at_half_the_run_is_capped_and_flagged():
    t = np.linspace(0.0, 1.0, 10001)
    eps = np.where(t < 0.5, 0.3, 0.8)
    w = detect_settled_window(t, eps, np.c_[eps * C, np.zeros_like(t)], np.full_like(t, OMEGA), C)
    assert w.start == pytest.approx(0.5)
    assert "cap" in w.limited_by and "eps mean" in w.limited_by
    assert any("did not end in the first half" in m for m in w.warnings)


def test_drift_check_shows_a_slow_drift():
    t = np.linspace(0.0, 1.0, 10001)
    eps = 0.2 + 0.7 * t  # still drifting at the end of the run
    s = summary_of(synthetic_run(eps, 0.0, t))
    first, second = s["settled_drift"]["cage_eps_mean"]
    start = s["settled_window"][0]
    # time means of a linear ramp over the two halves of [start, 1] (to the sample spacing)
    assert first == pytest.approx(0.2 + 0.7 * (start + 0.25 * (1 - start)), abs=1e-4)
    assert second == pytest.approx(0.2 + 0.7 * (start + 0.75 * (1 - start)), abs=1e-4)
    assert second - first > 0.1
    assert set(s["settled_drift"]) == {"cage_eps_mean", "cage_metal_contact_fraction", "cage_land_force_mean",
                                       "cage_offset_azimuth_mean", "land_film_min"}
    assert s["settled_drift"]["cage_land_force_mean"] == [pytest.approx(50.0), pytest.approx(50.0)]


def test_a_run_too_short_to_settle_says_so():
    t = np.linspace(0.0, 0.1, 2001)  # 1.6 cage revolutions
    s = summary_of(synthetic_run(0.5, 1.0, t))
    assert s["settled_window"][0] == pytest.approx(0.05)  # capped at half the run
    assert any(m.startswith("run too short to settle") for m in s["warnings"])
    assert s["settled_revolutions"] == pytest.approx(0.05 / REV)


def test_missing_film_series_are_warned_and_the_film_is_derived_from_eps():
    t = np.linspace(0.0, 1.0, 5001)
    run = synthetic_run(0.7, 2.0, t)
    run.pop("film_power"), run.pop("min_film")
    s = summary_of(run)
    assert s["burn_zone_energy_film"] == 0.0
    assert s["land_film_min"] == pytest.approx(C * (1 + EPS0 - 0.7))
    assert any("film-power" in m for m in s["warnings"]) and any("min_film" in m for m in s["warnings"])
