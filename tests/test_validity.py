"""The physical-validity layer (pipeline.scene.validity): scene checks before any solve, result checks
after it, and the command line's answers to the cases of the issue "Never silently wrong".

Reference numbers: the 209 bearing of deep-groove-209 (Harris & Kotzalas, Rolling Bearing
Analysis, 5th ed.) has D = 12.7 mm, f_i = f_o = 0.52, so A = (0.52 + 0.52 - 1) D = 0.508 mm
and the clearance at which the free contact angle acos(1 - P_d/2A) reaches 90° is 2A = 1.016 mm.
"""

from __future__ import annotations

import copy
import json
import math

import pytest
from typer.testing import CliRunner

from bearingsim.pipeline.staging import result_checks
from bearingsim.pipeline.scene import validity
from bearingsim.pipeline.cli.commands import app
from bearingsim.pipeline.scene.load import load_scene, read_scene_table, resolve
from bearingsim.pipeline.scene.schema import SceneError

runner = CliRunner()


def scene_with(name: str, **sets):
    return load_scene(name, [f"{k}={v}" for k, v in sets.items()])


def keys(findings, level=None):
    return [f.key for f in findings if level is None or f.level == level]


# --- before the solve: geometry ------------------------------------------------------------
def test_clearance_limit_is_twice_the_curvature_centre_distance():
    A = 0.04 * 0.0127  # (f_i + f_o - 1) D
    ok = scene_with("deep-groove-209", **{"bearing.diametral_clearance": 0.999 * 2 * A})
    assert math.degrees(ok.bearing.free_contact_angle) < 90.0
    with pytest.raises(SceneError) as info:
        scene_with("deep-groove-209", **{"bearing.diametral_clearance": 1.001 * 2 * A})
    text = str(info.value)
    assert text.startswith("bearing.diametral_clearance:") and "allowed: diametral clearance < 0.001016 m" in text


def test_issue_case_clearance_0_0012_is_refused_before_solving(tmp_path):
    """Issue case 1a: contact angle 180° and loads on the wrong side, reported as converged."""
    out = tmp_path / "run"
    result = runner.invoke(app, ["quasistatic", "deep-groove-209", "--set", "bearing.diametral_clearance=0.0012",
                                 "--out", str(out)])
    assert result.exit_code == 2
    assert "bearing.diametral_clearance: 0.0012 m" in result.stderr and "[m]" in result.stderr
    assert not out.exists()  # refused before anything was written


def test_form1_clearance_names_the_groove_keys():
    table, _ = read_scene_table("helicopter-b-given-hinge")
    table = copy.deepcopy(table)
    table["bearing"]["outer_groove_center_diameter"] = 0.1586  # play 1.418 mm > 2A = 1.218 mm
    with pytest.raises(SceneError, match="bearing.outer_groove_center_diameter"):
        resolve(table)


def test_the_lands_bound_the_clearance_before_90_degrees():
    """helicopter-b: lands at 64.5° (inner, 150 mm) and 74.9° (outer, 166 mm); A = 0.609 mm."""
    b = load_scene("helicopter-b-given-hinge").bearing
    theta = validity._land_angle(b, "inner")
    assert math.degrees(theta) == pytest.approx(64.49, abs=0.01)  # the solver's number (fuzz log)
    limit = 2 * b.curvature_center_distance * (1 - math.cos(theta))
    table = copy.deepcopy(read_scene_table("helicopter-b-given-hinge")[0])
    table["bearing"]["outer_groove_center_diameter"] += 1.01 * (limit - b.diametral_clearance)
    with pytest.raises(SceneError, match="inner land at 64.5"):
        resolve(table)


def test_a_land_outside_its_ring_is_refused():
    with pytest.raises(SceneError, match="bearing.inner_shoulder_diameter"):
        scene_with("helicopter-b-given-hinge", **{"bearing.inner_shoulder_diameter": 0.159})


def test_cage_outside_the_bearing_is_refused_with_the_allowed_range():
    """Issue case 1d: cage.mean_diameter = 0.5 m in a 158 mm bearing."""
    with pytest.raises(SceneError) as info:
        scene_with("helicopter-b-given-hinge", **{"cage.mean_diameter": 0.5, "cage.guidance": "'inner'"})
    text = str(info.value)
    assert text.startswith("cage.mean_diameter: 0.5 m puts the cage outside the bearing")
    # bore > inner land 150 mm and outside < outer land 166 mm with t = 7.42 mm
    assert "allowed: 0.1574 m < mean_diameter < 0.1586 m" in text and text.endswith("[m]")


