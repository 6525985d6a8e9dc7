"""Outputs never touch a user's file; every failure is a message; caches stay honest.

Cases of the issue "Never silently wrong, never lose a user's file": a scene file overwritten
by `--out .` (2), owner-only result files (4), tracebacks for unusable paths and names (5),
a damaged cache served (5), and the smaller ones (8): stale downstream results, number
spelling in cache keys, temporaries of killed runs, Ctrl-C, names, sweep size, code edits.
"""

from __future__ import annotations

import dataclasses
import json
import os
import stat
import subprocess
import sys
import time
from pathlib import Path

import pytest
from typer.testing import CliRunner

from bearingsim.pipeline.staging import provenance
from bearingsim.pipeline.staging.artefacts import RUN_MARKER, atomic_write_json, input_key, sweep_stale_temporaries
from bearingsim.pipeline.cli.commands import app
from bearingsim.pipeline.staging.runner import Stage, run_stages, stage_key
from bearingsim.pipeline.scene.load import load_scene
from bearingsim.pipeline.stages import STAGES

runner = CliRunner()
SCENE_TEXT = (Path(__file__).parents[1] / "pipeline" / "scenes" / "deep-groove-209.toml").read_text()


def quasistatic(*args):
    return runner.invoke(app, ["quasistatic", *args])


# --- 2. a user's files are never overwritten or deleted ---------------------------------------
def test_out_dot_next_to_the_users_scene_is_refused(tmp_path, monkeypatch):
    scene = tmp_path / "scene.toml"
    scene.write_text("# my notes\n" + SCENE_TEXT)
    scene.chmod(0o644)
    before = scene.read_bytes()
    monkeypatch.chdir(tmp_path)
    result = quasistatic("scene.toml", "--out", ".", "--set", "load.radial=1000")
    assert result.exit_code == 2
    assert "--out .: the directory holds files that are not a bearingsim run" in result.stderr
    assert scene.read_bytes() == before and stat.S_IMODE(scene.stat().st_mode) == 0o644
    assert sorted(p.name for p in tmp_path.iterdir()) == ["scene.toml"]  # not even a lock file


def test_a_users_scene_toml_in_a_run_directory_is_not_replaced(tmp_path):
    run = tmp_path / "run"
    assert quasistatic("deep-groove-209", "--out", str(run)).exit_code == 0
    (run / "scene.toml").write_text(SCENE_TEXT)  # the user keeps their own scene there
    result = quasistatic(str(run / "scene.toml"), "--out", str(run))
    assert result.exit_code == 2 and "is a scene file of yours" in result.stderr
    assert (run / "scene.toml").read_text() == SCENE_TEXT


def test_a_users_folder_named_like_a_stage_is_not_deleted(tmp_path):
    run = tmp_path / "run"
    run.mkdir()
    (run / RUN_MARKER).write_text("")  # a bearingsim run directory ...
    (run / "quasistatic").mkdir()  # ... holding a folder of the user's in a stage's place
    (run / "quasistatic" / "mine.txt").write_text("keep me")
    result = quasistatic("deep-groove-209", "--out", str(run))
    assert result.exit_code == 2 and "was not written by bearingsim" in result.stderr
    assert (run / "quasistatic" / "mine.txt").read_text() == "keep me"


def test_a_users_file_inside_a_stage_folder_is_not_deleted_by_a_recompute(tmp_path):
    """A stage replaces its folder whole, so a file the manifest does not list stops it."""
    run = tmp_path / "run"
    assert quasistatic("deep-groove-209", "--out", str(run)).exit_code == 0
    (run / "quasistatic" / "notes.txt").write_text("keep me")  # e.g. beside the figure
    before = (run / "quasistatic" / "quasistatic.json").read_bytes()
    result = quasistatic("deep-groove-209", "--out", str(run), "--force")
    assert result.exit_code == 2 and "notes.txt" in result.stderr and "move it out" in result.stderr
    assert (run / "quasistatic" / "notes.txt").read_text() == "keep me"
    assert (run / "quasistatic" / "quasistatic.json").read_bytes() == before
    assert not list(run.glob(".quasistatic.*"))  # nothing half-written beside it


def test_a_new_or_empty_directory_is_accepted_and_marked(tmp_path):
    empty = tmp_path / "empty"
    empty.mkdir()
    for out in (empty, tmp_path / "new" / "deeper"):
        assert quasistatic("deep-groove-209", "--out", str(out)).exit_code == 0
        assert (out / RUN_MARKER).is_file() and (out / "quasistatic" / "quasistatic.json").is_file()


