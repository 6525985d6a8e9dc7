"""`bearingsim.sweep` from Python (two short real runs, in this process), and the Dask side of
sweeps a user sees: task keys that name the point, lost workers and retried points in the
progress line."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

import bearingsim
from bearingsim.pipeline.sweep.api import vary_strings
from bearingsim.pipeline.sweep.console import status_line
from bearingsim.pipeline.sweep.driver import SweepStatus, WorkerWatch, plan_sweep, task_key

SCENE = "helicopter-b-given-hinge"


def test_vary_accepts_values_ranges_and_strings():
    assert vary_strings({"load.moment": [0, 300.0], "speed.inner_rpm": "2000:6000:3"}) == [
        "load.moment=0,300.0", "speed.inner_rpm=2000:6000:3"]
    assert vary_strings({"physics.cage_race": ["hybrid", "dry"]}) == ['physics.cage_race="hybrid","dry"']
    assert vary_strings("load.moment=0,300") == ["load.moment=0,300"]


def test_sweep_returns_the_table_and_the_map(tmp_path):
    scene = bearingsim.load_scene(SCENE, {"solver.duration": 0.002, "output.figures": False})
    with pytest.warns(UserWarning, match="too short to settle") as caught:
        result = bearingsim.sweep(scene, vary={"load.moment": [200, 430]}, workers=0, out=tmp_path / "sw")
    assert {Path(w.filename).name for w in caught} == {Path(__file__).name}  # at the call, not in the library
    assert result.varied == ["load.moment"] and len(result.rows) == 2
    for row, moment in zip(result.rows, (200.0, 430.0)):
        assert row["status"] == "done" and row["load.moment"] == moment
        assert row["cage_class"] in ("centred", "whirling", "pressed", "crushed", "chaotic")
        assert row["risk"] in ("low", "elevated", "high")
        assert row["duration"] == pytest.approx(0.002, abs=1e-5) and row["cage_speed_mean"] > 100.0
        assert "too short to settle" in row["warnings"]  # 2 ms is far below ten cage revolutions
        summary = json.loads((tmp_path / "sw" / "points" / row["point_id"] / "simulate" / "summary.json").read_text())
        assert row["cage_speed_mean"] == summary["cage_speed_mean"]
    assert result.map.is_file() and result.table.name == "results.csv"
    assert "load.moment [N m]" in result.table.read_text().splitlines()[0]
    assert list(result.column("load.moment")) == [200.0, 430.0]
    assert "2 points over load.moment" in repr(result) and "<table>" in result._repr_html_()
    again = bearingsim.sweep(scene, vary={"load.moment": [200, 430]}, workers=0, out=tmp_path / "sw")
    assert [r["cage_speed_mean"] for r in again.rows] == [r["cage_speed_mean"] for r in result.rows]


def test_task_keys_carry_the_point_values(tmp_path):
    plan = plan_sweep(SCENE, [], ["load.moment=0,300", "speed.inner_rpm=2000"], out=tmp_path / "sw")
    keys = [task_key(r, "tok") for r in plan.requests]
    assert keys[1] == f"bearingsim-point-load.moment=300_speed.inner_rpm=2000-{plan.requests[1].point_id}-tok"
    assert len(set(keys)) == 2


class FakeClient:
    """The two scheduler calls WorkerWatch makes, with workers that can leave."""

    def __init__(self, processing):
        self.processing_now = processing

    def scheduler_info(self):
        return {"workers": {w: {} for w in self.processing_now}}

    def processing(self):
        return self.processing_now


def test_lost_workers_and_retried_points_reach_the_progress_line():
    client = FakeClient({"tcp://a": ["k1", "other"], "tcp://b": ["k2"]})
    watch = WorkerWatch(client)
    watch.poll({"k1", "k2", "k3"})
    assert (watch.lost, watch.retried) == (0, 0)
    client.processing_now = {"tcp://b": ["k2", "k1"]}  # worker a died while running k1
    watch.poll({"k1", "k2", "k3"})
    assert (watch.lost, watch.retried) == (1, 1)
    status = SweepStatus(4, 1, 0, 2, 0, 30.0, 60.0, lost_workers=watch.lost, retried=watch.retried)
    assert "1 worker lost (1 point retried)" in status_line(status)
    assert "lost" not in status_line(SweepStatus(4, 1, 0, 2, 0, 30.0, 60.0))


def test_a_refused_sweep_folder_is_named_as_the_python_argument(tmp_path):
    """From Python there is no --out: the sweep folder is named as sweep()'s `out`."""
    mine = tmp_path / "mine"
    mine.mkdir()
    (mine / "notes.txt").write_text("mine")
    with pytest.raises(bearingsim.OutputRefused) as refused:
        bearingsim.sweep(SCENE, vary={"load.moment": [200, 430]}, workers=0, out=mine)
    message = str(refused.value)
    assert message.startswith(f"out={str(mine)!r}: the directory holds files that are not a bearingsim sweep")
    assert "--out" not in message and sorted(p.name for p in mine.iterdir()) == ["notes.txt"]
