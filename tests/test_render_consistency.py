"""`render` draws only what the stages computed from one consistent set of inputs, under the run
directory's lock, redraws the figures a user deleted, and writes nothing into a folder that is
not a run directory (docs/reliability.md)."""

from __future__ import annotations

import json
import shutil
import warnings

import pytest
from typer.testing import CliRunner

import bearingsim
from bearingsim.pipeline.cli.commands import app
from bearingsim.pipeline.staging.artefacts import cache_state, read_manifest

runner = CliRunner()
SCENE = "helicopter-b-given-hinge"
SHORT = ["--set", "solver.duration=0.002"]


@pytest.fixture(scope="module")
def finished(tmp_path_factory):
    """`bearingsim run` of a 2 ms run, with its figures and report."""
    run = tmp_path_factory.mktemp("consistency") / "run"
    result = runner.invoke(app, ["run", SCENE, "--out", str(run), *SHORT])
    assert result.exit_code == 0, result.output[-3000:]
    return run


@pytest.fixture()
def run(finished, tmp_path):
    shutil.copytree(finished, tmp_path / "run", symlinks=True)
    return tmp_path / "run"


def _figures(run):
    return sorted(p.relative_to(run).as_posix() for p in run.glob("*/*.png"))


def test_render_redraws_the_figures_a_user_deleted(run):
    """The command's documented purpose: `rm R/*/*.png R/report/*.html; bearingsim render R`."""
    before = _figures(run)
    assert any(p.startswith("quasistatic/") for p in before) and any(p.startswith("simulate/") for p in before)
    for path in [*run.glob("*/*.png"), *run.glob("report/*.html")]:
        path.unlink()
    result = runner.invoke(app, ["render", str(run)])
    assert result.exit_code == 0, result.output[-3000:]
    assert _figures(run) == before and (run / "report" / "report.html").is_file()
    for stage in ("quasistatic", "simulate"):  # still intact results: nothing is recomputed
        assert cache_state(run / stage, read_manifest(run / stage)["key"])[0] == "fresh", stage
    again = runner.invoke(app, ["simulate", SCENE, "--out", str(run), *SHORT])
    assert again.exit_code == 0 and "simulate     cached" in again.stderr


def test_a_hand_edited_scene_toml_is_refused_and_flagged(run):
    text = (run / "scene.toml").read_text()
    assert "moment = 430" in text
    (run / "scene.toml").write_text(text.replace("moment = 430", "moment = 100"))
    result = runner.invoke(app, ["render", str(run)])
    assert result.exit_code == 2, result.output
    message = " ".join(result.stderr.split())
    assert "does not describe the results" in message and "load.moment: 430" in message and "100 in scene.toml" in message
    assert f"bearingsim run {run / 'scene.toml'} --out {run}" in message
    assert "render refused" in (run / "run.log").read_text()
    with pytest.warns(UserWarning, match="does not describe the results"):
        opened = bearingsim.open_run(run)
    assert opened.problems


def test_scene_toml_of_an_interrupted_run_with_new_inputs_is_refused(run, monkeypatch):
    """`simulate --set solver.duration=0.003` interrupted: scene.toml says 3 ms, the results are of 2 ms."""
    import bearingsim.pipeline.staging.runner as runner_module

    real = runner_module.compute_stage

    def interrupted(stage, *args, **kwargs):
        if stage.name == "simulate":
            raise KeyboardInterrupt
        return real(stage, *args, **kwargs)

    monkeypatch.setattr(runner_module, "compute_stage", interrupted)
    stopped = runner.invoke(app, ["simulate", SCENE, "--out", str(run), "--set", "solver.duration=0.003"])
    assert stopped.exit_code == 130
    monkeypatch.setattr(runner_module, "compute_stage", real)
    result = runner.invoke(app, ["render", str(run)])
    assert result.exit_code == 2 and "solver.duration: 0.002 computed, 0.003 in scene.toml" in " ".join(result.stderr.split())


def test_an_intact_run_opens_without_a_warning(run):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert bearingsim.open_run(run).problems == []


def test_an_edited_summary_is_flagged_by_open_run(run):
    path = run / "simulate" / "summary.json"
    summary = json.loads(path.read_text())
    summary["cage_speed_mean"] = 0.0
    path.write_text(json.dumps(summary))
    with pytest.warns(UserWarning, match="summary.json changed or went missing"):
        bearingsim.open_run(run)


def test_render_holds_the_run_directory_lock(run, monkeypatch):
    """A run that starts while render draws is refused (it would replace a stage under the
    report), and render is refused while a run holds the directory."""
    import bearingsim.pipeline.stages.report as report
    from bearingsim.pipeline.staging.artefacts import RunDirectoryBusy, run_directory_lock

    seen = []

    def while_rendering(run_dir, show=False, progress=None):
        try:
            with run_directory_lock(run_dir):
                seen.append("a second writer got the lock")
        except RunDirectoryBusy:
            seen.append("busy")
        raise KeyboardInterrupt

    monkeypatch.setattr(report, "render_run", while_rendering)
    runner.invoke(app, ["render", str(run)])
    assert seen == ["busy"]
    monkeypatch.undo()
    with run_directory_lock(run):
        result = runner.invoke(app, ["render", str(run)])
    assert result.exit_code == 1 and "another bearingsim process is writing" in result.stderr


def test_render_writes_nothing_into_a_folder_that_is_not_a_run(tmp_path):
    folder = tmp_path / "mine"
    folder.mkdir()
    (folder / "scene.toml").write_text("name = 'mine'\n")
    (folder / "run.log").write_text("my own log\n")
    before = {p.name: p.read_bytes() for p in folder.iterdir()}
    result = runner.invoke(app, ["render", str(folder)])
    assert result.exit_code == 2 and "not a run directory" in " ".join(result.stderr.split())
    assert {p.name: p.read_bytes() for p in folder.iterdir()} == before  # not even a .lock


def test_a_corrupt_stage_manifest_is_refused_not_left_out(run):
    """A simulate/stage.json that cannot be read made the report leave the dynamics out, silently."""
    (run / "simulate" / "stage.json").write_text("{ not json")
    result = runner.invoke(app, ["render", str(run)])
    assert result.exit_code == 2 and "stage.json (unreadable or missing)" in " ".join(result.stderr.split())


def test_a_run_of_another_version_renders(run):
    """Stage keys hash the code version too: a run computed by another version (an upgrade, or
    an edited checkout) has other keys for the same inputs, and is of its scene all the same."""
    renamed = {}
    for stage in ("quasistatic", "simulate", "report"):
        manifest = json.loads((run / stage / "stage.json").read_text())
        renamed[manifest["key"]] = "0" * 63 + str(len(renamed))
        manifest["key"] = renamed[manifest["key"]]
        manifest["upstream"] = {d: renamed.get(k, k) for d, k in manifest.get("upstream", {}).items()}
        (run / stage / "stage.json").write_text(json.dumps(manifest))
    result = runner.invoke(app, ["render", str(run)])
    assert result.exit_code == 0, result.output
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        bearingsim.open_run(run)


def test_a_stage_computed_from_another_upstream_result_is_refused(run):
    manifest = json.loads((run / "simulate" / "stage.json").read_text())
    manifest["upstream"]["quasistatic"] = "f" * 64
    (run / "simulate" / "stage.json").write_text(json.dumps(manifest))
    (run / "simulate" / "stage.json").chmod(0o644)
    result = runner.invoke(app, ["render", str(run)])
    assert result.exit_code == 2 and "computed from another quasistatic result" in " ".join(result.stderr.split())
