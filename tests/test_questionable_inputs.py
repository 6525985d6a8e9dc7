"""Inputs judged questionable by a reliability probe, as decided in docs/reliability.md: a UTF-8
byte-order mark is read, a `--set` value with a line break is refused, inch-valued geometry is
flagged like millimetres, `stiffness --speeds` has a limit, and solver hints reach the user
whatever the failure's position ("at the minimum step") with real scene keys."""

from __future__ import annotations

from pathlib import Path

import pytest

from bearingsim.pipeline.scene.load import variant
from typer.testing import CliRunner

from bearingsim.dynamics.multibody.results import IntegrationError, Result
from bearingsim.pipeline.cli.commands import app
from bearingsim.pipeline.console import explain
from bearingsim.pipeline.scene.load import load_scene
from bearingsim.pipeline.scene.schema import SceneError

runner = CliRunner()
SCENE_TEXT = (Path(__file__).parents[1] / "pipeline" / "scenes" / "deep-groove-209.toml").read_text()


def test_a_byte_order_mark_is_read(tmp_path):
    scene = tmp_path / "bom.toml"
    scene.write_bytes(b"\xef\xbb\xbf" + SCENE_TEXT.encode())
    assert runner.invoke(app, ["check", str(scene)]).exit_code == 4  # read: valid, quasi-static only


def test_a_set_value_with_a_line_break_is_refused():
    with pytest.raises(SceneError, match="holds a line break"):
        load_scene("deep-groove-209", ["load.radial=1\n[evil]\nx=1"])


@pytest.mark.parametrize("inches", [0.25, 0.5, 1.0])
def test_inch_ball_diameter_is_flagged(inches):
    """Balls of rolling bearings stay below about 0.1 m; a diameter in inches reads as 0.25-1 m.
    (A whole inch-valued scene fails the geometry checks first; this is the warning behind them.)"""
    import copy
    import dataclasses

    from bearingsim.pipeline.scene.validity import _plausibility

    scene = load_scene("deep-groove-209")
    bearing = copy.copy(scene.bearing)
    object.__setattr__(bearing, "ball_diameter", inches)  # past the geometry checks, which refuse it
    scene = variant(scene, bearing=bearing)
    texts = [f.text for f in _plausibility(scene)]
    assert any("millimetres or inches" in t for t in texts), texts


def test_stiffness_speed_count_is_limited(tmp_path):
    result = runner.invoke(app, ["stiffness", "deep-groove-209", "--speeds", "0:1000:20000", "--out", str(tmp_path / "s")])
    assert result.exit_code == 2 and "at most 1000 per call" in result.stderr
    assert not (tmp_path / "s").exists()


@pytest.mark.parametrize("where", ["at the minimum step", "at the fixed step"])
@pytest.mark.parametrize("failure", [Result.NEWTON_DIVERGED, Result.NEWTON_MAX_ITER])
def test_integration_hints_name_the_first_step(failure, where):
    text = explain(IntegrationError(0.0, 1e-6, f"{failure.value} {where}", failure.hint))
    assert "solver.first_step" in text and "K_t" not in text  # the console's hint, in scene keys


def test_a_changed_quasistatic_says_it_removed_the_simulation(tmp_path):
    out = tmp_path / "run"
    short = ["--set", "solver.duration=0.002", "--set", "output.figures=false"]
    assert runner.invoke(app, ["simulate", "helicopter-b-given-hinge", "--out", str(out), *short]).exit_code == 0
    result = runner.invoke(app, ["quasistatic", "helicopter-b-given-hinge", "--out", str(out), *short,
                                 "--set", "load.moment=200"])
    assert result.exit_code == 0 and "removed simulate/" in result.stderr
    assert not (out / "simulate").exists()


def test_a_negative_thrust_is_said_to_be_mirrored():
    result = runner.invoke(app, ["check", "helicopter-b-given-hinge", "--set", "load.axial=-34000"])
    assert result.exit_code == 0 and "thrust along -z" in result.stderr
    assert "thrust along -z" not in runner.invoke(app, ["check", "helicopter-b-given-hinge"]).stderr


# --- the questionable cases of the second reliability probe (docs/reliability.md) ---------------
def test_duplicate_sweep_values_are_one_point():
    """100, 100.0 and 1e2 (or -0.0, 0.0 and 0) are one value for the stages' keys: one point."""
    from bearingsim.pipeline.scene.sweep_section import build_sweep_section
    from bearingsim.pipeline.sweep.points import expand

    section = build_sweep_section({"vary": {"load.moment": [100, 100.0, 1e2, 0, -0.0, 0.0, 200]}})
    points = expand(section)
    assert [p.overrides for p in points] == [(("load.moment", 100),), (("load.moment", 0),), (("load.moment", 200),)]