def test_simulate_refuses_a_cage_narrower_than_the_groove_at_its_land():
    """The cage of case b overlaps the outer lands only beyond the groove's opening there:
    2 sqrt(r_o^2 - (D_land/2 - d_oc/2)^2) with r_o = 9.906 mm, D_land = 166 mm and
    d_oc = 157.3 mm (the scene's Table 1 values) is 17.80 mm; a journal of no length
    stopped `simulate` after `check` had passed it."""
    opening = 2.0 * math.sqrt(0.009906**2 - (0.083 - 0.07865) ** 2)
    assert opening == pytest.approx(0.0178, abs=5e-6)
    narrow = scene_with("helicopter-b-given-hinge", **{"cage.width": 0.017})
    [finding] = validity.run_findings(narrow, {"simulate"})
    assert finding.level == "error" and finding.key == "cage.width"
    assert finding.text.startswith("cage.width: 0.017 m does not reach the outer race's lands: the groove is "
                                   "0.0178 m wide where it meets the land (bearing.outer_shoulder_diameter)")
    assert finding.text.endswith("or give cage.land_length [m]")
    assert validity.run_findings(narrow, {"quasistatic"}) == []  # only the journal needs the overlap
    for fix in ({"cage.land_length": 0.002}, {"physics.cage_race": "'none'"}):
        assert validity.run_findings(scene_with("helicopter-b-given-hinge", **{"cage.width": 0.017, **fix}),
                                     {"simulate"}) == []
    wide = scene_with("helicopter-b-given-hinge", **{"cage.width": 0.0185})
    assert validity.run_findings(wide, {"simulate"}) == []
    assert wide.nominal.cage.guide_land_length(wide.nominal.bearing) == pytest.approx(0.0185 - opening, rel=1e-9)


def test_a_cage_without_its_guiding_land_is_refused():
    table = copy.deepcopy(read_scene_table("helicopter-b-given-hinge")[0])
    del table["bearing"]["outer_shoulder_diameter"]
    with pytest.raises(SceneError, match="bearing.outer_shoulder_diameter: required with a cage"):
        resolve(table)


def test_simulate_refuses_an_inner_guided_cage_but_quasistatic_runs_it(tmp_path):
    """Issue case 1d: the dynamics always runs the journal against the outer race."""
    args = ["--set", "cage.guidance=inner", "--set", "cage.mean_diameter=0.158", "--set", "solver.duration=0.002"]
    result = runner.invoke(app, ["simulate", "helicopter-b-given-hinge", "--out", str(tmp_path / "s"), *args])
    assert result.exit_code == 2 and "cage.guidance: 'inner' is not modelled by the dynamic stage" in result.stderr
    assert not (tmp_path / "s").exists()
    check = runner.invoke(app, ["check", "helicopter-b-given-hinge", *args])
    assert check.exit_code == 0 and check.stderr.startswith("note: simulate and run would refuse")


# --- before the solve: resources -----------------------------------------------------------
def test_too_few_samples_is_refused_before_any_stage(tmp_path):
    """Issue case 3: duration 1 ms sampled every 10 ms gave 1e302, NaN and duration 0."""
    out = tmp_path / "run"
    result = runner.invoke(app, ["simulate", "helicopter-b-given-hinge", "--set", "solver.duration=0.001",
                                 "--set", "output.sample_interval=0.01", "--out", str(out)])
    assert result.exit_code == 2
    assert "output.sample_interval: 0.01 s gives 0 samples" in result.stderr
    assert "allowed <= duration / 20 = 5e-05 [s]" in result.stderr
    assert not out.exists()


@pytest.mark.parametrize("setting, key", [("solver.duration=1e9", "solver.duration"),
                                          ("output.sample_interval=1e-12", "output.sample_interval")])
def test_runs_too_large_for_memory_or_time_are_refused_up_front(setting, key, tmp_path):
    """Issue case 5: MemoryError after the quasi-static stage had run."""
    out = tmp_path / "run"
    result = runner.invoke(app, ["simulate", "helicopter-b-given-hinge", "--set", setting, "--out", str(out)])
    assert result.exit_code == 2 and f"error: scene: {key}:" in result.stderr, result.output
    assert "Traceback" not in result.output and not out.exists()


def test_memory_estimate_scales_with_samples():
    s = load_scene("helicopter-b-given-hinge")
    # 22 balls + cage: 2 + 2 (6*22 + 12) + 16 + 15*22 = 636 doubles a sample, three copies
    assert validity.sample_bytes(s) == 8 * 636 * 3
    assert validity.sample_count(s) == int(0.8 / 1e-5) + 2


