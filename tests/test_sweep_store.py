"""The shared stage store of `run_stages(..., store=)`: a stage with the same key
is computed once for many run directories, even when they run at the same time."""

from __future__ import annotations

import copy
import dataclasses
import shutil
import threading
import time

import pytest

from bearingsim.pipeline.staging.artefacts import atomic_write_json, read_manifest
from bearingsim.pipeline.staging.runner import Stage, run_stages
from bearingsim.pipeline.scene.load import read_scene_table, resolve


@pytest.fixture()
def scene():
    table = copy.deepcopy(read_scene_table("helicopter-b-given-hinge")[0])
    return resolve(table)


def make_stages(calls: list[str], delay: float = 0.0, fail: set[str] = frozenset()) -> list[Stage]:
    """Stand-ins shaped like the real stages: identify (always needed here) and quasistatic
    feed simulate; identify depends only on the FE inputs, like the real one."""
    lock = threading.Lock()

    def compute(name):
        def run(ctx):
            with lock:
                calls.append(name)
            time.sleep(delay)
            atomic_write_json(ctx.out_dir / "result.json", {"stage": name, "moment": ctx.scene.load.moment})
            if name in fail:
                raise RuntimeError(f"{name} failed on purpose")
            return {"ok": True}
        return run

    return [
        Stage("identify", (), lambda s: True, lambda s: {"fe": "fixed"}, compute("identify"), ""),
        Stage("quasistatic", (), lambda s: True, lambda s: {"load": dataclasses.asdict(s.load)},
              compute("quasistatic"), ""),
        Stage("simulate", ("identify", "quasistatic"), lambda s: True,
              lambda s: {"solver": dataclasses.asdict(s.solver)}, compute("simulate"), ""),
    ]


def statuses(outcomes):
    return {o.name: o.status for o in outcomes}


def with_moment(scene, moment):
    return scene.replace(**{"load.moment": moment})


def test_second_run_dir_links_from_store(scene, tmp_path):
    calls: list[str] = []
    stages, store = make_stages(calls), tmp_path / "store"
    first = run_stages(scene, tmp_path / "a", stages, ["simulate"], store=store)
    assert set(statuses(first).values()) == {"computed"}
    second = run_stages(scene, tmp_path / "b", stages, ["simulate"], store=store)
    assert set(statuses(second).values()) == {"from store"}
    assert calls == ["identify", "quasistatic", "simulate"]
    for name in ("identify", "quasistatic", "simulate"):
        a, b = tmp_path / "a" / name / "result.json", tmp_path / "b" / name / "result.json"
        assert a.read_text() == b.read_text()
        assert read_manifest(tmp_path / "b" / name)["key"] == read_manifest(tmp_path / "a" / name)["key"]
    # the run directories are independent: deleting one leaves the other and the store whole
    shutil.rmtree(tmp_path / "a")
    assert (tmp_path / "b" / "simulate" / "result.json").is_file()
    third = run_stages(scene, tmp_path / "c", stages, ["simulate"], store=store)
    assert set(statuses(third).values()) == {"from store"}


def test_changed_input_recomputes_only_dependents(scene, tmp_path):
    """A sweep over the moment: identify is shared, quasistatic and simulate are not."""
    calls: list[str] = []
    stages, store = make_stages(calls), tmp_path / "store"
    run_stages(scene, tmp_path / "a", stages, ["simulate"], store=store)
    calls.clear()
    out = run_stages(with_moment(scene, 250.0), tmp_path / "b", stages, ["simulate"], store=store)
    assert statuses(out) == {"identify": "from store", "quasistatic": "computed", "simulate": "computed"}
    assert calls == ["quasistatic", "simulate"]


def test_without_store_nothing_is_shared(scene, tmp_path):
    calls: list[str] = []
    stages = make_stages(calls)
    run_stages(scene, tmp_path / "a", stages, ["simulate"])
    run_stages(scene, tmp_path / "b", stages, ["simulate"])
    assert calls == ["identify", "quasistatic", "simulate"] * 2
    assert not (tmp_path / "store").exists()


def test_concurrent_runs_compute_a_shared_stage_once(scene, tmp_path):
    """Three points started together (three worker threads): the lock per key makes the
    others wait for the first and link its result."""
    calls: list[str] = []
    stages, store = make_stages(calls, delay=0.3), tmp_path / "store"
    scenes = [with_moment(scene, m) for m in (0.0, 300.0, 600.0)]
    outcomes: dict[int, list] = {}

    def point(i):
        outcomes[i] = run_stages(scenes[i], tmp_path / f"p{i}", stages, ["simulate"], store=store)

    threads = [threading.Thread(target=point, args=(i,)) for i in range(3)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert calls.count("identify") == 1
    assert calls.count("quasistatic") == 3 and calls.count("simulate") == 3
    assert sorted(statuses(o)["identify"] for o in outcomes.values()) == ["computed", "from store", "from store"]


def test_failed_stage_publishes_nothing(scene, tmp_path):
    calls: list[str] = []
    store = tmp_path / "store"
    with pytest.raises(RuntimeError, match="on purpose"):
        run_stages(scene, tmp_path / "a", make_stages(calls, fail={"simulate"}), ["simulate"], store=store)
    assert not (store / "simulate").exists() or not [p for p in (store / "simulate").iterdir()
                                                     if not p.name.startswith(".")]
    calls.clear()
    out = run_stages(scene, tmp_path / "b", make_stages(calls), ["simulate"], store=store)
    assert statuses(out) == {"identify": "from store", "quasistatic": "from store", "simulate": "computed"}


def test_force_recomputes_and_republishes(scene, tmp_path):
    calls: list[str] = []
    stages, store = make_stages(calls), tmp_path / "store"
    run_stages(scene, tmp_path / "a", stages, ["simulate"], store=store)
    calls.clear()
    out = run_stages(scene, tmp_path / "b", stages, ["simulate"], force={"simulate"}, store=store)
    assert statuses(out)["simulate"] == "computed" and calls == ["simulate"]
    assert (store / "simulate" / read_manifest(tmp_path / "b" / "simulate")["key"] / "result.json").is_file()


def test_a_marker_written_by_a_concurrent_run_is_not_foreign(tmp_path, monkeypatch):
    """The race behind a sweep computing one identification twice: another worker writes the
    store's marker after this one found it missing and before it lists the folder. The marker
    seen in the listing is the store's own, not a file of the user's."""
    from pathlib import Path

    from bearingsim.pipeline.staging.stage_store import STORE_MARKER, claim_store_directory

    store = tmp_path / "store"
    store.mkdir()
    (store / STORE_MARKER).write_text("bearingsim stage store\n")
    real_is_file = Path.is_file
    # the first look for the marker happens before the other worker's rename lands
    monkeypatch.setattr(Path, "is_file", lambda self: False if self.name == STORE_MARKER else real_is_file(self))
    claim_store_directory(store)  # raised OutputRefused ("holds .bearingsim-store") before the fix
    monkeypatch.undo()
    assert (store / STORE_MARKER).is_file()
