"""bearingsim writes only into folders it made, and never through a link or into a special file.

A folder of the user's that merely looks like bearingsim's (a copied stage folder, a scene.toml,
a results.csv, a sweep.json of their own) is refused with exit 2 and a safe `--out` to use
instead, before any file — not even the marker or the lock — is written. In a run directory
that is bearingsim's, a link or a FIFO where run.log or .lock belongs is refused, never
written through (docs/reliability.md).
"""

from __future__ import annotations

import json
import os
from pathlib import Path

import pytest
from typer.testing import CliRunner

from bearingsim.pipeline.staging.artefacts import RUN_MARKER
from bearingsim.pipeline.cli.commands import app

runner = CliRunner()
SCENE_TEXT = (Path(__file__).parents[1] / "pipeline" / "scenes" / "deep-groove-209.toml").read_text()
A_STAGE_MANIFEST = {"stage": "quasistatic", "status": "done", "key": "0" * 64, "files": {}}


def snapshot(folder: Path) -> dict[str, bytes | str]:
    """Every entry under `folder`: file bytes, link targets, "dir" for folders."""
    out = {}
    for path in sorted(folder.rglob("*")):
        name = path.relative_to(folder).as_posix()
        out[name] = (f"-> {os.readlink(path)}" if path.is_symlink() else "dir" if path.is_dir()
                     else path.read_bytes())
    return out


# --- a user's folder that looks like bearingsim's is refused, untouched --------------------------
def _copied_stage_folder(folder: Path) -> None:
    (folder / "old").mkdir()
    (folder / "old" / "stage.json").write_text(json.dumps(A_STAGE_MANIFEST))
    (folder / "versions.json").write_text('{"mine": true}')
    (folder / "run.log").write_text("my notes\n")


def _users_scene_beside_versions(folder: Path) -> None:
    (folder / "scene.toml").write_text(SCENE_TEXT)
    (folder / "versions.json").write_text('{"mine": true}')


def _a_results_table(folder: Path) -> None:
    (folder / "results.csv").write_text("mine\n")


def _a_sweep_json_of_the_users(folder: Path) -> None:
    (folder / "sweep.json").write_text('{"my": "plan"}')
    (folder / "stability_map.png").write_bytes(b"not a png")


def _study_tables_of_the_users(folder: Path) -> None:
    (folder / "stability.md").write_text("my notes\n")
    (folder / "work_precision.md").write_text("my notes\n")


LOOKALIKES = {"copied stage folder": _copied_stage_folder, "scene.toml and versions.json": _users_scene_beside_versions,
              "results.csv": _a_results_table, "sweep.json and a map": _a_sweep_json_of_the_users,
              "study tables": _study_tables_of_the_users}


# command, what the refusal says, the safe folder it proposes inside the user's
REFUSING = {
    "quasistatic": (["quasistatic", "deep-groove-209"], "not a bearingsim run", "run"),
    "sweep": (["sweep", "helicopter-b-given-hinge", "--set", "solver.duration=0.002", "--vary", "load.moment=1,2"],
              "not a bearingsim sweep", "sweep"),
    "stability": (["stability", "preload", "--window", "4e-5"], "not bearingsim's studies", "study"),
    "bench": (["bench", "helicopter-b-given-hinge", "--quick", "--no-fe"], "not bearingsim's studies", "study"),
}


@pytest.mark.parametrize("command", REFUSING)
@pytest.mark.parametrize("content", LOOKALIKES)
def test_a_users_lookalike_folder_is_refused(content, command, tmp_path):
    args, says, safe = REFUSING[command]
    folder = tmp_path / "mine"
    folder.mkdir()
    LOOKALIKES[content](folder)
    before = snapshot(folder)
    result = runner.invoke(app, [*args, "--out", str(folder)])
    assert result.exit_code == 2, result.output
    assert says in result.stderr and f"--out {folder / safe}" in result.stderr
    assert snapshot(folder) == before  # not even the marker or the lock


