"""Scene loading, both geometry forms, derived geometry and every kind of bad input."""

from __future__ import annotations

import copy
import math

import pytest

from bearingsim.dynamics.geometry import BearingGeometry
from bearingsim.pipeline.scene.load import (
    apply_overrides,
    builtin_scene_names,
    load_scene,
    read_scene_table,
    resolve,
)
from bearingsim.pipeline.scene.schema import SceneError


@pytest.fixture(scope="module")
def table_b() -> dict:
    """helicopter-b without [lubricant]/[fe] so these tests do not depend on other stages."""
    table, _ = read_scene_table("helicopter-b-given-hinge")
    table = copy.deepcopy(table)
    table.pop("lubricant", None)
    table["physics"].update(traction="coulomb", cage_race="dry")  # a dry scene
    return table


def test_builtin_scenes_present():
    names = builtin_scene_names()
    for required in ("helicopter-a", "helicopter-b", "helicopter-b-given-hinge"):
        assert required in names


def test_reference_derived_geometry(table_b):
    """docs/model.md §2 'Derived (check these in a unit test)' — numbers computed by hand there."""
    b = resolve(table_b).bearing
    assert b.inner_groove_bottom_diameter == pytest.approx(0.138894, abs=1e-9)
    assert b.outer_groove_bottom_diameter == pytest.approx(0.177112, abs=1e-9)
    assert b.pitch_diameter == pytest.approx(0.158003, abs=1e-9)
    assert b.curvature_center_distance == pytest.approx(0.609e-3, abs=1e-12)
    assert b.curvature_center_radial_offset == pytest.approx(0.55e-3, abs=1e-12)
    assert math.degrees(b.free_contact_angle) == pytest.approx(25.43, abs=0.005)
    assert b.diametral_clearance == pytest.approx(0.118e-3, abs=1e-12)


def test_reference_masses_and_cage_guide(table_b):
    """docs/model.md §2: ball ≈ 28.4 g, cage ≈ 0.36 kg, guide clearance 0.29 mm, L ≈ 7.6 mm."""
    s = resolve(table_b)
    assert s.bearing.ball_mass(s.materials.ball) == pytest.approx(0.0284, rel=2e-3)
    assert s.cage.mass(s.materials.cage, s.bearing) == pytest.approx(0.36, rel=0.01)
    assert s.cage.guide_clearance(s.bearing) == pytest.approx(0.29e-3, abs=1e-9)
    assert s.cage.guide_land_length(s.bearing) == pytest.approx(7.6e-3, rel=0.01)


def test_catalogue_form_resolves_to_same_geometry(table_b):
    """Form 2 built from form 1's derived numbers gives back form 1's geometry."""
    ref = resolve(table_b).bearing
    t = copy.deepcopy(table_b)
    for k in ("inner_groove_center_diameter", "outer_groove_center_diameter",
              "inner_groove_radius", "outer_groove_radius"):
        del t["bearing"][k]
    t["bearing"].update(pitch_diameter=ref.pitch_diameter, inner_conformity=ref.inner_conformity,
                        outer_conformity=ref.outer_conformity,
                        diametral_clearance=ref.diametral_clearance)
    got = resolve(t).bearing
    for name in ("inner_groove_center_diameter", "outer_groove_center_diameter",
                 "inner_groove_radius", "outer_groove_radius"):
        assert getattr(got, name) == pytest.approx(getattr(ref, name), rel=1e-12)


def test_harris_209_free_contact_angle():
    """Harris & Kotzalas, Rolling Bearing Analysis 5th ed., 209 DGBB example: alpha_0 = 9.86 deg,
    from D = 12.7 mm, f = 0.52, P_d = 0.015 mm (catalogue form)."""
    s = load_scene("deep-groove-209")
    assert math.degrees(s.bearing.free_contact_angle) == pytest.approx(9.86, abs=0.01)
    assert s.cage is None and s.lubricant is None and s.hinge.source == "none"
    # docs/scenes.md: without [lubricant] the contacts are dry
    assert (s.physics.traction, s.physics.cage_race, s.physics.ehd_film) == ("coulomb", "dry", False)


def test_overrides_apply_and_validate(table_b):
    t = apply_overrides(table_b, ["load.moment=250", "solver.duration=0.05", "name=short"])
    s = resolve(t)
    assert s.load.moment == 250.0 and s.solver.duration == 0.05 and s.name == "short"
    assert table_b["load"]["moment"] == 430.0  # the original table is untouched


def _bad(table_b, edit) -> SceneError:
    t = copy.deepcopy(table_b)
    edit(t)
    with pytest.raises(SceneError) as info:
        resolve(t)
    return info.value


