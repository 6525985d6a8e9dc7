"""`bearingsim sweep` on the command line: the definition from a scene's `[sweep]` table or
`--vary`, errors before anything runs (exit 2), and the plan without running (--dry-run)."""

from __future__ import annotations

from importlib import resources

from typer.testing import CliRunner

from bearingsim.pipeline.cli.commands import app

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


def _finish(request, status="done"):
    """Leave the record a finished point writes (and its summary), as a run would."""
    import json
    from pathlib import Path

    run_dir = Path(request.run_dir)
    (run_dir / "simulate").mkdir(parents=True)
    (run_dir / "simulate" / "summary.json").write_text(json.dumps({"duration": 0.1, "warnings": []}))
    (run_dir / "point.json").write_text(json.dumps({"status": status, "scene_hash": request.scene_hash,
                                                    "summary": {"duration": 0.1, "warnings": []}}))


def test_dry_run_shows_points_finished_before(tmp_path):
    """A dry run plans a resume: points an earlier run finished are shown as such, not pending."""
    from bearingsim.pipeline.sweep.driver import plan_sweep

    args = ["--vary", "load.moment=100,200", "--out", str(tmp_path / "sw")]
    plan = plan_sweep("helicopter-b-given-hinge", [], ["load.moment=100,200"], out=tmp_path / "sw")
    _finish(plan.requests[0])
    result = runner.invoke(app, ["sweep", "helicopter-b-given-hinge", "--dry-run", *args])
    assert result.exit_code == 0, result.output
    assert "2 points, 1 finished in an earlier run (kept), 1 to run" in result.stderr
    statuses = [line.split()[2] for line in result.stdout.splitlines() if line.split()[:1] in (
        [plan.points[0].id], [plan.points[1].id])]
    assert statuses == ["done", "pending"]


def test_a_sweep_of_other_points_in_the_same_folder_is_announced(tmp_path):
    """Running another plan in a sweep folder replaces its table and map: said before it runs."""
    from bearingsim.pipeline.sweep.driver import _write_plan, plan_sweep, replaced_sweep

    first = plan_sweep("helicopter-b-given-hinge", [], ["load.moment=0:600:7"], out=tmp_path / "sw")
    (tmp_path / "sw").mkdir()
    _write_plan(first)
    assert replaced_sweep(first) is None  # the same plan again resumes it
    second = plan_sweep("helicopter-b-given-hinge", [], ["load.moment=0,100"], out=tmp_path / "sw")
    note = replaced_sweep(second)
    assert note.startswith(f"{tmp_path / 'sw'}/ holds another sweep (7 points); this one replaces its results")
    result = runner.invoke(app, ["sweep", "helicopter-b-given-hinge", "--dry-run", "--vary", "load.moment=0,100",
                                 "--out", str(tmp_path / "sw")])
    assert result.exit_code == 0 and "warning:" in result.stderr and "holds another sweep (7 points)" in result.stderr