def test_a_run_directory_of_an_older_version_is_still_recognised(tmp_path):
    run = tmp_path / "run"
    assert quasistatic("deep-groove-209", "--out", str(run)).exit_code == 0
    (run / RUN_MARKER).unlink()  # written before the marker existed: stage.json files say it is ours
    assert quasistatic("deep-groove-209", "--out", str(run)).exit_code == 0


# --- 4. files follow the umask -------------------------------------------------------------------
@pytest.mark.parametrize("umask, file_mode, dir_mode", [(0o022, 0o644, 0o755), (0o002, 0o664, 0o775),
                                                        (0o077, 0o600, 0o700)])
def test_result_files_follow_the_umask(umask, file_mode, dir_mode, tmp_path):
    out = tmp_path / "run"
    proc = subprocess.run([sys.executable, "-c", "from bearingsim.pipeline.cli.commands import main; main()",
                           "quasistatic", "deep-groove-209", "--out", str(out)],
                          capture_output=True, text=True, preexec_fn=lambda: os.umask(umask))
    assert proc.returncode == 0, proc.stderr
    for path in [out, *out.rglob("*")]:
        mode = stat.S_IMODE(path.stat().st_mode)
        assert mode == (dir_mode if path.is_dir() else file_mode), (path, oct(mode))


# --- 5. every failure is a message ---------------------------------------------------------------
def test_a_scene_file_that_is_not_utf8(tmp_path):
    path = tmp_path / "latin1.toml"
    path.write_bytes(SCENE_TEXT.replace("deep-groove-209", "d\xe9ep").encode("latin-1"))
    result = runner.invoke(app, ["check", str(path)])
    assert result.exit_code == 2 and "is not UTF-8 text (byte 0xe9 on line 5)" in result.stderr


def test_an_array_nested_3000_deep(tmp_path):
    path = tmp_path / "deep.toml"
    path.write_text("name = 'x'\nv = " + "[" * 3000 + "]" * 3000 + "\n")
    for argv in (["check", str(path)], ["check", "deep-groove-209", "--set", "load.radial=" + "[" * 3000 + "]" * 3000]):
        result = runner.invoke(app, argv)
        assert result.exit_code == 2 and "too deeply" in result.stderr, result.output


@pytest.mark.parametrize("name", ['"a\\u0000b"', '"' + "a" * 300 + '"', '"   "', '"two\\nlines"', '"a;rm -rf ~"',
                                  '"$(whoami)"', '"a b"', '"../up"', '".hidden"'])
def test_names_that_cannot_be_folder_names_are_refused(name, tmp_path):
    result = quasistatic("deep-groove-209", "--set", f"name={name}", "--out", str(tmp_path / "r"))
    assert result.exit_code == 2 and "cannot name a run directory" in result.stderr, result.output
    assert not (tmp_path / "r").exists()


@pytest.mark.parametrize("scene_arg", ["a" * 300, "a" * 300 + ".toml", "nul\x00byte"])
def test_unreadable_scene_arguments(scene_arg):
    result = runner.invoke(app, ["check", scene_arg])
    assert result.exit_code == 2 and "error: scene:" in result.stderr, result.output


def test_out_that_is_a_file_a_device_or_unwritable(tmp_path):
    a_file = tmp_path / "file"
    a_file.write_text("mine")
    for out, text in ((a_file, "exists and is not a directory"), (Path("/dev/null"), "exists and is not a directory"),
                      (Path("/proc/bearingsim-cannot-be-here"), "cannot use this directory")):
        result = quasistatic("deep-groove-209", "--out", str(out))
        assert result.exit_code == 2 and text in result.stderr, result.output
    assert a_file.read_text() == "mine"


def test_a_damaged_cached_result_is_recomputed(tmp_path):
    out = tmp_path / "run"
    assert quasistatic("deep-groove-209", "--out", str(out)).exit_code == 0
    result_file = out / "quasistatic" / "quasistatic.json"
    good = json.loads(result_file.read_text())
    result_file.write_text(result_file.read_text()[:100])  # truncated, e.g. by a full disk
    result = quasistatic("deep-groove-209", "--out", str(out), "--json")
    assert result.exit_code == 0, result.output
    assert "the cached result was damaged (quasistatic.json" in result.stderr
    assert json.loads(result.stdout)["balls"] == good["balls"]
    assert "damaged" in (out / "run.log").read_text()


