"""Every lock bearingsim takes (run directory, stage store, kernel cache) refuses a link or a
special file in its place: the link's target is neither created nor written, and a stage store
with such a file is not used (the stage is computed in the run directory, with a warning that
names the file) (docs/reliability.md)."""

from __future__ import annotations

import os
import threading

import pytest

from bearingsim.pipeline.machine.file_lock import LockBusy, NotALockFile, exclusive_lock
from bearingsim.pipeline.scene.load import load_scene
from bearingsim.pipeline.staging.artefacts import atomic_write_text
from bearingsim.pipeline.staging.runner import Stage, run_stages, stage_key


def _write(ctx):
    atomic_write_text(ctx.out_dir / "result.txt", "42\n")
    return {}


TOY = Stage(name="toy", depends=(), needed=lambda scene: True, inputs=lambda scene: {"moment": scene.load.moment},
            compute=_write, summary="a stage that writes one file")


@pytest.fixture(scope="module")
def scene():
    return load_scene("deep-groove-209")


@pytest.mark.parametrize("planted", ["link to a missing file", "link to a file", "fifo"])
def test_a_planted_store_lock_is_never_followed(planted, scene, tmp_path):
    store, victim = tmp_path / "store", tmp_path / "victim"
    lock = store / "toy" / f".{stage_key(TOY, scene, {})}.lock"
    lock.parent.mkdir(parents=True)
    if planted == "fifo":
        os.mkfifo(lock)
    else:
        if planted == "link to a file":
            victim.write_text("someone else's\n")
        lock.symlink_to(victim)
    outcomes = run_stages(scene, tmp_path / "run", [TOY], ["toy"], store=store)
    assert (tmp_path / "run" / "toy" / "result.txt").read_text() == "42\n"
    if planted == "link to a missing file":
        assert not victim.exists()
    elif planted == "link to a file":
        assert victim.read_text() == "someone else's\n"
    message = outcomes[0].warnings[0]["message"]
    assert f"the stage store {store} cannot be used ({lock} is" in message and "--no-store" in message
    assert not (store / "toy" / stage_key(TOY, scene, {})).exists()  # nothing published through it


def test_the_store_is_used_when_its_lock_is_a_plain_file(scene, tmp_path):
    store = tmp_path / "store"
    run_stages(scene, tmp_path / "a", [TOY], ["toy"], store=store)
    second = run_stages(scene, tmp_path / "b", [TOY], ["toy"], store=store)
    assert second[0].status == "from store" and not second[0].warnings


@pytest.mark.parametrize("what", ["link", "folder"])
def test_a_kernel_cache_lock_refuses_links_and_folders(what, tmp_path):
    path = tmp_path / ".bearingsim-compile-x.lock"
    if what == "link":
        path.symlink_to(tmp_path / "victim")
    else:
        path.mkdir()
    with pytest.raises(NotALockFile), exclusive_lock(path):
        pass
    assert not (tmp_path / "victim").exists()


def test_a_held_lock_is_busy_for_another_holder_and_free_after(tmp_path):
    path = tmp_path / ".lock"
    with exclusive_lock(path):
        seen = []
        worker = threading.Thread(target=lambda: seen.append(_try(path)))
        worker.start()
        worker.join()
        assert seen == ["busy"]
    assert _try(path) == "held"
    assert path.is_file() and not path.is_symlink()


def _try(path):
    try:
        with exclusive_lock(path, wait=False):
            return "held"
    except LockBusy:
        return "busy"
