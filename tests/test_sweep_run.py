"""Sweeps on an in-process Dask cluster : a tiny sweep with its table
and map, per-point failures as data, a shared stage computed once, resuming after lost
points, and a real two-point sweep of short dynamic runs."""

from __future__ import annotations

import dataclasses
import functools
import json
import math

import pytest

from bearingsim.pipeline.staging.artefacts import atomic_write_json
from bearingsim.pipeline.staging.runner import Stage
from bearingsim.pipeline.scene.cage_classes import CAGE_CLASSES
from bearingsim.pipeline.sweep.driver import gather, plan_sweep, run_sweep
from bearingsim.pipeline.sweep.point_runner import RECORD_FILE, run_point
from bearingsim.pipeline.sweep.table import read_table

distributed = pytest.importorskip("distributed")

SCENE = "helicopter-b-given-hinge"


@pytest.fixture(scope="module")
def client():
    with distributed.Client(processes=False, n_workers=1, threads_per_worker=2,
                            dashboard_address=":0") as c:
        yield c


def _log(path, line: str) -> None:
    """Calls are logged to a file: tasks reach the worker pickled, so a list would be a copy."""
    with open(path, "a", encoding="utf-8") as fh:
        fh.write(line + "\n")


def calls_in(path) -> list[str]:
    return path.read_text().splitlines() if path.exists() else []


def _identify(log, ctx):
    _log(log, "identify")
    atomic_write_json(ctx.out_dir / "hinge.json", {"H": 1e9})


def _simulate(log, ctx):
    m = ctx.scene.load.moment
    _log(log, f"simulate {m:g} {ctx.scene.speed.inner_rpm:g}")
    if m < 0:
        raise RuntimeError(f"Newton failed at t = 1.2e-4 s for moment {m:g}; try a smaller max_step")
    metal = m / 1000.0
    atomic_write_json(ctx.out_dir / "summary.json", {
        "duration": 0.1, "cage_speed_mean": 143.7, "cage_speed_variation": 0.01,
        "cage_metal_contact_fraction": metal, "cage_contact_angle_spread": 0.2 if metal > 0 else None,
        "cage_whirl_ratio": 0.0, "burn_zone_sector": [1.0, 1.5] if metal > 0 else None})


def fake_stages(log) -> list[Stage]:
    """Stand-in stages: simulate writes a summary whose metal-contact fraction is
    moment / 1000 N·m, crushed (spread 0.2 rad) from 0.5 on; a negative moment makes the
    'solver' give up, like a real solver failure. Identify is shared by every point."""
    return [Stage("identify", (), lambda s: True, lambda s: {"fe": "same for all"},
                  functools.partial(_identify, log), ""),
            Stage("simulate", ("identify",), lambda s: True,
                  lambda s: {"load": dataclasses.asdict(s.load), "speed": dataclasses.asdict(s.speed)},
                  functools.partial(_simulate, log), "")]


VARY = ["load.moment=-100,0,300,600", "speed.inner_rpm=2000,6000"]


def test_tiny_sweep_table_classes_failures_and_map(client, tmp_path):
    log = tmp_path / "calls.log"
    plan = plan_sweep(SCENE, [], VARY, out=tmp_path / "sw")
    seen = []
    records = run_sweep(plan, client, progress=seen.append, poll_s=0.05,
                        point_function=functools.partial(run_point, stages=fake_stages(log)))
    calls = calls_in(log)
    assert calls.count("identify") == 1, "the shared stage must be computed once for the sweep"
    assert len([c for c in calls if c.startswith("simulate")]) == 8
    assert [r["status"] for r in records].count("failed") == 2
    paths = gather(plan, records)
    rows = read_table(paths["table"])
    assert len(rows) == 8
    by_moment = {}
    for r in rows:
        by_moment.setdefault(r["load.moment"], set()).add(r["cage_class"])
    assert by_moment == {-100.0: {"failed"}, 0.0: {"centred"}, 300.0: {"chaotic"}, 600.0: {"crushed"}}
    failed = [r for r in rows if r["status"] == "failed"]
    assert all("Newton failed at t = 1.2e-4 s" in r["error"] for r in failed)
    assert [r["burn_zone_start"] for r in rows if r["load.moment"] == 600.0] == pytest.approx([math.degrees(1.0)] * 2)
    assert paths["map"].stat().st_size > 10_000
    final = seen[-1]
    assert (final.total, final.done, final.failed, final.running) == (8, 6, 2, 0)
    plan_file = json.loads((tmp_path / "sw" / "sweep.json").read_text())
    assert len(plan_file["points"]) == 8 and plan_file["axes"]["speed.inner_rpm"] == [2000, 6000]


