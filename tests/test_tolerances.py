"""Crush probability over tolerance stacks (docs/model.md §10.2): a known answer, the surrogate
against full quasi-static screens, reproducibility, and the [tolerances] table's errors."""

from __future__ import annotations

import numpy as np
import pytest

from bearingsim.pipeline.quasistatic import tolerances as tol
from bearingsim.pipeline.scene.load import load_scene
from bearingsim.pipeline.scene.schema import SceneError

# Sources of the typed numbers: Table 1 of the reference paper (docs/model.md §2) for the
# dimensions; AISI 52100 11.9e-6 1/K and silicon bronze C65500 18.0e-6 1/K (test_operating_clearances).
ALPHA_STEEL, ALPHA_BRONZE = 11.9e-6, 18.0e-6
LAND_O, CAGE_OD, POCKET, BALL = 0.166, 0.16542, 0.02023, 0.01905


@pytest.fixture(scope="module")
def scene():
    return load_scene("helicopter-b-given-hinge")


def test_one_uniform_tolerance_gives_the_share_beyond_the_closed_form_threshold(scene):
    """Cage OD deviation uniform on [0, 400] µm at 100 °C: crushed where the guide clearance
    1/2 (d_land f_o - (d_cage + delta) f_c) falls below e_req = s1 - c_p/2 (M.116, M.121), so
    P(crushed) = (400 µm - delta*) / 400 µm with delta* = (d_land f_o - 2 e_req)/f_c - d_cage."""
    from bearingsim.pipeline.stages.quasistatic import cage_screen, solve

    s1 = cage_screen(scene, solve(scene)).first_harmonic  # the excursion: an input here, not under test
    f_steel, f_bronze = 1 + ALPHA_STEEL * 80.0, 1 + ALPHA_BRONZE * 80.0
    c_p = POCKET * f_bronze - BALL * f_steel
    e_req = s1 - 0.5 * c_p
    delta_star = (LAND_O * f_steel - 2.0 * e_req) / f_bronze - CAGE_OD
    upper = 400e-6
    expected = (upper - delta_star) / upper
    spec = tol.build_tolerance_spec({"samples": 20000, "seed": 3,
                                     "cage_outside_diameter": {"lower": 0.0, "upper": upper}}, scene)
    result = tol.analyse(scene, spec)
    p = float(np.mean(result.regime == 2))
    se = np.sqrt(expected * (1 - expected) / 20000)
    assert 0.2 < expected < 0.8
    assert abs(p - expected) < 4 * se


def test_surrogate_against_full_screen(scene):
    """Stacks with load and ring-temperature deviations, each rerun as a scene through the
    quasi-static solve and the screen: the sampled margin agrees within 0.01."""
    from bearingsim.pipeline.stages.quasistatic import cage_screen, solve

    spec = tol.build_tolerance_spec({
        "samples": 200, "seed": 11,
        "moment": {"sd": 30.0}, "inner_ring_temperature": {"lower": -10.0, "upper": 10.0},
        "outer_ring_temperature": {"lower": -10.0, "upper": 10.0}, "pocket_diameter": {"sd": 10e-6},
        "cage_bore_diameter": {"lower": -30e-6, "upper": 30e-6}}, scene)
    result = tol.analyse(scene, spec)
    for k in (0, 57, 123):
        stack = {name: float(v[k]) for name, v in result.deviations.items()}
        full = load_scene("helicopter-b-given-hinge", tol.stack_overrides(scene, stack))
        screen = cage_screen(full, solve(full))
        assert result.margin[k] == pytest.approx(screen.crush_margin, abs=0.01)


def test_sampling_is_reproducible_from_its_seed(scene):
    spec = tol.build_tolerance_spec({"samples": 500, "seed": 5, "pocket_diameter": {"sd": 10e-6},
                                     "cage_temperature": {"lower": 0.0, "upper": 10.0}}, scene)
    a, b = tol.analyse(scene, spec), tol.analyse(scene, spec)
    c = tol.analyse(scene, spec, seed=6)
    assert np.array_equal(a.margin, b.margin) and not np.array_equal(a.margin, c.margin)
    # adding a quantity leaves the streams of the others as they were
    more = tol.build_tolerance_spec({"samples": 500, "seed": 5, "pocket_diameter": {"sd": 10e-6},
                                     "cage_temperature": {"lower": 0.0, "upper": 10.0},
                                     "outer_land_diameter": {"sd": 5e-6}}, scene)
    assert np.array_equal(tol.sample_deviations(more)["pocket_diameter"], a.deviations["pocket_diameter"])


def test_summary_ranks_the_driver_that_dominates(scene):
    spec = tol.build_tolerance_spec({"samples": 5000, "seed": 2, "pocket_diameter": {"sd": 40e-6},
                                     "outer_land_diameter": {"sd": 2e-6}}, scene)
    s = tol.summary(tol.analyse(scene, spec), scene)
    assert s["drivers"][0]["quantity"] == "pocket_diameter" and s["drivers"][0]["spearman"] > 0.9
    assert sum(p["probability"] for p in s["regime_probability"].values()) == pytest.approx(1.0)
    assert s["margin_percentiles"]["p5"] < s["margin_percentiles"]["p50"] < s["margin_percentiles"]["p95"]


@pytest.mark.parametrize("table, match", [
    ({"pocket_size": {"sd": 1e-6}}, r"tolerances.pocket_size: unknown quantity"),
    ({"pocket_diameter": {"lower": 1e-6, "upper": -1e-6}}, r"lower = 1e-06 must be smaller than upper.*\[m\]"),
    ({"moment": {"sd": -1.0}}, r"tolerances.moment.sd.*allowed > 0 \[N.m\]"),
    ({"samples": 10, "moment": {"sd": 1.0}}, r"tolerances.samples.*100 to"),
    ({"moment": {"mean": 1.0}}, r"give lower and upper .* or sd alone"),
    ({"samples": 1000}, r"no quantity to vary"),
])
def test_bad_tolerance_tables_name_key_range_and_unit(table, match):
    with pytest.raises(SceneError, match=match):
        tol.build_tolerance_spec(table)


def test_scene_tolerances_are_validated_on_load():
    with pytest.raises(SceneError, match="tolerances.moment"):
        load_scene("helicopter-b-given-hinge", ["tolerances.moment={sd = 0.0}"])
