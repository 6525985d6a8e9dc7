"""Scenes are data: every form `load_scene` takes, the exact round trip through `to_toml` and
`to_dict`, one validated `replace`, the typed values beside the operating ones, and the displays."""

from __future__ import annotations

import dataclasses

import pytest

import bearingsim
from bearingsim.pipeline.scene.load import builtin_scene_names, builtin_scene_text


@pytest.mark.parametrize("name", builtin_scene_names())
def test_every_builtin_scene_round_trips_through_toml_and_dict(name):
    d = bearingsim.load_scene(name).to_dict()
    scene = bearingsim.load_scene(d)
    assert bearingsim.load_scene(scene.to_toml()) == scene
    assert bearingsim.load_scene(scene.to_dict()) == scene
    from bearingsim.pipeline.scene.mesh_files import example_for

    if scene.fe is not None and getattr(scene.fe, "mesh_file", None) and example_for(scene.fe.mesh_file):
        return  # its text names an example mesh bearingsim writes, which only a built-in scene finds
    assert bearingsim.load_scene(builtin_scene_text(name)) == scene  # the built-in's own TOML text


def test_replace_raises_what_the_file_raises(tmp_path):
    """The same SceneError text from a bad value given by replace and by the scene file."""
    scene = bearingsim.load_scene("helicopter-b-given-hinge")
    for key, bad in (("solver.duration", -1.0), ("load.radial", -5.0), ("physics.traction", "magic"),
                     ("cage.guidance", "sideways")):
        table = scene.to_dict()
        section, name = key.split(".")
        table[section][name] = bad
        import tomli_w

        path = tmp_path / f"{section}-{name}.toml"
        path.write_text(tomli_w.dumps(table), encoding="utf-8")
        with pytest.raises(bearingsim.SceneError) as from_file:
            bearingsim.load_scene(path)
        with pytest.raises(bearingsim.SceneError) as from_replace:
            scene.replace(**{key: bad})
        assert str(from_replace.value) == str(from_file.value), key
        assert key in str(from_replace.value)


def test_replace_changes_only_what_it_names():
    scene = bearingsim.load_scene("helicopter-b-given-hinge")
    moved = scene.replace(**{"load.moment": 500})
    assert moved.load.moment == 500.0 and scene.load.moment == 430.0
    assert moved.bearing == scene.bearing and moved.solver == scene.solver
    assert scene.replace({"load.moment": 500}) == moved == scene.replace(["load.moment=500"])
    assert bearingsim.load_scene(moved.to_toml()) == moved


def test_dataclasses_replace_is_refused_with_the_way_to_do_it():
    scene = bearingsim.load_scene("helicopter-b-given-hinge")
    with pytest.raises(TypeError, match=r"scene\.replace"):
        dataclasses.replace(scene, load=dataclasses.replace(scene.load, moment=-1e9))


def test_inputs_read_back_as_typed_and_the_operating_values_apart():
    """helicopter-b's ball is 19.05 mm on the drawing (the scene file); at the oil's 100 °C the
    steel ball grows by alpha dT = 11.9e-6 1/K x 80 K (AISI 52100, as test_operating_clearances)."""
    scene = bearingsim.load_scene("helicopter-b-given-hinge")
    assert scene.bearing.ball_diameter == 0.01905
    assert scene.operating.bearing.ball_diameter == pytest.approx(0.01905 * (1 + 11.9e-6 * 80.0), rel=1e-9)
    assert scene.nominal.bearing is scene.bearing


def test_other_forms_and_what_is_not_a_scene():
    text = builtin_scene_text("deep-groove-209")
    assert bearingsim.load_scene(text).name == "deep-groove-209"
    with pytest.raises(bearingsim.SceneError, match="not valid TOML"):
        bearingsim.load_scene("name = 'x'\n[bearing\n")
    with pytest.raises(bearingsim.SceneError, match="a dict"):
        bearingsim.load_scene(42)
    with pytest.raises(bearingsim.SceneError, match="load.moment"):
        bearingsim.load_scene({**bearingsim.load_scene("deep-groove-209").to_dict(), "load": {"moment": None}})


def test_short_repr_and_html_display():
    scene = bearingsim.load_scene("helicopter-b")
    text = repr(scene)
    assert len(text) < 200 and "19.05 mm" in text and "430" in text
    page = scene._repr_html_()
    assert "ball_diameter" in page and "<details" in page and "operating" in page and "µm" in page
