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