# Each bad-input kind: (id, edit, substrings the message must contain: key, value or hint)
BAD_INPUTS = [
    ("missing key", lambda t: t["bearing"].pop("ball_diameter"), ["bearing.ball_diameter", "missing", "[m]"]),
    ("missing table", lambda t: t.pop("load"), ["load", "missing"]),
    ("unknown key", lambda t: t["load"].update(momnt=3.0), ["load.momnt", "unknown", "moment"]),
    ("unknown table", lambda t: t.update(bearings={}), ["bearings", "unknown"]),
    ("negative diameter", lambda t: t["bearing"].update(ball_diameter=-0.019), ["bearing.ball_diameter", "-0.019", "> 0", "[m]"]),
    ("pocket smaller than ball", lambda t: t["cage"].update(pocket_diameter=0.018), ["pocket_diameter", "0.018", "ball"]),
    ("both geometry forms", lambda t: t["bearing"].update(pitch_diameter=0.158), ["form 1", "form 2", "never both"]),
    ("groove radius < ball radius", lambda t: t["bearing"].update(inner_groove_radius=0.009), ["inner_groove_radius", "0.009", "ball radius"]),
    ("zero balls", lambda t: t["bearing"].update(ball_count=0), ["bearing.ball_count", "0", ">= 3"]),
    ("balls do not fit", lambda t: t["bearing"].update(ball_count=30), ["ball_count = 30", "do not fit", "at most 25"]),
    ("NaN", lambda t: t["load"].update(axial=float("nan")), ["load.axial", "nan", "finite", "[N]"]),
    ("wrong type", lambda t: t["bearing"].update(ball_count="22"), ["bearing.ball_count", "'22'", "integer"]),
    ("float for integer", lambda t: t["bearing"].update(ball_count=22.0), ["bearing.ball_count", "integer"]),
    ("bad choice", lambda t: t["physics"].update(traction="magic"), ["physics.traction", "magic", "eyring"]),
    ("alpha out of range", lambda t: t["solver"].update(alpha=0.5), ["solver.alpha", "0.5", "<= 0.333"]),
    ("step bounds inconsistent", lambda t: t["solver"].update(min_step=1e-5), ["min_step", "first_step", "max_step"]),
    ("poisson ratio", lambda t: t["materials"]["ball"].update(poisson_ratio=0.6), ["materials.ball.poisson_ratio", "0.6", "< 0.5"]),
    ("cage without material", lambda t: t["materials"].pop("cage"), ["materials.cage", "required"]),
    ("given hinge without values", lambda t: t["hinge"].pop("bending"), ["hinge", "bending"]),
    ("hinge vector length", lambda t: t["hinge"].update(translational=[1e9, 1e9]), ["translational", "3 values"]),
    ("eyring without lubricant", lambda t: t["physics"].update(traction="eyring"), ["physics.traction", "[lubricant]"]),
    ("film needed by cage model", lambda t: t["physics"].update(cage_race="hybrid"), ["physics.cage_race", "[lubricant]"]),
    ("boolean wrong type", lambda t: t["physics"].update(centrifugal="yes"), ["physics.centrifugal", "true or false"]),
    ("cage wider than land", lambda t: t["cage"].update(radial_thickness=0.0082), ["outer_shoulder_diameter", "cage outside diameter"]),
]


@pytest.mark.parametrize("edit,needles", [(e, n) for _, e, n in BAD_INPUTS], ids=[i for i, _, _ in BAD_INPUTS])
def test_bad_input_names_key_value_and_allowed(table_b, edit, needles):
    message = str(_bad(table_b, edit))
    for needle in needles:
        assert needle in message, f"{needle!r} not in error message: {message}"


def test_bad_override_syntax(table_b):
    with pytest.raises(SceneError, match="KEY=VALUE"):
        apply_overrides(table_b, ["load.moment"])


def test_unknown_scene_name_lists_builtins():
    with pytest.raises(SceneError, match="helicopter-b"):
        load_scene("no-such-scene")


def test_geometry_rejects_direct_construction_errors():
    with pytest.raises(ValueError, match="outer_groove_radius"):
        BearingGeometry(0.01905, 22, 0.1584, 0.1573, 0.009753, 0.009)


def test_a_built_in_name_wins_over_a_folder_of_that_name(tmp_path, monkeypatch):
    """`bearingsim run helicopter-b` from a folder holding the run directory helicopter-b/."""
    from bearingsim.pipeline.scene.load import load_scene

    (tmp_path / "helicopter-b").mkdir()
    monkeypatch.chdir(tmp_path)
    assert load_scene("helicopter-b").name == "helicopter-b"
