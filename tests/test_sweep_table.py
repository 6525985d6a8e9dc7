"""The sweep's results table (pipeline/sweep/table.py, driver.table_rows): text stays text when
read back, every varied key has a column with each point's value, and a point's validity
warnings reach its row."""

from __future__ import annotations

from pathlib import Path

from bearingsim.pipeline.scene.cage_classes import CageClassThresholds
from bearingsim.pipeline.sweep.driver import plan_sweep, table_rows
from bearingsim.pipeline.sweep.points import SweepPoint
from bearingsim.pipeline.sweep.table import read_table, result_row, write_table

SCENE_TEXT = (Path(__file__).parents[1] / "pipeline" / "scenes" / "helicopter-b-given-hinge.toml").read_text()


def test_a_point_id_that_looks_like_a_number_is_read_back_as_text(tmp_path):
    """A 12-digit hex id with one inner `e` parses as a float (489815446e53 = 4.9e61): read
    as a number, it broke the console table and the API's rows."""
    rows = [{"point_id": "489815446e53", "status": "done", "load.moment": 50.0, "cage_class": "centred",
             "cage_speed_mean": 143.5, "warnings": None},
            {"point_id": "123456789012", "status": "failed", "load.moment": 250.0, "cage_class": "failed",
             "cage_speed_mean": None, "warnings": "1e3"}]
    [csv_path, *_] = write_table(rows, tmp_path)
    back = read_table(csv_path)
    assert [r["point_id"] for r in back] == ["489815446e53", "123456789012"]
    assert [r["load.moment"] for r in back] == [50.0, 250.0] and back[0]["cage_speed_mean"] == 143.5
    assert back[1]["warnings"] == "1e3" and back[1]["cage_speed_mean"] is None


def test_list_mode_rows_have_every_varied_key_with_the_points_scene_value(tmp_path):
    """docs/sweeps.md's list mode: a point that leaves speed.inner_rpm out runs at the scene's
    3060 rev/min, and the table says so in a column of its own."""
    scene = tmp_path / "list.toml"
    scene.write_text(SCENE_TEXT + '\n[sweep]\nmode = "list"\npoints = [{ "load.moment" = 100 }, '
                                  '{ "load.moment" = 350, "speed.inner_rpm" = 6000 }]\n')
    plan = plan_sweep(str(scene), [], [], out=tmp_path / "sw")
    rows = table_rows(plan, {})
    assert [(r["load.moment"], r["speed.inner_rpm"]) for r in rows] == [(100, 3060.0), (350, 6000)]
    [csv_path, *_] = write_table(rows, tmp_path)
    header = csv_path.read_text().splitlines()[0]
    assert "speed.inner_rpm [rev/min]" in header
    assert [r["speed.inner_rpm"] for r in read_table(csv_path)] == [3060.0, 6000.0]


def test_columns_are_the_union_of_the_rows(tmp_path):
    rows = [{"point_id": "a", "load.moment": 1.0}, {"point_id": "b", "load.moment": 2.0, "speed.inner_rpm": 9.0}]
    [csv_path, *_] = write_table(rows, tmp_path)
    assert [r["speed.inner_rpm"] for r in read_table(csv_path)] == [None, 9.0]


def test_validity_warnings_of_a_point_reach_its_row(tmp_path):
    """A point at 100 kN·m read "done, pressed" with none of its quasi-static warnings."""
    point = SweepPoint((("load.moment", 1e5),))
    record = {"status": "done", "summary": {"duration": 0.02, "warnings": ["run too short to settle"]},
              "validity": ["quasistatic: load.moment: 7.1 GPa contact pressure, beyond the ISO 76 rating"]}
    row = result_row(point, record, tmp_path, CageClassThresholds())
    assert row["warnings"] == ("run too short to settle; quasistatic: load.moment: 7.1 GPa contact pressure, "
                               "beyond the ISO 76 rating")
