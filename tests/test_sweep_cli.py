"""`bearingsim sweep` on the command line: the definition from a scene's `[sweep]` table or
`--vary`, errors before anything runs (exit 2), and the plan without running (--dry-run)."""

from __future__ import annotations

from importlib import resources

from typer.testing import CliRunner

from bearingsim.pipeline.cli import app

runner = CliRunner()

SWEEP_TABLE = '''
[sweep]
name = "moment-speed"

[sweep.vary]
"load.moment" = "0:600:3"
"speed.inner_rpm" = [2000, 6000]

[sweep.thresholds]
crushed_spread = 0.4
'''


def scene_with_sweep(tmp_path):
    text = (resources.files("bearingsim.pipeline") / "scenes" / "helicopter-b-given-hinge.toml").read_text(encoding="utf-8")
    path = tmp_path / "with-sweep.toml"
    path.write_text(text + SWEEP_TABLE, encoding="utf-8")
    return path


def test_scene_sweep_table_plans_a_factorial_sweep(tmp_path):
    scene = scene_with_sweep(tmp_path)
    assert runner.invoke(app, ["check", str(scene)]).exit_code == 0  # [sweep] is a valid scene key
    result = runner.invoke(app, ["sweep", str(scene), "--dry-run", "--out", str(tmp_path / "sw")])
    assert result.exit_code == 0, result.output
    assert "6 points" in result.output
    assert not (tmp_path / "sw").exists(), "a dry run writes nothing"


def test_command_line_vary_replaces_the_scene_points(tmp_path):
    scene = scene_with_sweep(tmp_path)
    result = runner.invoke(app, ["sweep", str(scene), "--dry-run", "--vary", "load.moment=100,200",
                                 "--out", str(tmp_path / "sw")])
    assert result.exit_code == 0, result.output
    assert "2 points" in result.output


def test_bad_definitions_exit_2_naming_the_key(tmp_path):
    result = runner.invoke(app, ["sweep", "helicopter-b-given-hinge", "--dry-run", "--vary", "load.moment=0:600"])
    assert result.exit_code == 2 and "start:stop:count" in result.output
    result = runner.invoke(app, ["sweep", "helicopter-b-given-hinge", "--dry-run", "--vary", "bearing.ball_count=0,22"])
    assert result.exit_code == 2 and "bearing.ball_count" in result.output
    result = runner.invoke(app, ["sweep", "helicopter-b-given-hinge", "--dry-run"])
    assert result.exit_code == 2 and "nothing to vary" in result.output
