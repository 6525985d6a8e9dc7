"""docs/scenes.md is generated from the scene dataclasses' metadata: it must be current, and
every key must say what it means."""

from __future__ import annotations

from pathlib import Path

from bearingsim.pipeline.scene.reference import render

DOC = Path(__file__).resolve().parents[1] / "docs" / "scenes.md"


def test_docs_scenes_md_is_current():
    assert DOC.read_text(encoding="utf-8") == render(), (
        "docs/scenes.md is stale: regenerate it with "
        "`python -m bearingsim.pipeline.scene.reference > docs/scenes.md`")


def test_every_key_has_a_meaning():
    empty = [line.split("|")[1].strip() for line in render().splitlines()
             if line.startswith("| `") and line.rstrip().endswith("|  |")]
    assert not empty, f"scene keys without a 'doc' in their field metadata: {empty}"


def test_every_built_in_scene_key_is_documented():
    import tomllib

    from bearingsim.pipeline.scene.load import builtin_scene_names, read_scene_table

    text = render()
    for name in builtin_scene_names():
        table, _ = read_scene_table(name)
        for section, body in table.items():
            if not isinstance(body, dict) or section in ("materials", "sweep"):
                continue
            for key in body:
                assert f"`{key}`" in text, f"{name}: [{section}] {key} is not in docs/scenes.md"
    assert tomllib  # the scenes are TOML
