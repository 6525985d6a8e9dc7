"""Stiffness export: the table's 5x5 at the scene speed is the quasi-static stiffness of the
run directory exactly, every listed speed is a fresh quasi-static solve at that speed, the
CSV and JSON carry the same numbers with units, and the hinge is the one the dynamics uses."""

from __future__ import annotations

import csv
import json
import math

import numpy as np
import pytest

import bearingsim
from bearingsim.pipeline.scene.schema import SceneError
from bearingsim.pipeline.stages.quasistatic import solve
from bearingsim.pipeline.stiffness_export import (
    CSV_TERMS,
    DOFS,
    ROSS_TERMS,
    TERMS,
    hinge_of,
    parse_speeds,
    stiffness_table,
)

SCENE = "helicopter-b-given-hinge"  # case b with the hinge given by hand: no FE stage
SPEEDS = [6000.0, 3060.0, 1000.0]  # deliberately not sorted; 3060 is the scene's own speed


@pytest.fixture(scope="module")
def exported(tmp_path_factory):
    run_dir = tmp_path_factory.mktemp("stiffness") / "run"
    scene = bearingsim.load_scene(SCENE)
    table = bearingsim.export_stiffness(scene, run_dir, SPEEDS)
    run = bearingsim.run(scene, run_dir, stages=["quasistatic"])  # the pipeline's own stage
    return scene, run_dir, table, run


def test_scene_speed_row_is_the_quasistatic_stiffness_exactly(exported):
    scene, _, table, run = exported
    assert scene.speed.inner_rpm == 3060.0
    K_run = np.array(run.quasistatic["stiffness"], dtype=float)
    assert run.quasistatic["stiffness_order"] == ["dx", "dy", "dz", "rx", "ry"]
    np.testing.assert_array_equal(table.at(3060.0), K_run)


def test_each_row_is_a_fresh_solve_at_its_speed(exported):
    _, _, table, _ = exported
    np.testing.assert_array_equal(table.speeds_rpm, SPEEDS)  # order as given
    for n, rpm in enumerate(SPEEDS):
        fresh = solve(bearingsim.load_scene(SCENE, {"speed.inner_rpm": rpm}))
        assert fresh.converged and table.converged[n]
        np.testing.assert_array_equal(table.bearing[n], fresh.stiffness)
        assert table.cage_speed[n] == fresh.cage_speed
    # the speed reaches the solve: centrifugal force softens the outer contacts, so the
    # stiffness changes with speed (a table that ignored the speeds would repeat one row)
    assert not np.allclose(table.bearing[0], table.bearing[2], rtol=1e-3, atol=0.0)
    assert table.cage_speed[0] > table.cage_speed[1] > table.cage_speed[2] > 0.0


def test_csv_rows_units_and_round_trip(exported):
    _, run_dir, table, _ = exported
    with open(run_dir / "stiffness" / "stiffness.csv", newline="", encoding="utf-8") as fh:
        rows = list(csv.DictReader(fh))
    assert len(rows) == len(SPEEDS)
    header = list(rows[0])
    assert header[:3] == ["speed [rev/min]", "speed [rad/s]", "converged [1]"]
    assert header[3:8] == ["kxx [N/m]", "kxy [N/m]", "kyx [N/m]", "kyy [N/m]", "kzz [N/m]"]
    assert {"kx_ry [N/rad]", "kry_x [N m/m]", "krx_rx [N m/rad]", "kry_ry [N m/rad]"} <= set(header)
    assert len(CSV_TERMS) == 25 == len(set(CSV_TERMS))
    for n, row in enumerate(rows):
        assert float(row["speed [rev/min]"]) == SPEEDS[n]
        assert float(row["speed [rad/s]"]) == pytest.approx(SPEEDS[n] * 2 * math.pi / 60, rel=1e-15)
        assert row["converged [1]"] == "1"
        K = np.empty((5, 5))
        for key, value in row.items():
            name = key.split(" [")[0]
            if name in TERMS:
                K[TERMS[name]] = float(value)
        np.testing.assert_array_equal(K, table.bearing[n])  # repr floats: exact
        # names are row (force) then column (displacement): kxy = K[0, 1], ROSS's convention.
        # The x-y block is symmetric here, so check the order on the unsymmetric x-ry pair
        assert float(row["kxy [N/m]"]) == table.bearing[n][0, 1]
        assert float(row["kyx [N/m]"]) == table.bearing[n][1, 0]
        assert float(row["kx_ry [N/rad]"]) == table.bearing[n][0, 4] != table.bearing[n][4, 0]
        assert float(row["kry_x [N m/m]"]) == table.bearing[n][4, 0]
        # the given hinge of the scene (1e9 N/m diagonal, 1e5 N.m/rad), the same in every row
        assert float(row["hinge_kxx [N/m]"]) == 1e9 and float(row["hinge_kxy [N/m]"]) == 0.0
        assert float(row["hinge_krx_rx [N m/rad]"]) == 1e5 == float(row["hinge_kry_ry [N m/rad]"])