def test_a_study_folder_is_claimed_once_and_reused(tmp_path):
    from bearingsim.pipeline.studies import STUDY_MARKER

    out = tmp_path / "stab"
    for _ in range(2):  # new, then its own
        result = runner.invoke(app, ["stability", "preload", "--window", "4e-5", "--out", str(out)])
        assert result.exit_code == 0, result.output[-2000:]
    assert sorted(p.name for p in out.iterdir()) == [STUDY_MARKER, "stability.json", "stability.md", "stability.png"]


def test_a_dangling_link_as_out_is_named_and_not_followed(tmp_path):
    link = tmp_path / "link"
    link.symlink_to(tmp_path / "nowhere")
    result = runner.invoke(app, ["quasistatic", "deep-groove-209", "--out", str(link)])
    assert result.exit_code == 2 and "is a link to" in result.stderr and "does not exist" in result.stderr
    assert not (tmp_path / "nowhere").exists()


def test_a_file_as_sweep_directory_is_refused(tmp_path):
    path = tmp_path / "a-file"
    path.write_text("mine")
    result = runner.invoke(app, ["sweep", "helicopter-b-given-hinge", "--vary", "load.moment=1,2",
                                 "--out", str(path)])
    assert result.exit_code == 2 and "not a directory" in result.stderr
    assert path.read_text() == "mine"


def test_an_own_sweep_directory_is_claimed_and_recognised(tmp_path):
    from bearingsim.pipeline.sweep.driver import SWEEP_MARKER, claim_sweep_directory, is_own_sweep_dir

    new, empty = tmp_path / "new", tmp_path / "empty"
    empty.mkdir()
    for folder in (new, empty):
        claim_sweep_directory(folder)
        assert (folder / SWEEP_MARKER).is_file() and is_own_sweep_dir(folder)
    older = tmp_path / "older"  # a sweep of a version before the marker: its plan says so
    older.mkdir()
    (older / "sweep.json").write_text(json.dumps({"name": "s", "scene": "x", "axes": {}, "points": []}))
    claim_sweep_directory(older)
    assert (older / SWEEP_MARKER).is_file()


# --- links and special files in a run directory are never written through ----------------------
@pytest.fixture()
def run_dir(tmp_path):
    run = tmp_path / "run"
    assert runner.invoke(app, ["quasistatic", "deep-groove-209", "--out", str(run)]).exit_code == 0
    assert (run / RUN_MARKER).is_file()
    return run


@pytest.mark.parametrize("name", ["run.log", ".lock"])
@pytest.mark.parametrize("target_exists", [True, False])
def test_a_link_in_a_run_directory_is_not_written_through(name, target_exists, run_dir, tmp_path):
    target = tmp_path / "elsewhere.txt"
    if target_exists:
        target.write_text("someone else's file\n")
    (run_dir / name).unlink()
    (run_dir / name).symlink_to(target)
    result = runner.invoke(app, ["quasistatic", "deep-groove-209", "--out", str(run_dir)])
    assert result.exit_code == 2, result.output
    assert f"{run_dir / name} is a symbolic link" in result.stderr and "--out" in result.stderr
    if target_exists:
        assert target.read_text() == "someone else's file\n"
    else:
        assert not target.exists()
    assert (run_dir / name).is_symlink()


@pytest.mark.parametrize("name", ["run.log", ".lock"])
def test_a_fifo_in_a_run_directory_is_refused_at_once(name, run_dir):
    (run_dir / name).unlink()
    os.mkfifo(run_dir / name)
    result = runner.invoke(app, ["quasistatic", "deep-groove-209", "--out", str(run_dir)])
    assert result.exit_code == 2 and "is not a regular file" in result.stderr


def test_render_refuses_a_linked_run_log(run_dir, tmp_path):
    target = tmp_path / "elsewhere.txt"
    target.write_text("keep\n")
    (run_dir / "run.log").unlink()
    (run_dir / "run.log").symlink_to(target)
    result = runner.invoke(app, ["render", str(run_dir)])
    assert result.exit_code == 2 and "is a symbolic link" in result.stderr
    assert target.read_text() == "keep\n"