def test_a_run_into_a_sweep_point_folder_is_refused(tmp_path):
    point = tmp_path / "sweep" / "points" / "0123456789ab"
    point.mkdir(parents=True)
    (point / ".bearingsim-run").write_text("run\n")
    (point / "point.json").write_text('{"status": "done"}')
    result = runner.invoke(app, ["quasistatic", "deep-groove-209", "--out", str(point)])
    assert result.exit_code == 2 and "is a point of a sweep" in " ".join(result.stderr.split())
    assert sorted(p.name for p in point.iterdir()) == [".bearingsim-run", "point.json"]


def test_a_second_sweep_on_one_folder_is_refused(tmp_path):
    from bearingsim.pipeline.machine.file_lock import exclusive_lock

    out = tmp_path / "sweep"
    out.mkdir()
    (out / ".bearingsim-sweep").write_text("sweep\n")
    with exclusive_lock(out / ".lock"):
        result = runner.invoke(app, ["sweep", "deep-groove-209", "--vary", "load.radial=1000,2000",
                                     "--out", str(out)])
    assert result.exit_code == 1 and "another bearingsim sweep is writing" in " ".join(result.stderr.split())


def test_a_stage_store_that_is_a_folder_of_yours_is_refused(tmp_path):
    """`--store /` would fill the root with stage folders: a store must be new, empty or a
    store bearingsim marked (a folder of the user's stands in for / here)."""
    mine = tmp_path / "mine"
    mine.mkdir()
    (mine / "notes.txt").write_text("mine\n")
    result = runner.invoke(app, ["sweep", "deep-groove-209", "--vary", "load.radial=1000,2000",
                                 "--out", str(tmp_path / "sweep"), "--store", str(mine)])
    assert result.exit_code == 2 and "not a bearingsim stage store" in " ".join(result.stderr.split())
    assert sorted(p.name for p in mine.iterdir()) == ["notes.txt"]


def test_an_unusable_store_in_a_sweep_names_its_option(tmp_path, monkeypatch):
    from bearingsim.pipeline.staging.runner import STORE_ADVICE, Stage, run_stages

    stage = Stage("toy", (), lambda s: True, lambda s: {}, lambda ctx: {}, "a stage")
    afile = tmp_path / "afile"
    afile.write_text("x")
    token = STORE_ADVICE.set("give the sweep a writable stage store with --store (store= in Python)")
    try:
        outcome = run_stages(load_scene("deep-groove-209"), tmp_path / "run", [stage], ["toy"], store=afile)[0]
    finally:
        STORE_ADVICE.reset(token)
    assert "--store" in outcome.warnings[0]["message"] and "--no-store" not in outcome.warnings[0]["message"]


def test_a_large_sweep_says_it_is_validating(monkeypatch):
    from bearingsim.pipeline.sweep import driver

    monkeypatch.setattr(driver, "PLAN_PROGRESS_POINTS", 2)
    heard = []
    driver.plan_sweep("deep-groove-209", vary=["load.radial=1000:4000:4"], progress=heard.append)
    assert heard == ["validating the scene of every point: 0 of 4", "validating the scene of every point: 2 of 4"]


def test_stiffness_messages_name_the_command_line_option(tmp_path):
    mine = tmp_path / "mine"
    mine.mkdir()
    (mine / "notes.txt").write_text("mine\n")
    result = runner.invoke(app, ["stiffness", "helicopter-b-given-hinge", "--out", str(mine)])
    assert result.exit_code == 2 and f"--out {mine}" in result.stderr and "run_dir=" not in result.stderr
    huge = runner.invoke(app, ["stiffness", "helicopter-b-given-hinge", "--speeds", "1e308", "--out", str(tmp_path / "s")])
    assert huge.exit_code == 2 and "speed.inner_rpm" in huge.stderr


def test_a_near_conforming_groove_is_named_instead_of_the_load(tmp_path):
    result = runner.invoke(app, ["quasistatic", "deep-groove-209", "--out", str(tmp_path),
                                 "--set", "bearing.inner_conformity=0.5000000001"])
    assert result.exit_code == 2 and "bearing.inner_conformity = 0.5000000001" in " ".join(result.stderr.split())


def test_sub_nanometre_part_lengths_are_flagged():
    result = runner.invoke(app, ["check", "helicopter-b-given-hinge", "--set", "cage.land_roughness=1e-20",
                                 "--set", "bearing.width=1e-12"])
    text = " ".join(result.stderr.split())
    assert result.exit_code == 0 and "cage.land_roughness: 1e-20 m is smaller than a few atoms" in text
    assert "bearing.width: 1e-12 m is smaller than a few atoms" in text


def test_an_empty_scene_argument_is_named():
    result = runner.invoke(app, ["run", ""])
    assert result.exit_code == 2 and "the scene argument is empty" in result.stderr


def test_tolerance_values_are_shown_as_toml(tmp_path):
    path = tmp_path / "tol.toml"
    path.write_text("[tolerances]\nsamples = true\nmoment = { sd = 1.0 }\n")
    result = runner.invoke(app, ["tolerances", "helicopter-b-given-hinge", "--tolerances", str(path)])
    assert result.exit_code == 2 and "tolerances.samples: true is out of range" in result.stderr