def test_json_matches_the_table(exported):
    _, run_dir, table, _ = exported
    doc = json.loads((run_dir / "stiffness" / "stiffness.json").read_text(encoding="utf-8"))
    assert doc["order"] == list(DOFS) and doc["damping"] is None
    assert [r["speed_rpm"] for r in doc["rows"]] == SPEEDS
    for n, row in enumerate(doc["rows"]):
        np.testing.assert_array_equal(np.array(row["stiffness"]), table.bearing[n])
    assert doc["hinge"]["source"] == "given"
    np.testing.assert_array_equal(doc["hinge"]["translational"], np.eye(3) * 1e9)
    assert doc["operating_point"] == {"axial_N": 34000.0, "radial_N": 0.0, "moment_Nm": 430.0, "outer_rpm": 0.0}


def test_ross_coefficients(exported):
    _, _, table, _ = exported
    ross = table.ross_coefficients()
    for name, (i, j) in zip(ROSS_TERMS, [(0, 0), (0, 1), (1, 0), (1, 1), (2, 2)]):
        np.testing.assert_array_equal(ross[name], table.bearing[:, i, j])
    np.testing.assert_allclose(ross["frequency"], np.array(SPEEDS) * 2 * math.pi / 60, rtol=1e-15)
    assert all(not ross[c].any() for c in ("cxx", "cyy", "cxy", "cyx"))  # no damping


def test_default_speed_is_the_scenes_and_bad_speeds_are_refused():
    scene = bearingsim.load_scene(SCENE)
    table = stiffness_table(scene)
    np.testing.assert_array_equal(table.speeds_rpm, [3060.0])
    for bad in ([], [float("nan")], ["fast"]):
        with pytest.raises(SceneError, match="speeds"):
            stiffness_table(scene, bad)
    # 60 000 rev/min: centrifugal force drives the inner contact angle over the land
    with pytest.raises(RuntimeError, match="at 60000 rev/min .*land"):
        stiffness_table(scene, [3060.0, 60000.0])
    assert parse_speeds("1000,3060") == [1000.0, 3060.0]
    assert parse_speeds("0:6000:3") == [0.0, 3000.0, 6000.0]
    with pytest.raises(SceneError, match="--speeds"):
        parse_speeds("fast,slow")


def test_fe_hinge_is_read_from_the_identify_stage(tmp_path):
    from bearingsim.fe_model.artefacts import write_hinge_toml

    scene = bearingsim.load_scene("helicopter-b")
    assert scene.hinge.source == "fe"
    with pytest.raises(SceneError, match="identify"):
        hinge_of(scene, tmp_path / "identify")  # not identified yet
    (tmp_path / "identify").mkdir()
    H_u = np.array([[6.5e8, 1e6, 0.0], [1e6, 6.6e8, 0.0], [0.0, 0.0, 5.3e8]])
    write_hinge_toml(tmp_path / "identify" / "hinge.toml", H_u, np.array([8.7e6, 8.8e6]), {})
    hinge = hinge_of(scene, tmp_path / "identify")
    assert hinge["source"] == "fe"
    np.testing.assert_array_equal(hinge["translational"], H_u)
    np.testing.assert_array_equal(hinge["bending"], [8.7e6, 8.8e6])
    assert hinge_of(bearingsim.load_scene("deep-groove-209"), None) is None  # hinge.source = "none"


