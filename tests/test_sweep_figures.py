"""Sweeps can skip each point's figures: `[sweep] figures = false` (or `--no-figures`) runs
every point with the scene key `output.figures = false`, without changing the points' ids or
scene hashes (figures are output: switching them reruns no finished point)."""

from __future__ import annotations

from pathlib import Path

import pytest

from bearingsim.pipeline.scene.schema import SceneError
from bearingsim.pipeline.sweep.driver import plan_sweep
from bearingsim.pipeline.sweep.point_runner import point_run_table, run_point
from bearingsim.pipeline.scene.sweep_section import build_sweep_section, with_command_line

SCENE = "helicopter-b-given-hinge"


def test_sweep_table_and_command_line_option():
    assert build_sweep_section({}).figures is True
    section = build_sweep_section({"figures": False})
    assert section.figures is False
    assert with_command_line(section, [], None, None).figures is False  # not given: the scene's
    assert with_command_line(section, [], None, None, figures=True).figures is True
    with pytest.raises(SceneError, match="sweep.figures: expected true or false"):
        build_sweep_section({"figures": "no"})


def test_no_figures_keeps_point_ids_and_hashes(tmp_path):
    drawn = plan_sweep(SCENE, [], ["load.moment=100,300"], out=tmp_path / "sw")
    bare = plan_sweep(SCENE, [], ["load.moment=100,300"], out=tmp_path / "sw", figures=False)
    assert [r.figures for r in drawn.requests] == [True, True]
    assert [r.figures for r in bare.requests] == [False, False]
    assert [(r.point_id, r.scene_hash) for r in bare.requests] == [(r.point_id, r.scene_hash) for r in drawn.requests]
    assert point_run_table(bare.requests[0])["output"]["figures"] is False
    assert point_run_table(drawn.requests[0]) == drawn.requests[0].table


def test_a_no_figures_point_writes_results_but_no_png(tmp_path):
    sets = ["solver.duration=0.002"]
    bare = plan_sweep(SCENE, sets, ["load.moment=300"], out=tmp_path / "bare", figures=False).requests[0]
    drawn = plan_sweep(SCENE, sets, ["load.moment=300"], out=tmp_path / "drawn").requests[0]
    for request in (bare, drawn):
        record = run_point(request)
        assert record["status"] == "done", record["error"]
    bare_dir, drawn_dir = Path(bare.run_dir), Path(drawn.run_dir)
    assert not sorted(bare_dir.rglob("*.png"))
    assert (drawn_dir / "simulate" / "cage_orbit.png").is_file()  # the same point with figures on
    for f in ("timeseries.h5", "impacts.csv", "summary.json"):
        assert (bare_dir / "simulate" / f).is_file()
    assert "figures = false" in (bare_dir / "scene.toml").read_text()
