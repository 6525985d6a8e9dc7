"""`render` draws only results as their stage wrote them, and says what went wrong without a
traceback: an edited or deleted stage file is refused (exit 2) with the command that recomputes
it, as `simulate` recomputes it; a run directory it cannot write is named; Ctrl-C is logged
(docs/reliability.md)."""

from __future__ import annotations

import json
import os

import pytest
from typer.testing import CliRunner

from bearingsim.pipeline.cli.commands import app

runner = CliRunner()


@pytest.fixture(scope="module")
def finished_run(tmp_path_factory):
    run = tmp_path_factory.mktemp("render") / "run"
    result = runner.invoke(app, ["simulate", "helicopter-b-given-hinge", "--out", str(run),
                                 "--set", "solver.duration=0.002", "--set", "output.figures=false"])
    assert result.exit_code == 0, result.output[-3000:]
    return run


@pytest.fixture()
def run_copy(finished_run, tmp_path):
    import shutil

    shutil.copytree(finished_run, tmp_path / "run", symlinks=True)
    return tmp_path / "run"


def _edit_verdict(run):
    path = run / "simulate" / "summary.json"
    summary = json.loads(path.read_text())
    summary["verdict"] = "TAMPERED"
    path.write_text(json.dumps(summary))


def _delete_summary(run):
    (run / "simulate" / "summary.json").unlink()


@pytest.mark.parametrize("damage", [_edit_verdict, _delete_summary], ids=["edited", "deleted"])
def test_render_refuses_damaged_stage_files(damage, run_copy):
    damage(run_copy)
    result = runner.invoke(app, ["render", str(run_copy)])
    assert result.exit_code == 2, result.output[-3000:]
    assert "summary.json changed or went missing" in result.stderr
    assert f"bearingsim run {run_copy / 'scene.toml'} --out {run_copy}" in result.stderr
    assert not (run_copy / "report").exists()
    assert "render refused" in (run_copy / "run.log").read_text()


def test_simulate_recomputes_what_render_refuses(run_copy):
    _edit_verdict(run_copy)
    result = runner.invoke(app, ["simulate", "helicopter-b-given-hinge", "--out", str(run_copy),
                                 "--set", "solver.duration=0.002", "--set", "output.figures=false"])
    assert result.exit_code == 0 and "damaged" in result.stderr
    assert json.loads((run_copy / "simulate" / "summary.json").read_text())["verdict"] != "TAMPERED"


def test_render_cannot_write_names_the_directory(run_copy, monkeypatch):
    import bearingsim.pipeline.staging.runner as runner_module

    def read_only(*args, **kwargs):
        raise PermissionError(13, "Permission denied", str(run_copy / "report"))

    monkeypatch.setattr(runner_module, "compute_stage", read_only)
    result = runner.invoke(app, ["render", str(run_copy)])
    assert result.exit_code == 2 and "cannot write the report there" in result.stderr
    assert f"cp -r {run_copy}" in result.stderr and "Traceback" not in result.output


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes into read-only folders")
def test_render_of_a_read_only_run_directory(run_copy):
    os.chmod(run_copy, 0o555)
    try:
        result = runner.invoke(app, ["render", str(run_copy)])
    finally:
        os.chmod(run_copy, 0o755)
    assert result.exit_code == 2 and "cp -r" in result.stderr


def test_ctrl_c_during_render_is_logged(run_copy, monkeypatch):
    import bearingsim.pipeline.staging.runner as runner_module

    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(runner_module, "compute_stage", interrupted)
    result = runner.invoke(app, ["render", str(run_copy)])
    assert result.exit_code == 130 and "interrupted (Ctrl-C)" in result.stderr
    assert "render interrupted (Ctrl-C)" in (run_copy / "run.log").read_text()
