"""Summary metrics on synthetic signals whose answers are known in closed form."""

from __future__ import annotations

import math

import numpy as np
import pytest

from bearingsim.pipeline.results.cage_metrics import (
    burn_zone_histogram,
    burn_zone_sector,
    CageSeries,
    PocketImpacts,
    cage_summary,
    circular_spread,
    whirl_ratio,
)
from bearingsim.pipeline.results.timeseries import Series, read_timeseries, write_timeseries


def test_circular_spread_limits():
    assert circular_spread(np.full(10, 1.3)) == pytest.approx(0.0, abs=1e-7)
    # von Mises-free check: two angles ±d about a mean have R = cos d, spread = sqrt(-2 ln cos d)
    d = 0.4
    assert circular_spread(np.array([1.0 - d, 1.0 + d])) == pytest.approx(math.sqrt(-2 * math.log(math.cos(d))))
    # wrap-around: angles near 0 and 2 pi are close, not pi apart
    assert circular_spread(np.array([0.05, 2 * math.pi - 0.05])) < 0.06


def test_whirl_ratio_of_synchronous_orbit():
    t = np.linspace(0.0, 1.0, 20001)
    omega_c, omega_w = 130.0, 130.0 * 0.7
    x, y = 1e-4 * np.cos(omega_w * t), 1e-4 * np.sin(omega_w * t)
    assert whirl_ratio(t, x, y, np.full_like(t, omega_c)) == pytest.approx(0.7, rel=1e-6)


def test_burn_zone_sector_finds_shortest_arc_across_zero():
    hist = np.zeros(360)
    hist[350:360] = 1.0  # energy straddles azimuth 0
    hist[0:10] = 1.0
    hist[180] = 0.5      # a little elsewhere: 80 % still lies in the 20-degree arc
    start, end = burn_zone_sector(hist, 0.8)
    # 80 % of 20.5 needs 17 of the unit sectors: the shortest arc is 17° inside [350°, 370°]
    assert math.degrees(end - start) == pytest.approx(17.0)
    assert 350.0 - 1e-9 <= math.degrees(start) and math.degrees(end) <= 370.0 + 1e-9
    assert burn_zone_sector(np.zeros(36)) is None


def test_burn_zone_histogram_conserves_energy():
    rng = np.random.default_rng(1)
    az = rng.uniform(-10, 10, 1000)
    e = rng.uniform(0, 1, 1000)
    assert burn_zone_histogram(az, e, 72).sum() == pytest.approx(e.sum())


def test_cage_summary_on_constructed_run():
    """Cage spinning at 130 rad/s ± 1 %, in metal contact during the second quarter of the
    window [0.1, 0.2] s at azimuth 30°, 10 impacts of 1..10 N. The window is given
    (`settled_start`): this test checks the metrics' formulas; the detection of the
    settled window has its own tests (tests/test_settled_window.py)."""
    t = np.linspace(0.0, 0.2, 4001)
    speed = 130.0 * (1 + 0.01 * np.sin(2 * math.pi * 50 * t))
    eps = np.where((t > 0.125) & (t <= 0.15), 1.02, 0.5)
    az = np.full_like(t, math.radians(30))
    power = np.where(eps > 1, 2.0, 0.0)
    xy = np.c_[1e-4 * np.cos(40 * t), 1e-4 * np.sin(40 * t)]
    s = cage_summary(CageSeries(t, xy, speed, eps, az, power, np.full_like(t, 5e-5)),
                     PocketImpacts(np.arange(1.0, 11.0)), settled_start=0.1)
    assert s["cage_speed_mean"] == pytest.approx(130.0, rel=1e-3)
    assert s["cage_speed_variation"] == pytest.approx(0.02, rel=0.01)
    assert s["cage_metal_contact_fraction"] == pytest.approx(0.25, abs=2e-3)
    assert s["cage_contact_angle_spread"] == pytest.approx(0.0, abs=1e-6)
    assert s["cage_whirl_ratio"] == pytest.approx(40 / 130, rel=2e-3)
    assert s["inner_race_axial_mean"] == pytest.approx(5e-5)
    assert s["pocket_impacts"] == 10
    assert s["pocket_impact_force_p95"] == pytest.approx(np.percentile(np.arange(1, 11), 95))
    start, end = s["burn_zone_sector"]
    assert start <= math.radians(30) <= end and end - start <= math.radians(1.01)
    assert s["burn_zone_energy_total"] == pytest.approx(2.0 * 0.025, rel=2e-3)


def test_timeseries_roundtrip_keeps_units(tmp_path):
    t = np.linspace(0, 1, 11)
    series = {"time": Series(t, "s", "sample time"),
              "cage/position": Series(np.zeros((11, 3)), "m", "cage centre", ("time", "xyz"))}
    write_timeseries(tmp_path / "ts.h5", series, {"scene": "x"})
    back, attrs = read_timeseries(tmp_path / "ts.h5")
    assert attrs["scene"] == "x"
    assert back["cage/position"].units == "m" and back["cage/position"].dims == ("time", "xyz")
    np.testing.assert_array_equal(back["time"].data, t)
    with pytest.raises(ValueError, match="dimensions"):
        write_timeseries(tmp_path / "bad.h5", {"x": Series(np.zeros((2, 2)), "m", "x")})
    assert not (tmp_path / "bad.h5").exists()