# --- 8. downstream results, cache keys, temporaries, interrupts, sizes, code edits -------------------
def stand_in_stages(calls: list[str]) -> list[Stage]:
    def compute(name):
        def run(ctx):
            calls.append(name)
            atomic_write_json(ctx.out_dir / "out.json", {"stage": name})
        return run

    inputs = {"identify": lambda s: {}, "quasistatic": lambda s: dataclasses.asdict(s.load),
              "simulate": lambda s: dataclasses.asdict(s.solver), "report": lambda s: {"name": s.name}}
    return [dataclasses.replace(real, inputs=inputs[real.name], compute=compute(real.name)) for real in STAGES]


def test_an_old_report_is_removed_when_the_results_it_shows_change(tmp_path):
    scene = load_scene("helicopter-b-given-hinge")
    calls: list[str] = []
    stages = stand_in_stages(calls)
    run_stages(scene, tmp_path, stages, ["report"])
    assert (tmp_path / "report").is_dir()
    changed = scene.replace(**{"solver.duration": 0.05})
    run_stages(changed, tmp_path, stages, ["simulate"])  # `bearingsim simulate` with new inputs
    assert not (tmp_path / "report").exists(), "a report of the old results stayed beside the new ones"
    assert (tmp_path / "quasistatic").is_dir()  # upstream and unchanged: kept
    # new loads make both simulate and report stale when only quasistatic reruns
    run_stages(changed, tmp_path, stages, ["report"])
    loaded = changed.replace(**{"load.moment": 100.0})
    run_stages(loaded, tmp_path, stages, ["quasistatic"])
    assert not (tmp_path / "simulate").exists() and not (tmp_path / "report").exists()


def test_a_stale_report_holding_a_users_file_is_kept(tmp_path, caplog):
    scene = load_scene("helicopter-b-given-hinge")
    stages = stand_in_stages([])
    run_stages(scene, tmp_path, stages, ["report"])
    (tmp_path / "report" / "annotated.png").write_bytes(b"mine")
    changed = scene.replace(**{"solver.duration": 0.05})
    with caplog.at_level("WARNING"):
        run_stages(changed, tmp_path, stages, ["simulate"])
    assert (tmp_path / "report" / "annotated.png").read_bytes() == b"mine"
    assert "stage report: kept" in caplog.text and "annotated.png" in caplog.text


def test_cache_keys_compare_numbers_by_value():
    assert input_key("s", {"m": 430}, "v") == input_key("s", {"m": 430.0}, "v")
    assert input_key("s", {"m": [0, -0.0]}, "v") == input_key("s", {"m": [0.0, 0.0]}, "v")
    assert input_key("s", {"m": 430}, "v") != input_key("s", {"m": 431}, "v")
    assert input_key("s", {"flag": True}, "v") != input_key("s", {"flag": 1}, "v")
    a = load_scene("helicopter-b-given-hinge", ["load.moment=430", "speed.inner_rpm=3060"])
    b = load_scene("helicopter-b-given-hinge", ["load.moment=430.0", "speed.inner_rpm=3060.0"])
    for stage in STAGES:  # simulate hashes the raw table, where 430 and 430.0 differ
        assert stage_key(stage, a, {}) == stage_key(stage, b, {}), stage.name


def test_cache_keys_keep_integers_exact():
    """Numbers hash by their exact value: an integer a float cannot hold stays an integer, so
    seeds 2**53 and 2**53 + 1 are two keys (as floats they are one)."""
    assert float(2**53) == float(2**53 + 1)  # why the key must not go through float
    assert input_key("s", {"seed": 2**53}, "v") != input_key("s", {"seed": 2**53 + 1}, "v")
    assert input_key("s", {"n": 2**53 + 1}, "v") != input_key("s", {"n": 2**53 + 2}, "v")
    assert input_key("s", {"n": 2**53}, "v") == input_key("s", {"n": float(2**53)}, "v")  # one value
    assert input_key("s", {"n": 10**30}, "v") != input_key("s", {"n": float(10**30)}, "v")  # 1e30 != 10**30
    tolerances = "tolerances={samples = 100, moment = { sd = 10 }, seed = %d}"
    a, b = (load_scene("helicopter-b-given-hinge", [tolerances % s]) for s in (2**53, 2**53 + 1))
    quasistatic = next(s for s in STAGES if s.name == "quasistatic")
    assert stage_key(quasistatic, a, {}) != stage_key(quasistatic, b, {})