# --- before the solve: units ---------------------------------------------------------------
def test_a_scene_in_millimetres_is_flagged_by_check(tmp_path):
    """Issue case 7: a 12.7 m ball (2.8e10 g) passed `check` silently."""
    table, _ = read_scene_table("deep-groove-209")
    for key in ("ball_diameter", "pitch_diameter", "diametral_clearance"):
        table["bearing"][key] *= 1000.0
    import tomli_w

    path = tmp_path / "mm.toml"
    path.write_text(tomli_w.dumps(table))
    result = runner.invoke(app, ["check", str(path)])
    assert result.exit_code == 0
    assert "warning: bearing.ball_diameter: 12.7 m" in result.stderr and "millimetres" in result.stderr


@pytest.mark.parametrize("setting, key", [
    ("materials.ball.youngs_modulus=207.7", "materials.ball.youngs_modulus"),
    ("materials.race.density=7.85", "materials.race.density"),
    ("speed.inner_rpm=3e6", "speed.inner_rpm"),
    ("load.moment=430000", "load.moment"),
    ("lubricant.temperature_degC=300", "lubricant.temperature_degC"),  # hotter than oils survive
    ("physics.min_film=0.05", "physics.min_film"),  # 0.05 µm typed as m
    ("lubricant.density=1.003", "lubricant.density"),  # g/cm^3
    ("lubricant.eyring_stress=5", "lubricant.eyring_stress"),  # MPa
])
def test_values_in_the_wrong_unit_are_warned(setting, key):
    s = load_scene("helicopter-b-given-hinge", [setting])
    assert key in keys(validity.scene_findings(s), "warning")


def test_builtin_scenes_have_no_findings():
    from bearingsim.pipeline.scene.load import builtin_scene_names

    for name in builtin_scene_names():
        assert validity.scene_findings(load_scene(name)) == [], name


# --- after the solve ---------------------------------------------------------------------------
def payload(pressure=2e9, angle=0.4, margin=1e-3, displacement=1e-5, balls=9):
    ball = {"azimuth": 0.0, "inner_load": 1000.0, "outer_load": 1000.0, "inner_contact_angle": angle,
            "outer_contact_angle": -angle, "max_pressure_inner": pressure, "max_pressure_outer": pressure / 2,
            "truncation_margin_inner": margin, "truncation_margin_outer": None}
    return {"inner_race": {"displacement": [displacement, 0.0, 0.0], "tilt": [0.0, 0.0]},
            "balls": [dict(ball) for _ in range(balls)], "converged": True, "warnings": []}


def test_result_checks_against_the_contact_model():
    s = load_scene("deep-groove-209")
    assert result_checks.quasistatic_findings(s, payload()) == []
    # ISO 76: 4.2 GPa is the static-rating pressure; 10 GPa the fully plastic limit of the steel
    warned = result_checks.quasistatic_findings(s, payload(pressure=5e9))
    assert [f.level for f in warned] == ["warning"] and "ISO 76" in warned[0].message
    # the load that brings p_max (∝ Q^(1/3)) back to 4.2 GPa: 8900 N x (4.2/5)^3 = 5275 N
    assert "load.radial <= 5275" in warned[0].message
    assert [f.level for f in result_checks.quasistatic_findings(s, payload(pressure=12e9))] == ["error"]
    assert [f.level for f in result_checks.quasistatic_findings(s, payload(angle=math.radians(100)))] == ["error"]
    assert [f.level for f in result_checks.quasistatic_findings(s, payload(margin=-1e-4))] == ["warning"]
    assert [f.level for f in result_checks.quasistatic_findings(s, payload(displacement=0.01))] == ["error"]
    broken = payload()
    broken["inner_race"]["tilt"] = [None, 0.0]
    assert [f.level for f in result_checks.quasistatic_findings(s, broken)] == ["error"]


def test_issue_case_radial_1e9_is_refused_with_the_reason(tmp_path):
    """Issue case 1b: 75.9 mm displacement and 117 GPa reported as converged."""
    out = tmp_path / "run"
    result = runner.invoke(app, ["quasistatic", "deep-groove-209", "--set", "load.radial=1e9", "--out", str(out)])
    assert result.exit_code == 2, result.output
    err = result.stderr
    assert "error: scene: load.radial: 1e+09 N pushes ball" in err and "out of its groove" in err
    assert "GPa" in err and "allowed" in err
    assert not (out / "quasistatic").exists()  # the meaningless result is not kept (nor cached)
    assert "outside the model's validity" in (out / "run.log").read_text()