def test_rerun_skips_finished_points(client, tmp_path):
    log = tmp_path / "calls.log"
    fn = functools.partial(run_point, stages=fake_stages(log))
    plan = plan_sweep(SCENE, [], VARY, out=tmp_path / "sw")
    run_sweep(plan, client, poll_s=0.05, point_function=fn)
    log.unlink()
    seen = []
    records = run_sweep(plan, client, progress=seen.append, poll_s=0.05, point_function=fn)
    assert calls_in(log) == [] and seen[-1].resumed == 6
    assert [r["status"] for r in records].count("done") == 6
    run_sweep(plan, client, poll_s=0.05, point_function=fn, retry_failed=True)
    assert sorted(calls_in(log)) == ["simulate -100 2000", "simulate -100 6000"]
    # a different base scene reruns every point (here its stages' keys are unchanged, so
    # the runs are quick, but each record is rewritten for the new scene)
    changed = plan_sweep(SCENE, ["solver.rtol=2e-4"], VARY, out=tmp_path / "sw")
    assert {r.scene_hash for r in changed.requests}.isdisjoint({r.scene_hash for r in plan.requests})
    records = run_sweep(changed, client, poll_s=0.05, point_function=fn)
    assert [r["scene_hash"] for r in records] == [r.scene_hash for r in changed.requests]


def lose_point(lost_label: str, fn, request):
    """A worker that dies with the point: the task ends without a record."""
    if request.label == lost_label:
        raise ConnectionResetError("worker died (simulated)")
    return fn(request)


def test_lost_points_rerun_and_finished_ones_are_kept(client, tmp_path):
    log = tmp_path / "calls.log"
    fn = functools.partial(run_point, stages=fake_stages(log))
    plan = plan_sweep(SCENE, [], ["load.moment=0,300,600"], out=tmp_path / "sw")
    lost = plan.points[1].label
    records = run_sweep(plan, client, poll_s=0.05, point_function=functools.partial(lose_point, lost, fn))
    assert [r.get("lost", False) for r in records] == [False, True, False]
    assert not (tmp_path / "sw" / "points" / plan.points[1].id / RECORD_FILE).exists()
    rows = read_table(gather(plan, records)["table"])
    assert rows[1]["status"] == "failed" and "worker died" in rows[1]["error"]
    log.unlink()
    records = run_sweep(plan, client, poll_s=0.05, point_function=fn)
    assert calls_in(log) == ["simulate 300 3060"]
    assert [r["status"] for r in records] == ["done"] * 3


def test_real_two_point_sweep_shares_the_quasistatic_stage(tmp_path):
    """Two short dynamic runs differing only in a numerical setting: the quasi-static
    start is computed once and linked into the second point from the store. One worker
    thread, as in the local cluster (numba kernels hold the GIL)."""
    plan = plan_sweep(SCENE, ["solver.duration=0.002"], ["solver.atol=1e-9,2e-9"], out=tmp_path / "sw")
    with distributed.Client(processes=False, n_workers=1, threads_per_worker=1, dashboard_address=":0") as c:
        records = run_sweep(plan, c, poll_s=0.1)
    assert [r["status"] for r in records] == ["done", "done"], [r.get("error") for r in records]
    assert sorted(r["stages"]["quasistatic"] for r in records) == ["computed", "from store"]
    rows = read_table(gather(plan, records)["table"])
    for row in rows:
        assert row["cage_class"] in CAGE_CLASSES
        assert row["duration"] == 0.002 and math.isfinite(row["cage_speed_mean"])
    assert (tmp_path / "sw" / "stability_map.png").is_file()