def test_temporaries_of_a_killed_run_are_swept_when_old(tmp_path):
    old_dir, old_file = tmp_path / ".simulate.k1ll3d.tmp", tmp_path / ".scene.toml.abc123.tmp"
    young, old_swap = tmp_path / ".quasistatic.l1v3.tmp", tmp_path / ".report.old-4242"
    mine = tmp_path / ".my-notes"
    for d in (old_dir, young, old_swap):
        d.mkdir()
    old_file.write_text("x")
    mine.write_text("keep")
    past = time.time() - 2 * 3600
    for p in (old_dir, old_file, old_swap, mine):
        os.utime(p, (past, past))
    assert sorted(sweep_stale_temporaries(tmp_path)) == sorted(p.name for p in (old_dir, old_file, old_swap))
    assert young.exists() and mine.exists()


def test_the_command_line_sweeps_old_temporaries(tmp_path):
    out = tmp_path / "run"
    assert quasistatic("deep-groove-209", "--out", str(out)).exit_code == 0
    leftover = out / ".simulate.k1ll3d.tmp"
    leftover.mkdir()
    past = time.time() - 2 * 3600
    os.utime(leftover, (past, past))
    assert quasistatic("deep-groove-209", "--out", str(out)).exit_code == 0
    assert not leftover.exists()


def test_ctrl_c_is_logged_and_exits_130(tmp_path, monkeypatch):
    import bearingsim.pipeline.staging.runner as runner_module

    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(runner_module, "run_stages", interrupted)
    out = tmp_path / "run"
    result = quasistatic("deep-groove-209", "--out", str(out))
    assert result.exit_code == 130
    assert "interrupted (Ctrl-C)" in result.stderr
    assert "interrupted by the user (Ctrl-C)" in (out / "run.log").read_text()


def test_a_sweep_has_a_size_limit_with_an_override(tmp_path):
    base = ["sweep", "helicopter-b-given-hinge", "--dry-run", "--out", str(tmp_path / "s"),
            "--set", "solver.duration=0.01"]
    result = runner.invoke(app, [*base, "--vary", "load.moment=0:600:2000000"])
    assert result.exit_code == 2 and "2000000 points" in result.stderr and "--max-points 2000000" in result.stderr
    result = runner.invoke(app, [*base, "--vary", "load.moment=0:600:12", "--max-points", "10"])
    assert result.exit_code == 2 and "--max-points 12" in result.stderr
    result = runner.invoke(app, [*base, "--vary", "load.moment=0:600:12", "--max-points", "12"])
    assert result.exit_code == 0, result.output


@pytest.mark.parametrize("name", ["bad name", "two\nlines", "a|b"])
def test_a_sweep_name_that_cannot_be_a_folder_is_refused(name, tmp_path):
    result = runner.invoke(app, ["sweep", "helicopter-b-given-hinge", "--dry-run", "--name", name,
                                 "--vary", "load.moment=0,100"])
    assert result.exit_code == 2 and "sweep.name" in result.stderr and "cannot name a run directory" in result.stderr


def test_code_edits_in_a_source_checkout_change_the_stage_keys(tmp_path, monkeypatch):
    for folder in provenance.SOURCE_FOLDERS:
        (tmp_path / folder).mkdir()
        (tmp_path / folder / "mod.py").write_text("X = 1\n")
    (tmp_path / "pyproject.toml").write_text("")
    monkeypatch.setattr(provenance, "source_checkout", lambda: tmp_path)
    scene = load_scene("deep-groove-209")
    quasistatic_stage = next(s for s in STAGES if s.name == "quasistatic")
    provenance.source_fingerprint.cache_clear()
    try:
        first = stage_key(quasistatic_stage, scene, {})
        assert "+src." in provenance.code_version()
        (tmp_path / "dynamics" / "mod.py").write_text("X = 2\n")
        provenance.source_fingerprint.cache_clear()
        assert stage_key(quasistatic_stage, scene, {}) != first
    finally:
        provenance.source_fingerprint.cache_clear()


def test_this_checkout_is_recognised_as_a_source_checkout():
    root = provenance.source_checkout()
    assert root is not None and (root / "pyproject.toml").is_file()
    assert provenance.code_version().startswith(provenance.package_version() + "+src.")
