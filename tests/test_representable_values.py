"""Every number a scene accepts is one the model computes with (docs/reliability.md): an
integer too large for a float, a value beyond 1e30 or a non-zero one below 1e-30 in size, an
integer beyond 64 bits are refused by `check` with the key, the value, the range and the unit,
never an OverflowError or ZeroDivisionError traceback; and a value inside the window that the
solver cannot carry ends with the solver's message (exit 1), not a raw exception or warning."""

from __future__ import annotations

import pytest
from typer.testing import CliRunner

from bearingsim.pipeline.cli.commands import app
from bearingsim.pipeline.scene.load import load_scene
from bearingsim.pipeline.scene.schema import SceneError

runner = CliRunner()
SCENE = "helicopter-b-given-hinge"
HUGE = "9" * 400  # a TOML integer no float holds


@pytest.mark.parametrize("key, value, shown, unit", [
    ("load.moment", HUGE, "an integer of 400 digits", "[N.m]"),
    ("load.moment", "1e308", "1e+308", "[N.m]"),
    ("load.axial", "-1e308", "-1e+308", "[N]"),
    ("materials.ball.density", "1e308", "1e+308", "[kg/m^3]"),
    ("materials.ball.youngs_modulus", "1e-300", "1e-300", "[Pa]"),
    ("cage.land_roughness", "1e-300", "1e-300", "[m]"),
    ("bearing.width", "1e-300", "1e-300", "[m]"),
    ("hinge.translational", "[1e300, 1e9, 1e9]", "1e+300", "[N/m]"),
    ("speed.inner_rpm", "1e100", "1e+100", "[rev/min]"),
])
def test_values_the_model_cannot_compute_with_are_refused_by_check(key, value, shown, unit):
    result = runner.invoke(app, ["check", SCENE, "--set", f"{key}={value}"])
    assert result.exit_code == 2, result.output
    line = result.stderr.replace("\n", " ")
    assert f"{key}" in line and f"{shown} is out of range: allowed" in line and "1e-30 <= |value| <= 1e30" in line
    assert unit in line and "Traceback" not in result.output


def test_load_scene_raises_scene_error_for_a_huge_integer():
    with pytest.raises(SceneError) as info:
        load_scene(SCENE, [f"load.moment={HUGE}"])
    assert info.value.key == "load.moment"


@pytest.mark.parametrize("where", ["--set", "file"])
def test_an_integer_longer_than_python_reads_is_refused(where, tmp_path):
    digits = "9" * 5000
    if where == "--set":
        argv = ["check", SCENE, "--set", f"load.moment={digits}"]
    else:
        path = tmp_path / "scene.toml"
        path.write_text(f"name = 'x'\n[load]\nmoment = {digits}\n")
        argv = ["check", str(path)]
    result = runner.invoke(app, argv)
    text = result.stderr.replace("\n", " ")
    assert result.exit_code == 2 and ("5000 digits" in text or "4300 digits" in text), result.output


def test_an_integer_beyond_64_bits_is_refused():
    result = runner.invoke(app, ["check", SCENE, "--set", f"solver.max_newton_iter={2**70}"])
    assert result.exit_code == 2 and "solver.max_newton_iter" in result.stderr
    assert "at most 2**63 - 1" in result.stderr.replace("\n", " ")


def test_zero_stays_allowed_where_the_key_allows_it():
    result = runner.invoke(app, ["check", SCENE, "--set", "load.moment=0", "--set", "load.axial=-0.0"])
    assert result.exit_code == 0, result.output


def test_a_load_inside_the_window_the_bearing_cannot_carry_fails_with_a_message(tmp_path):
    """1e29 N.m is a number the model computes with, and no bearing carries it: the solver
    says so (exit 1, README exit codes) and names the load keys."""
    result = runner.invoke(app, ["quasistatic", SCENE, "--out", str(tmp_path), "--set", "load.moment=1e29"])
    assert result.exit_code == 1, result.output
    assert "load" in result.stderr and "Traceback" not in result.output
    assert "RuntimeWarning" not in result.output and "LinAlgError" not in result.output
