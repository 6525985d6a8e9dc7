"""A sweep whose runs end before the cage settles says so wherever its classes are read: a
`too_short_to_settle` column of results.csv, the console table, the map's title and a Python
warning from `gather` (docs/reliability.md). The classes of such points describe a start-up
transient, not a regime."""

from __future__ import annotations

import dataclasses
import functools

import pytest
from rich.console import Console

from bearingsim.pipeline.staging.artefacts import atomic_write_json
from bearingsim.pipeline.staging.runner import Stage
from bearingsim.pipeline.sweep import stability_map
from bearingsim.pipeline.sweep.console import print_results
from bearingsim.pipeline.sweep.driver import gather, plan_sweep, run_sweep
from bearingsim.pipeline.sweep.point_runner import run_point
from bearingsim.pipeline.sweep.table import read_table

distributed = pytest.importorskip("distributed")
SHORT = "run too short to settle: the settled window (t >= 0.001 s) holds 0.1 cage revolutions (< 10)"


def _simulate(ctx):
    """A summary like a short run's for moment 300, like a settled run's for 600."""
    short = ctx.scene.load.moment < 500
    atomic_write_json(ctx.out_dir / "summary.json", {
        "duration": 0.005 if short else 0.8, "cage_speed_mean": 143.7, "cage_speed_variation": 0.01,
        "cage_metal_contact_fraction": 0.0, "cage_contact_angle_spread": None, "cage_whirl_ratio": 0.0,
        "burn_zone_sector": None, "warnings": [SHORT] if short else []})


STAGES = [Stage("simulate", (), lambda s: True, lambda s: {"load": dataclasses.asdict(s.load)}, _simulate, "")]


@pytest.fixture(scope="module")
def swept(tmp_path_factory):
    plan = plan_sweep("helicopter-b-given-hinge", [], ["load.moment=300,600"],
                      out=tmp_path_factory.mktemp("short") / "sw")
    with distributed.Client(processes=False, n_workers=1, threads_per_worker=1, dashboard_address=":0") as c:
        records = run_sweep(plan, c, poll_s=0.05, point_function=functools.partial(run_point, stages=STAGES))
    assert [r["status"] for r in records] == ["done", "done"], records
    return plan, records


def test_the_table_the_map_and_python_carry_the_warning(swept, monkeypatch):
    plan, records = swept
    titles = []
    real = stability_map.plot_stability_map
    monkeypatch.setattr(stability_map, "plot_stability_map",
                        lambda *a, **k: titles.append(k["title"]) or real(*a, **k))
    with pytest.warns(UserWarning, match="1 of 2 points ran too short to settle"):
        paths = gather(plan, records)
    rows = read_table(paths["table"])
    assert [r["too_short_to_settle"] for r in rows] == ["True", "False"]
    assert "RUN TOO SHORT TO SETTLE" in titles[0]


def test_the_console_table_marks_the_points(swept, tmp_path):
    plan, records = swept
    rows = read_table(gather(plan, records, warn=False)["table"])
    console = Console(record=True, width=200, file=open(tmp_path / "out.txt", "w"))
    print_results(rows, plan.varied, console)
    text = console.export_text()
    assert text.count("(too short to settle)") == 1
    assert "warning: 1 of 2 points ran too short to settle" in text and "solver.duration" in text


def test_settled_sweeps_stay_quiet(swept, recwarn):
    plan, records = swept
    settled = [r for r in records if not r["summary"]["warnings"]]
    one = dataclasses.replace(plan, points=plan.points[1:], requests=plan.requests[1:])
    rows = read_table(gather(one, settled)["table"])
    assert rows[0]["too_short_to_settle"] == "False"
    assert not [w for w in recwarn if "too short" in str(w.message)]