def test_issue_case_high_moment_warns_on_console_log_and_json(tmp_path):
    """Issue case 1c: 28 ellipse truncations up to 7.9 mm, silent on console and in run.log."""
    out = tmp_path / "run"
    result = runner.invoke(app, ["quasistatic", "helicopter-b-given-hinge", "--set", "load.moment=50000",
                                 "--out", str(out), "--json"])
    assert result.exit_code == 0, result.output
    assert "warning: quasistatic: load.moment" in result.stderr and "truncates" in result.stderr
    log = (out / "run.log").read_text()
    assert "WARNING stage quasistatic: load.moment" in log and "contact pressure" in log
    data = json.loads(result.stdout)
    assert {f["level"] for f in data["validity"]} == {"warning"}
    assert any("truncates" in f["message"] for f in data["validity"])
    assert any("4.2 GPa" in f["message"] for f in data["validity"])
    # a cached doubtful result says so again
    again = runner.invoke(app, ["quasistatic", "helicopter-b-given-hinge", "--set", "load.moment=50000",
                                "--out", str(out)])
    assert again.exit_code == 0 and "cached" in again.stderr and "truncates" in again.stderr


def test_absurd_summary_values_are_nulled_and_flagged(tmp_path):
    s = load_scene("helicopter-b-given-hinge")
    summary = {"duration": 0.8, "cage_speed_mean": 1e302, "energy": {"drive": 1.0}, "list": [1.0, -1e200]}
    findings = result_checks.simulation_findings(s, summary)
    assert [f.level for f in findings] == ["warning"]
    assert "cage_speed_mean" in findings[0].message and "list[1]" in findings[0].message
    (tmp_path / "summary.json").write_text(json.dumps(summary))
    result_checks.annotate("simulate", tmp_path, findings)
    data = json.loads((tmp_path / "summary.json").read_text())
    assert data["cage_speed_mean"] is None and data["list"] == [1.0, None] and data["validity"]


def test_json_writer_never_writes_nan_or_infinity(tmp_path):
    """Issue case 3: a NaN made summary.json invalid JSON."""
    import numpy as np

    from bearingsim.pipeline.staging.artefacts import atomic_write_json

    atomic_write_json(tmp_path / "x.json", {"a": float("nan"), "b": [np.inf, -np.inf, 1.5],
                                             "c": np.array([np.nan, 2.0]), "d": np.float64("nan")})

    def reject(name):
        raise ValueError(name)

    data = json.loads((tmp_path / "x.json").read_text(), parse_constant=reject)
    assert data == {"a": None, "b": [None, None, 1.5], "c": [None, 2.0], "d": None}


def test_crush_screen_is_flagged_when_balls_sit_in_the_unloaded_zone():
    """The screen assumes every ball rolls at its own pure-rolling speed; a ball under a tenth of the
    mean load cannot hold it (the unloaded zone of a radial load), so the screen only bounds the push."""
    s = load_scene("deep-groove-209")
    loaded = payload()
    loaded["cage_screen"] = {"regime": "pressed"}
    assert result_checks.quasistatic_findings(s, loaded) == []
    zone = copy.deepcopy(loaded)
    for ball in zone["balls"][:3]:
        ball["inner_load"] = ball["outer_load"] = 50.0  # mean (3 x 50 + 6 x 1000) / 9 = 683 N; 50 < 68.3
    warned = result_checks.quasistatic_findings(s, zone)
    assert [f.level for f in warned] == ["warning"]
    assert "3 of 9 balls in the unloaded zone" in warned[0].message and "'pressed'" in warned[0].message
    del zone["cage_screen"]  # no cage, no screen: nothing to flag
    assert result_checks.quasistatic_findings(s, zone) == []


def test_the_built_in_lubricant_and_film_floor_are_not_warned():
    """The plausibility ranges hold the reference oil (NATO O-156) and the default film floor."""
    s = load_scene("helicopter-b-given-hinge")
    assert not {k for k in keys(validity.scene_findings(s), "warning")
                if k.startswith(("lubricant.", "physics."))}


def test_a_ball_in_millimetres_is_named_in_the_groove_error():
    """One key typed in mm trips the groove check first; the message says what is likely wrong."""
    from bearingsim.pipeline.scene.schema import SceneError

    with pytest.raises(SceneError, match=r"ball_diameter = 19.05 m would be a ball of 19.05 metres.*not millimetres"):
        load_scene("helicopter-b-given-hinge", ["bearing.ball_diameter=19.05"])
    # a catalogue-form scene (pitch diameter and conformities): no groove radius to trip, the
    # groove bottom goes negative; the message names the keys of that form, and the likely slip
    with pytest.raises(SceneError, match=r"or ball_diameter against pitch_diameter \(form 2\); ball_diameter = "
                                         r"12\.7 m would be a ball of 12\.7 metres"):
        load_scene("deep-groove-209", ["bearing.ball_diameter=12.7"])
