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


# --- every stack is a bearing the scene allows, or it is counted and left out ------------------
@pytest.mark.parametrize("table, key, allowed", [
    ({"pocket_diameter": {"lower": -1.0, "upper": -0.5}}, "tolerances.pocket_diameter", "allowed lower > -0.00118 [m]"),
    ({"cage_temperature": {"lower": -500.0, "upper": 500.0}}, "tolerances.cage_temperature", "allowed lower > -200 [K]"),
    ({"pocket_diameter": {"sd": 1e-3}}, "tolerances.pocket_diameter", "allowed sd < 0.0003933 [m]"),
])
def test_a_tolerance_range_reaching_impossible_parts_is_refused_up_front(scene, table, key, allowed):
    """The issue's repros: a pocket of -1 .. -0.5 m made P(crushed) 100 %, a cage at -400 °C
    41 %. The allowed end is where the stacks stop being bearings (pocket = ball diameter
    0.01905 m of 0.02023 m drawn; the cage's -100 °C at 100 °C operating)."""
    with pytest.raises(SceneError) as info:
        tol.build_tolerance_spec({"samples": 1000, **table}, scene)
    assert info.value.key == key and allowed in str(info.value)


def test_the_command_refuses_an_impossible_range_with_exit_2(tmp_path):
    from typer.testing import CliRunner

    from bearingsim.pipeline.cli.commands import app

    path = tmp_path / "tol.toml"
    path.write_text("[tolerances]\nsamples = 1000\npocket_diameter = { lower = -1, upper = -0.5 }\n")
    result = CliRunner().invoke(app, ["tolerances", "helicopter-b-given-hinge", "--tolerances", str(path),
                                      "--out", str(tmp_path / "run")])
    assert result.exit_code == 2 and "tolerances.pocket_diameter" in result.stderr
    assert not (tmp_path / "run").exists()


def test_stacks_beyond_three_sd_that_are_no_bearing_are_counted_and_left_out(scene, tmp_path):
    """sd = 0.38 mm on a pocket 1.18 mm wider than the ball: 3.1 sd to the ball, so a few of
    5000 Latin-hypercube stacks (whose extreme strata reach 3.7 sd) have no room for the ball."""
    spec = tol.build_tolerance_spec({"samples": 5000, "seed": 4, "pocket_diameter": {"sd": 3.8e-4}}, scene)
    result = tol.analyse(scene, spec)
    bad = ~result.valid_mask
    assert 0 < bad.sum() < 20 and result.invalid == {"cage.pocket_diameter": int(bad.sum())}
    assert np.all(result.deviations["pocket_diameter"][bad] < -(POCKET - BALL))  # exactly those
    assert np.all(np.isnan(result.margin[bad])) and np.all(result.regime[bad] == tol.INVALID)
    s = tol.summary(result, scene)
    assert s["invalid_stacks"]["count"] == bad.sum() and s["valid_samples"] == 5000 - bad.sum()
    assert sum(p["probability"] for p in s["regime_probability"].values()) == pytest.approx(1.0)
    load_scene("helicopter-b-given-hinge", s["stack_at_p5_overrides"])  # a stack the scene accepts
    tol.write_samples_csv(tmp_path / "s.csv", result)
    rows = (tmp_path / "s.csv").read_text().splitlines()[1:]
    assert sum(r.endswith(",invalid") for r in rows) == bad.sum()


def test_the_stack_check_agrees_with_loading_the_stacks_scene(scene):
    """The fast per-stack validation against its slow twin: each stack's scene loaded in full
    (--set overrides through every check of the scene), over stacks that break several rules."""
    from bearingsim.pipeline.scene.tolerance_stacks import stack_problem, stack_values

    rng = np.random.default_rng(1)
    widths = {"pocket_diameter": 1.5e-3, "cage_outside_diameter": 1.5e-3, "cage_bore_diameter": 1.5e-3,
              "outer_land_diameter": 1.5e-3, "ball_diameter": 1.5e-3, "diametral_clearance": 3e-4,
              "cage_temperature": 300.0, "outer_ring_temperature": 300.0, "moment": 500.0}
    outcomes = set()
    for _ in range(60):
        names = rng.choice(list(widths), size=3, replace=False)
        stack = {str(k): float(rng.uniform(-1, 1) * widths[k]) for k in names}
        fast = stack_problem(scene, stack_values(scene, stack)) is None
        try:
            load_scene("helicopter-b-given-hinge", tol.stack_overrides(scene, stack))
            full = True
        except SceneError:
            full = False
        assert fast == full, stack
        outcomes.add(fast)
    assert outcomes == {True, False}  # both kinds of stack were drawn


def test_each_deviation_is_a_latin_hypercube(scene):
    """One stack in each of n equally likely strata, for uniform and for normal deviations."""
    from scipy.stats import norm

    spec = tol.build_tolerance_spec({"samples": 1000, "seed": 9, "moment": {"lower": -50.0, "upper": 50.0},
                                     "axial": {"sd": 100.0}}, scene)
    dev = tol.sample_deviations(spec)
    n = 1000
    assert np.array_equal(np.sort(np.floor((dev["moment"] + 50.0) / 100.0 * n)), np.arange(n))
    assert np.array_equal(np.sort(np.floor(norm.cdf(dev["axial"] / 100.0) * n)), np.arange(n))