def _stiffness_command_registered() -> bool:
    from bearingsim.pipeline.cli.commands import app

    return any((c.name or c.callback.__name__) == "stiffness" for c in app.registered_commands)


@pytest.mark.skipif(not _stiffness_command_registered(), reason="`bearingsim stiffness` is not wired yet")
def test_command_line_writes_the_same_table(tmp_path):
    from typer.testing import CliRunner

    from bearingsim.pipeline.cli.commands import app

    result = CliRunner().invoke(app, ["stiffness", SCENE, "--speeds", "1000,3060", "--out", str(tmp_path)])
    assert result.exit_code == 0, result.output
    assert "| 3060 |" in result.output
    with open(tmp_path / "stiffness" / "stiffness.csv", newline="", encoding="utf-8") as fh:
        rows = list(csv.DictReader(fh))
    assert [float(r["speed [rev/min]"]) for r in rows] == [1000.0, 3060.0]
    table = stiffness_table(bearingsim.load_scene(SCENE), [1000.0, 3060.0])
    assert float(rows[1]["kx_ry [N/rad]"]) == table.bearing[1][0, 4]
    bad = CliRunner().invoke(app, ["stiffness", SCENE, "--speeds", "fast", "--out", str(tmp_path / "b")])
    assert bad.exit_code == 2 and "--speeds" in bad.output


def test_json_holds_ross_arguments_as_numbers_and_the_hinge_damping(exported):
    """stiffness.json alone is enough for ROSS: keyword arguments as numbers, one value per
    speed; the hinge element carries G = c_G H (docs/model.md (M.18); the given scene's
    c_G = 1e-6 s and H_u = 1e9 N/m diagonal give 1000 N s/m)."""
    scene, run_dir, table, _ = exported
    doc = json.loads((run_dir / "stiffness" / "stiffness.json").read_text(encoding="utf-8"))
    bearing = doc["ross"]["bearing_element"]
    assert set(bearing) == {*ROSS_TERMS, "cxx", "cxy", "cyx", "cyy", "czz", "frequency"}
    assert all(isinstance(v, float) for values in bearing.values() for v in values)
    np.testing.assert_array_equal(bearing["kxy"], table.bearing[:, 0, 1])
    np.testing.assert_allclose(bearing["frequency"], np.array(SPEEDS) * 2 * math.pi / 60, rtol=1e-15)
    assert all(v == 0.0 for c in ("cxx", "cxy", "cyx", "cyy", "czz") for v in bearing[c])
    assert "not exported" in doc["damping_note"] and "(M.62)" in doc["damping_note"]
    hinge = doc["ross"]["hinge_element"]
    assert scene.hinge.damping_ratio_time == 1e-6
    assert hinge["kxx"] == [1e9] * 3 and hinge["cxx"] == pytest.approx([1000.0] * 3, rel=1e-12)
    assert hinge["cxy"] == [0.0] * 3
    np.testing.assert_allclose(doc["hinge"]["damping_translational"], np.eye(3) * 1e3, rtol=1e-12)
    assert doc["ross"]["speed_range_rpm"] == [1000.0, 6000.0]


def test_docs_ross_example_runs_against_the_json_alone(exported, tmp_path, monkeypatch):
    """docs/stiffness.md's ROSS block, verbatim but for the file's path (skipped without ross)."""
    import re
    from pathlib import Path

    ross = pytest.importorskip("ross")
    _, run_dir, table, _ = exported
    page = (Path(__file__).resolve().parents[1] / "docs" / "stiffness.md").read_text(encoding="utf-8")
    block = re.search(r"<!-- ross-example -->\s*```python\n(.*?)```", page, re.S).group(1)
    code = block.replace("runs/helicopter-b/stiffness/stiffness.json", str(run_dir / "stiffness" / "stiffness.json"))
    assert "import bearingsim" not in code
    namespace: dict = {}
    exec(compile(code, "docs/stiffness.md", "exec"), namespace)  # noqa: S102 - the documented example
    assert isinstance(namespace["bearing"], ross.BearingElement)
    np.testing.assert_allclose(namespace["bearing"].kxx_interpolated(table.speeds_rad_s[1]),
                               table.bearing[1, 0, 0], rtol=1e-9)
