"""Sweep definitions: `--vary` syntax, the scene's `[sweep]` table, expansion
into points, stable ids, and that a `[sweep]` table changes no stage key."""

from __future__ import annotations

import copy

import pytest

from bearingsim.pipeline.scene.load import read_scene_table, resolve
from bearingsim.pipeline.scene.schema import SceneError
from bearingsim.pipeline.stages import STAGES
from bearingsim.pipeline.staging.runner import stage_key
from bearingsim.pipeline.sweep.points import SweepPoint, expand, point_table
from bearingsim.pipeline.scene.sweep_section import build_sweep_section, parse_vary, with_command_line


@pytest.fixture(scope="module")
def base() -> dict:
    return copy.deepcopy(read_scene_table("helicopter-b-given-hinge")[0])


def test_range_is_inclusive_and_evenly_spaced():
    """The README's example: 0:600:13 is 0, 50, ..., 600 N·m."""
    axis = parse_vary("load.moment=0:600:13")
    assert axis.key == "load.moment"
    assert axis.values == tuple(50.0 * i for i in range(13))
    # decimal steps come out as written, not 0.0010000000000000002
    assert parse_vary("solver.duration=0.001:0.003:3").values == (0.001, 0.002, 0.003)
    assert parse_vary("load.moment=250:250:1").values == (250.0,)


def test_list_values_are_toml_literals():
    assert parse_vary("speed.inner_rpm=2000,3060,6000").values == (2000, 3060, 6000)
    assert parse_vary("physics.cage_race=hybrid,dry").values == ("hybrid", "dry")
    assert parse_vary("physics.gyroscopic=true,false").values == (True, False)


@pytest.mark.parametrize("text, fragment", [
    ("load.moment", "KEY=VALUES"),
    ("load.moment=0:600", "start:stop:count"),
    ("load.moment=0:600:2.5", "integer count"),
    ("load.moment=a:600:3", "start:stop:count"),
    ("name=x,y", "not a scene key"),
    ("sweep.name=x", "not a scene key"),
    ("load..moment=1", "not a scene key"),
])
def test_bad_vary_says_what_to_write(text, fragment):
    with pytest.raises(SceneError, match=fragment):
        parse_vary(text)


def test_factorial_and_list_expansion():
    section = with_command_line(build_sweep_section({}), ["load.moment=0:600:3", "speed.inner_rpm=2000,6000"],
                                None, None)
    points = expand(section)
    assert [p.overrides for p in points][:3] == [
        (("load.moment", 0.0), ("speed.inner_rpm", 2000)),
        (("load.moment", 0.0), ("speed.inner_rpm", 6000)),
        (("load.moment", 300.0), ("speed.inner_rpm", 2000)),
    ]
    assert len(points) == 6
    listed = expand(with_command_line(section, ["load.moment=0,300", "speed.inner_rpm=2000,6000"], "list", None))
    assert [dict(p.overrides) for p in listed] == [
        {"load.moment": 0, "speed.inner_rpm": 2000}, {"load.moment": 300, "speed.inner_rpm": 6000}]
    with pytest.raises(SceneError, match="same number of values"):
        expand(with_command_line(section, ["load.moment=0,300,600", "speed.inner_rpm=2000,6000"], "list", None))
    with pytest.raises(SceneError, match="nothing to vary"):
        expand(build_sweep_section({}))


def test_point_id_depends_only_on_its_overrides():
    a = SweepPoint((("load.moment", 300.0), ("speed.inner_rpm", 2000)))
    b = SweepPoint((("speed.inner_rpm", 2000), ("load.moment", 300.0)))
    c = SweepPoint((("load.moment", 350.0), ("speed.inner_rpm", 2000)))
    assert a.id == b.id != c.id
    assert a.set_args() == ["load.moment=300.0", "speed.inner_rpm=2000"]


def test_scene_sweep_table_is_validated(base):
    table = copy.deepcopy(base)
    table["sweep"] = {"name": "moment-speed", "vary": {"load.moment": "0:600:4", "speed.inner_rpm": [2000, 6000]},
                      "thresholds": {"crushed_spread": 0.3}}
    section = build_sweep_section(table["sweep"])
    assert [a.key for a in section.vary] == ["load.moment", "speed.inner_rpm"]
    assert section.thresholds.crushed_spread == 0.3
    assert len(expand(section)) == 8
    listed = build_sweep_section({"mode": "list", "points": [{"load.moment": 100}, {"load.moment": 200}]})
    assert [p.overrides for p in expand(listed)] == [(("load.moment", 100),), (("load.moment", 200),)]
    for bad, key in [({"mode": "random"}, "sweep.mode"), ({"thresholds": {"crushed_spread": -1.0}}, "crushed_spread"),
                     ({"thresholds": {"contact_free": 0.6}}, "contact_free"), ({"speed": 1}, "sweep.speed"),
                     ({"points": [{"load.moment": 1}]}, "sweep.points")]:
        with pytest.raises(SceneError, match=key):
            resolve({**table, "sweep": bad})


def test_sweep_table_changes_no_stage_key(base):
    """The sweep describes how to vary a scene, not the scene: every stage key is the same."""
    plain = resolve(copy.deepcopy(base))
    with_sweep = resolve({**copy.deepcopy(base), "sweep": {"vary": {"load.moment": [0, 600]}}})
    assert "sweep" not in with_sweep.raw
    for stage in STAGES:
        assert stage_key(stage, plain, {}) == stage_key(stage, with_sweep, {})


def test_bad_point_value_names_key_and_point(base):
    point = SweepPoint((("bearing.ball_count", 0),))
    with pytest.raises(SceneError, match=r"bearing\.ball_count.*sweep point bearing\.ball_count=0"):
        point_table(base, point)


def test_fe_identification_key_is_shared_by_load_and_speed_points(tmp_path):
    """the FE identification is computed once when the sweep does not change its
    inputs — every moment/speed point has the same identify key, a mesh-size point not."""
    from bearingsim.pipeline.sweep.driver import plan_sweep

    identify = next(s for s in STAGES if s.name == "identify")
    plan = plan_sweep("helicopter-b", [], ["load.moment=0,600", "speed.inner_rpm=2000,6000"], out=tmp_path)
    keys = {stage_key(identify, resolve(r.table), {}) for r in plan.requests}
    assert len(plan.requests) == 4 and len(keys) == 1
    meshes = plan_sweep("helicopter-b", [], ["fe.mesh_size=0.004,0.006"], out=tmp_path)
    assert len({stage_key(identify, resolve(r.table), {}) for r in meshes.requests}) == 2
