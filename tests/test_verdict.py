"""Land heat, film-thickness ratio, classes, risk and the verdict (pipeline/results/
cage_metrics.py, pipeline/scene/cage_classes.py, pipeline/results/verdict.py) on synthetic
series whose answers are known by construction, and the verdict printed by the CLI."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from typer.testing import CliRunner

from bearingsim.pipeline.results.cage_metrics import (
    film_heat_histogram,
    impact_regions,
    land_heat,
    time_weights,
)
from bearingsim.pipeline.results.verdict import cage_verdict, format_arc, verdict_lines, verdict_rows
from bearingsim.pipeline.scene.cage_classes import CageClassThresholds, classify_cage, risk_level

from .test_settled_window import C, EPS0, OMEGA, summary_of, synthetic_run

T = np.linspace(0.0, 1.0, 20001)  # 15.9 cage revolutions at OMEGA


def _summary(run, **kw):
    s = summary_of(run, **kw)
    s["duration"] = float(run["t"][-1])
    s["verdict"] = cage_verdict(s)
    return s


# --- film heat round the land -----------------------------------------------------------

def test_film_heat_sums_to_the_film_energy_and_peaks_at_the_offset():
    rng = np.random.default_rng(7)
    phi = rng.uniform(-4, 10, 50)
    k = rng.uniform(0.0, 0.99, 50)
    energy = rng.uniform(0.1, 2.0, 50)
    for i in range(phi.size):  # sample by sample: its sectors sum to its energy
        hist = film_heat_histogram(phi[i:i + 1], k[i:i + 1], energy[i:i + 1])
        assert hist.sum() == pytest.approx(energy[i], rel=1e-12)
        assert np.all(hist >= 0.0)
        peak = (np.argmax(hist) + 0.5) * 2 * math.pi / 360
        assert abs((peak - phi[i] + math.pi) % (2 * math.pi) - math.pi) <= math.radians(0.5) + 1e-12
        # the thickest film, opposite, gets least
        trough = (np.argmin(hist) + 0.5) * 2 * math.pi / 360
        assert abs((trough - phi[i]) % (2 * math.pi) - math.pi) <= math.radians(0.5) + 1e-12 or k[i] < 1e-3
    assert film_heat_histogram(phi, k, energy).sum() == pytest.approx(energy.sum(), rel=1e-12)


def test_film_heat_per_sector_matches_a_quadrature_of_one_over_h():
    """Second method: midpoint quadrature of 1/h(theta) over each sector, h = C_f (1 - k cos)."""
    phi, k, energy = math.radians(30.0), 0.8 / (1 + EPS0), 3.0
    hist = film_heat_histogram(np.array([phi]), np.array([k]), np.array([energy]), sectors=36)
    fine = (np.arange(36 * 2000) + 0.5) * 2 * math.pi / (36 * 2000)
    density = 1.0 / (1.0 - k * np.cos(fine - phi))
    expected = energy * density.reshape(36, 2000).sum(axis=1) / density.sum()
    np.testing.assert_allclose(hist, expected, rtol=1e-7)
    # peak/trough = h_max/h_min = (1 + k)/(1 - k) in the limit of thin sectors
    thin = film_heat_histogram(np.array([phi]), np.array([k]), np.array([1.0]), sectors=3600)
    assert thin.max() / thin.min() == pytest.approx((1 + k) / (1 - k), rel=1e-3)


@pytest.mark.parametrize("drag", [1.0, -1.0])
def test_film_heat_follows_the_film_torque_on_its_cavitated_side(drag):
    """Dragged film (drag = sign of cage + land speed): full film 1/h upstream of the
    thinnest film, striated film (fill h_min/h) downstream, density h_min/h^2 — the shear
    of (M.85). Second method: midpoint quadrature of that density per sector."""
    phi, k = math.radians(30.0), 0.7
    hist = film_heat_histogram(np.array([phi]), np.array([k]), np.array([1.0]), sectors=36, drag=drag)
    fine = (np.arange(36 * 4000) + 0.5) * 2 * math.pi / (36 * 4000)
    x = (fine - phi + math.pi) % (2 * math.pi) - math.pi
    density = np.where(drag * x <= 0.0, 1.0 / (1.0 - k * np.cos(x)), (1.0 - k) / (1.0 - k * np.cos(x)) ** 2)
    np.testing.assert_allclose(hist, density.reshape(36, 4000).sum(axis=1) / density.sum(), rtol=1e-7)
    # (M.85): round the land the density integrates to pi (2 + k) / ((1 + k) sqrt(1 - k^2))
    assert density.mean() * 2 * math.pi == pytest.approx(math.pi * (2 + k) / ((1 + k) * math.sqrt(1 - k * k)),
                                                          rel=1e-6)
    # the downstream (cavitated) half gets 1/(2 + k) of the heat, the upstream half the rest
    downstream = hist[np.arange(3, 21)] if drag > 0 else hist[np.r_[np.arange(21, 36), np.arange(0, 3)]]
    assert downstream.sum() == pytest.approx(1.0 / (2.0 + k), rel=1e-9)
    assert np.argmax(hist) in (2, 3)  # the sectors either side of 30°


def test_film_heat_limits():
    uniform = film_heat_histogram(np.array([1.0]), np.array([0.0]), np.array([3.6]))
    np.testing.assert_allclose(uniform, 0.01, rtol=1e-12)  # centred cage: even round the land
    touching = film_heat_histogram(np.array([math.radians(100.5)]), np.array([1.0]), np.array([2.0]))
    assert touching[100] == pytest.approx(2.0, rel=1e-3)  # k = 1: all at the contact azimuth


def test_land_heat_keeps_metal_at_the_contact_and_film_round_the_land():
    t = np.linspace(0.0, 0.1, 1001)
    az = np.full_like(t, math.radians(200.5))
    metal, film = land_heat(t, az, np.full_like(t, 0.9), np.full_like(t, 20.0), np.full_like(t, 5.0), EPS0)
    assert metal[200] == pytest.approx(2.0, rel=1e-12) and metal.sum() == pytest.approx(2.0, rel=1e-12)
    assert film.sum() == pytest.approx(0.5, rel=1e-12) and np.argmax(film) == 200
    assert np.count_nonzero(film) == 360
    metal_late, film_late = land_heat(t, az, np.full_like(t, 0.9), np.full_like(t, 20.0), np.full_like(t, 5.0),
                                      EPS0, start=0.05)
    assert metal_late.sum() == pytest.approx(1.0, rel=1e-12) and film_late.sum() == pytest.approx(0.25, rel=1e-12)


# --- film-thickness ratio ---------------------------------------------------------------

def test_film_thickness_ratio_by_hand():
    """eps 0.6 ± 0.3 sin: the thinnest film C (1 + eps0 - 0.9) = 43.5 µm where eps peaks."""
    eps = 0.6 + 0.3 * np.sin(2 * math.pi * 5.0 * T)
    direction = np.full_like(T, math.radians(75.0))
    s = _summary(synthetic_run(eps, direction, T), land_roughness=0.8e-6)
    h_min = C * (1 + EPS0 - 0.9)
    assert s["land_film_min"] == pytest.approx(h_min, rel=1e-6)
    assert s["land_roughness"] == 0.8e-6
    assert s["land_film_ratio_min"] == pytest.approx(h_min / 0.8e-6, rel=1e-6)
    # when: a crest of the sine, sin(2 pi 5 t) = 1 at t = 0.05 + 0.2 j
    assert (s["land_film_min_time"] - 0.05) / 0.2 == pytest.approx(round((s["land_film_min_time"] - 0.05) / 0.2), abs=1e-3)
    assert s["land_film_min_time"] >= s["settled_window"][0]
    assert math.degrees(s["land_film_min_azimuth"]) == pytest.approx(75.0)
    v = s["verdict"]
    assert v["land_film_min_um"] == pytest.approx(h_min * 1e6, rel=1e-6)
    assert v["land_film_min_azimuth_deg"] == pytest.approx(75.0)
    assert v["land_film_ratio_min"] == pytest.approx(h_min / 0.8e-6, rel=1e-6)
    assert v["land_roughness_um"] == pytest.approx(0.8)


# --- classes, risk and the verdict from series --------------------------------------------

def test_cage_pressed_at_30_degrees():
    direction = np.radians(30.0 + 4.0 * np.sin(2 * math.pi * 3.0 * T))
    eps = 0.88 + 0.03 * np.sin(2 * math.pi * 17.0 * T)
    s = _summary(synthetic_run(eps, direction, T))
    assert classify_cage(s) == "pressed"
    assert s["cage_offset_spread"] < 0.1 and s["cage_eps_mean"] == pytest.approx(0.88, abs=1e-3)
    v = s["verdict"]
    assert v["class"] == "pressed" and v["risk"] == "elevated"
    a, b = v["sector_deg"]
    assert 24.0 <= a < 30.0 < b <= 36.0  # 80 % of the time within the ±4° swing round 30°
    h_um = C * (1 + EPS0 - 0.91) * 1e6
    assert v["land_film_min_um"] == pytest.approx(h_um, rel=1e-4)
    assert v["text"] == (f"Cage pressed onto the outer-race land at {a:.0f}–{b:.0f}° through a {h_um:.0f} µm film "
                         f"(Λ {h_um:.0f}): elevated risk; no metal contact in the settled run.")
    # the same cage on a rough land (sigma 15 µm): Lambda 2.7 < 3, a mixed film on one sector
    rough = _summary(synthetic_run(eps, direction, T), land_roughness=15e-6)
    assert rough["verdict"]["risk"] == "high"
    assert "mixed film" in " ".join(rough["verdict"]["risk_reasons"])


def test_whirling_cage():
    """The centre orbits at 0.9 x the cage speed at eps 0.7: no fixed sector, low risk."""
    direction = 0.9 * OMEGA * T
    s = _summary(synthetic_run(0.7, direction, T))
    assert classify_cage(s) == "whirling"
    assert s["cage_whirl_ratio"] == pytest.approx(0.9, rel=1e-3)
    assert s["cage_offset_spread"] > 1.0
    v = s["verdict"]
    assert v["sector_deg"] is None and v["risk"] == "low"
    assert v["text"].startswith("Cage whirling at 0.9× the cage speed, thinnest land film 102 µm (Λ 102): low risk")


def test_crushed_cage_burns_one_sector():
    """Metal contact (eps 1.03) at 200° all the time with 50 W of friction."""
    s = _summary(synthetic_run(1.03, math.radians(200.3), T, friction=np.full_like(T, 50.0)))
    assert classify_cage(s) == "crushed"
    v = s["verdict"]
    assert v["risk"] == "high" and v["sector_deg"] == pytest.approx([200.0, 201.0])
    assert v["metal_contact_fraction"] == pytest.approx(1.0)
    assert s["burn_zone_energy_metal"] == pytest.approx(50.0 * (1.0 - s["settled_window"][0]), rel=1e-3)
    h_um = C * (1 + EPS0 - 1.03) * 1e6
    # the land law counts metal contact below a film of eps0 C, which the sentence names beside
    # the film and its Lambda (above 3 here) so that the two do not read as a contradiction
    assert s["land_contact_film"] == pytest.approx(EPS0 * C, rel=1e-12)
    assert v["text"] == (f"Cage crushed against the outer-race land at 200–201°, thinnest land film {h_um:.2g} µm "
                         f"(Λ {h_um:.2g}): high risk; metal contact 100 % of the settled run (the land law's, "
                         f"below a film of {EPS0 * C * 1e6:.0f} µm).")


def test_pocket_impact_regions_and_counts_in_the_settled_window():
    rng = np.random.default_rng(11)
    n = 400
    times = rng.uniform(0.0, 1.0, n)
    orbit = np.where(rng.uniform(size=n) < 0.6, rng.uniform(np.radians(120), np.radians(140), n),
                     rng.uniform(0.0, 2 * math.pi, n))
    peaks = rng.uniform(10.0, 100.0, n)
    run = synthetic_run(0.5, 0.0, T)
    run["impact_peak_forces"] = peaks
    s = _summary(run, impact_times=times, impact_orbital_positions=orbit)
    late = times >= s["settled_window"][0]
    assert s["pocket_impacts"] == int(late.sum()) and s["startup"]["pocket_impacts"] == int((~late).sum())
    assert s["pocket_impact_force_p95"] == pytest.approx(np.percentile(peaks[late], 95))
    regions = s["verdict"]["pocket_impact_regions_deg"]
    assert regions[0] == pytest.approx([120.0, 140.0])
    # the text gives each region's share of the settled impacts, counted here by hand
    in_region = late & (orbit >= np.radians(120)) & (orbit < np.radians(140))
    share = in_region.sum() / late.sum()
    assert s["verdict"]["pocket_impact_region_shares"][0] == pytest.approx(share)
    row = dict((q, value) for q, value, _ in verdict_rows(s["verdict"]))
    assert row["where the impacts concentrate (share, orbital position)"].startswith(
        f"{100 * share:.0f} % at 120–140°")
    # evenly spread impacts make no region; too few make no statement
    assert impact_regions(np.linspace(0, 2 * math.pi, 360, endpoint=False)) == []
    assert impact_regions(np.zeros(5)) is None


# --- the rules on summary dicts -------------------------------------------------------------

def base(**kw):
    s = {"duration": 1.0, "settled_window": [0.1, 1.0], "cage_speed_mean": 140.0, "cage_speed_variation": 0.01,
         "cage_metal_contact_fraction": 0.0, "cage_contact_angle_spread": None, "cage_whirl_ratio": 0.0,
         "cage_offset_spread": 2.0, "cage_eps_mean": 0.3, "land_film_ratio_min": 200.0}
    s.update(kw)
    return s


@pytest.mark.parametrize("metrics, cls, risk", [
    (base(), "centred", "low"),
    (base(cage_offset_spread=0.2, cage_eps_mean=0.85, land_film_ratio_min=24.0), "pressed", "elevated"),
    (base(cage_offset_spread=0.2, cage_eps_mean=0.85, land_film_ratio_min=2.0), "pressed", "high"),
    # offset steady but near the centre: centred, not pressed
    (base(cage_offset_spread=0.2, cage_eps_mean=0.4), "centred", "low"),
    # crushed comes first even though the offset is also in one sector
    (base(cage_metal_contact_fraction=0.8, cage_contact_angle_spread=0.1, cage_offset_spread=0.1,
          cage_eps_mean=1.02, land_film_ratio_min=0.5), "crushed", "high"),
    (base(cage_whirl_ratio=0.9, cage_eps_mean=0.7), "whirling", "low"),
    (base(cage_whirl_ratio=0.9, cage_eps_mean=0.9, cage_metal_contact_fraction=0.01), "whirling", "elevated"),
    (base(cage_metal_contact_fraction=0.2, cage_contact_angle_spread=1.5), "chaotic", "high"),
    (base(cage_metal_contact_fraction=0.02, cage_speed_variation=0.1), "chaotic", "elevated"),
    (base(cage_speed_variation=0.1), "chaotic", "low"),
    # a centred cage with isolated rubs: still centred, but not low risk
    (base(cage_metal_contact_fraction=0.02), "centred", "elevated"),
    # boundary lubrication somewhere on the land is high whatever the class
    (base(land_film_ratio_min=0.8), "centred", "high"),
    (base(land_film_ratio_min=2.0), "centred", "elevated"),
])
def test_documented_class_and_risk_rules(metrics, cls, risk):
    assert classify_cage(metrics) == cls
    assert risk_level(metrics)[0] == risk


def test_whirl_orbits_use_the_settled_window():
    # 0.6 * 140 rad/s over the 0.1 s settled window = 1.34 orbits; over 0.05 s only 0.67
    assert classify_cage(base(cage_whirl_ratio=0.6, settled_window=[0.9, 1.0])) == "whirling"
    assert classify_cage(base(cage_whirl_ratio=0.6, settled_window=[0.95, 1.0])) == "centred"


def test_risk_thresholds_move_with_the_fields():
    pressed = base(cage_offset_spread=0.2, cage_eps_mean=0.85, land_film_ratio_min=4.0)
    assert risk_level(pressed)[0] == "elevated"
    assert risk_level(pressed, CageClassThresholds(lambda_full_film=5.0))[0] == "high"
    assert classify_cage(pressed, CageClassThresholds(pressed_eps=0.9)) == "centred"
    with pytest.raises(ValueError, match="lambda_boundary"):
        CageClassThresholds(lambda_boundary=3.0, lambda_full_film=3.0)
    assert risk_level(None) == (None, [])


def test_format_arc():
    assert format_arc([5.2, 25.4]) == "5–25°"
    assert format_arc([350.0, 370.0]) == "350–10°"
    assert format_arc([10.0, 370.0]) == "all round"
    assert format_arc(None) == "—"


# --- the command line ---------------------------------------------------------------------

def test_run_and_simulate_print_the_verdict(tmp_path, monkeypatch):
    import bearingsim.pipeline.cli.commands as cli

    direction = np.radians(30.0 + 4.0 * np.sin(2 * math.pi * 3.0 * T))
    summary = _summary(synthetic_run(0.88, direction, T))
    (tmp_path / "simulate").mkdir()
    (tmp_path / "simulate" / "summary.json").write_text(json.dumps(summary))
    monkeypatch.setattr(cli, "_pipeline", lambda *args, **kw: (None, tmp_path, []))  # no solving
    for command in ("simulate", "run"):
        result = CliRunner().invoke(cli.app, [command, "helicopter-b-given-hinge", "--out", str(tmp_path)])
        assert result.exit_code == 0, result.output
        assert f"verdict: {summary['verdict']['text']}" in result.output
        assert "class pressed, risk elevated" in result.output
    assert verdict_lines({"duration": 1.0, "steps": 3}) == ["verdict: no cage in this scene (no cage metrics)"]
    assert verdict_lines(None) == []
    assert "--force" in verdict_lines({"duration": 1.0, "cage_speed_mean": 140.0})[0]  # an old summary
