"""Results table and stability map of a sweep, from hand-made rows (no runs)."""

from __future__ import annotations

import math

import pytest

from bearingsim.pipeline.scene.cage_classes import CageClassThresholds
from bearingsim.pipeline.sweep.points import SweepPoint
from bearingsim.pipeline.sweep.stability_map import axis_label, map_axes, plot_stability_map
from bearingsim.pipeline.sweep.table import SUMMARY_COLUMNS, read_table, result_row, write_table


def test_map_axes_prefer_moment_and_speed():
    assert map_axes(["hinge.damping_ratio_time", "speed.inner_rpm", "load.moment"]) == ("load.moment", "speed.inner_rpm")
    assert map_axes(["solver.atol"]) == ("solver.atol", None)
    assert map_axes(["load.moment", "speed.inner_rpm"], map_x="speed.inner_rpm") == ("speed.inner_rpm", "load.moment")
    with pytest.raises(ValueError, match="not varied"):
        map_axes(["load.moment"], map_y="speed.inner_rpm")


def test_axis_labels_carry_scene_units():
    assert axis_label("load.moment") == "load.moment [N.m]"
    assert axis_label("speed.inner_rpm") == "speed.inner_rpm [rev/min]"
    assert axis_label("bearing.ball_count") == "bearing.ball_count"


def record(metal, spread=0.2):
    return {"status": "done", "error": None, "summary": {
        "duration": 0.1, "cage_speed_mean": 143.7, "cage_speed_variation": 0.01, "steps": 100,
        "cage_metal_contact_fraction": metal, "cage_contact_angle_spread": spread,
        "cage_whirl_ratio": 0.0, "burn_zone_sector": [0.5, 1.0]}}


def test_table_round_trip_with_failed_and_pending_points(tmp_path):
    limits = CageClassThresholds()
    pts = [SweepPoint((("load.moment", m), ("physics.cage_race", c))) for m in (0.0, 600.0) for c in ("hybrid", "dry")]
    recs = [record(0.0, None), record(0.9), {"status": "failed", "error": "SceneError: boom", "summary": None}, None]
    rows = [result_row(p, r, tmp_path / p.id, limits) for p, r in zip(pts, recs)]
    write_table(rows, tmp_path)
    back = read_table(tmp_path / "results.csv")
    assert [r["status"] for r in back] == ["done", "done", "failed", "pending"]
    assert [r["cage_class"] for r in back] == ["centred", "crushed", "failed", "pending"]
    # positions in degrees in the table (summary.json's 0.5 and 1.0 rad)
    assert back[1]["burn_zone_start"] == pytest.approx(math.degrees(0.5), rel=1e-12)
    assert back[1]["burn_zone_end"] == pytest.approx(math.degrees(1.0), rel=1e-12)
    header = (tmp_path / "results.csv").read_text().splitlines()[0].split(",")
    # every number carries its unit; text columns (ids, classes, messages) none
    assert {"load.moment [N m]", "cage_speed_mean [rad/s]", "burn_zone_start [degree]",
            "cage_metal_contact_fraction [1]", "duration [s]"} <= set(header)
    assert {"point_id", "status", "physics.cage_race", "cage_class", "risk", "warnings", "error", "run_dir"} <= set(header)
    assert all("[" in h for h in header if h.split(" [")[0] in SUMMARY_COLUMNS)
    assert back[2]["error"] == "SceneError: boom" and back[0]["error"] is None
    assert back[1]["physics.cage_race"] == "dry" and back[1]["load.moment"] == 0.0


@pytest.mark.parametrize("varied, values", [
    (["load.moment", "speed.inner_rpm"], [(m, s) for m in (0.0, 200.0, 400.0, 600.0) for s in (2000.0, 6000.0)]),
    (["load.moment", "speed.inner_rpm"], [(0.0, 2000.0), (300.0, 3060.0), (600.0, 6000.0), (450.0, 2500.0)]),
    (["load.moment"], [(0.0,), (300.0,), (600.0,)]),
    (["load.moment", "speed.inner_rpm", "physics.cage_race"],
     [(m, s, c) for m in (0.0, 600.0) for s in (2000.0, 6000.0) for c in ("hybrid", "dry")]),
])
def test_map_draws_grids_scattered_points_and_panels(tmp_path, varied, values):
    limits = CageClassThresholds()
    rows = []
    for vals in values:
        point = SweepPoint(tuple(zip(varied, vals)))
        rows.append(result_row(point, record(vals[0] / 700.0), tmp_path, limits))
    out = plot_stability_map(rows, varied, tmp_path / "map.png")
    assert out.stat().st_size > 5_000


def test_grid_cells_paint_nothing_beyond_the_swept_range():
    """Sweeping 0 and 600 N·m painted -300..900 N·m: the cells now end at the outermost
    values, and the axes keep a margin round them."""
    import matplotlib

    matplotlib.use("Agg")
    import numpy as np
    from matplotlib.figure import Figure

    from bearingsim.pipeline.sweep.stability_map import _grid_cells

    ax = Figure().add_subplot()
    xs, ys = [0.0, 600.0, 0.0, 600.0], [2000.0, 2000.0, 6000.0, 6000.0]
    assert _grid_cells(ax, xs, ys, ["C0", "C1", "C2", "C3"])
    corners = np.asarray(ax.collections[0].get_coordinates())
    assert corners[..., 0].min() == 0.0 and corners[..., 0].max() == 600.0
    assert corners[..., 1].min() == 2000.0 and corners[..., 1].max() == 6000.0
    assert ax.get_xlim() == (-30.0, 630.0) and ax.get_ylim() == (1800.0, 6200.0)
