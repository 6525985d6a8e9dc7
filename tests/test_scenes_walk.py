"""Every scene the package ships (pipeline/scenes/ and its subfolders) keeps the rule of
docs/reliability.md: a scene that `check` passes (exit 0) is not refused by `simulate`, and a
scene that `simulate` would refuse makes `check` say so in its first line with exit code 4.

One test runs, for every scene, what `simulate` does before its first time step (the run's
screen, the `[physics]` screen, the quasi-static start and the dynamic model's parameters); the
other runs `simulate` itself for 2 ms. A scene whose hinge comes from the FE model is given its
hinge by hand (the reference values of docs/model.md §2) so that no identification runs;
`check` has screened its `[fe]` table already (session.fe_findings)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

import bearingsim
from bearingsim.pipeline.cli.commands import EXIT_NOT_SIMULABLE, EXIT_SCENE, app
from bearingsim.pipeline.scene.load import builtin_scene_names
from bearingsim.pipeline.scene.schema import SceneError
from bearingsim.pipeline.stages.session import check_before_solving
from bearingsim.pipeline.stages.simulate import build_model

SCENES_DIR = Path(bearingsim.pipeline.__file__).parent / "scenes"
SCENES = sorted(SCENES_DIR.rglob("*.toml"))
GIVEN_HINGE = ["hinge.source=given", "hinge.translational=[1e9, 1e9, 1e9]", "hinge.bending=[1e5, 1e5]"]
SHORT = ["solver.duration=0.002", "output.figures=false"]
runner = CliRunner()


def _id(path: Path) -> str:
    return str(path.relative_to(SCENES_DIR).with_suffix(""))


def _check(path: Path):
    return runner.invoke(app, ["check", str(path)])


def _without_fe(path: Path) -> list[str]:
    """Overrides that give an FE-hinged scene its hinge by hand (no identification)."""
    return GIVEN_HINGE if bearingsim.load_scene(path).hinge.source == "fe" else []


def test_the_walk_finds_every_built_in_scene():
    found = {_id(p) for p in SCENES}
    assert set(builtin_scene_names()) <= found
    assert any(name.startswith("stability/") for name in found)  # the subfolder is walked too
    # the gallery of cage guidances (docs/validation.md §15)
    assert {"acbb-7210-inner-guided", "deep-groove-6205-ball-guided", "turbine-thrust-120"} <= found


@pytest.mark.parametrize("path", SCENES, ids=_id)
def test_a_scene_check_passes_gets_through_the_screens_of_simulate(path):
    result = _check(path)
    assert result.exit_code in (0, EXIT_NOT_SIMULABLE), result.output[-2000:]
    scene = bearingsim.load_scene(path, _without_fe(path))
    if result.exit_code == EXIT_NOT_SIMULABLE:
        first = result.stderr.splitlines()[0]
        assert first.startswith("simulate and run would refuse this scene")
        with pytest.raises(SceneError) as refused:
            check_before_solving(scene, ["simulate"])
        assert refused.value.key in first  # check named the key simulate refuses
        return
    check_before_solving(scene, ["simulate"])  # raises what simulate would refuse
    params, start = build_model(scene)  # the quasi-static start and the model, as simulate builds them
    assert params.ball_count == scene.bearing.ball_count and start


def test_a_scene_check_marks_is_refused_by_simulate_before_any_stage(tmp_path):
    """The other half of the rule, on the one built-in scene check marks (exit 4): simulate
    refuses it as a scene error naming the same key, and writes no stage."""
    marked = [p for p in SCENES if _check(p).exit_code == EXIT_NOT_SIMULABLE]
    assert [_id(p) for p in marked] == ["deep-groove-209"]  # quasi-static only: no cage, no ring masses
    result = runner.invoke(app, ["simulate", str(marked[0]), "--out", str(tmp_path / "run")])
    assert result.exit_code == EXIT_SCENE
    assert "bearing.inner_bore_diameter" in result.stderr
    assert not (tmp_path / "run" / "quasistatic").exists()


@pytest.mark.parametrize("path", SCENES, ids=_id)
def test_a_scene_check_passes_simulates_2_ms(path, tmp_path):
    if _check(path).exit_code != 0:
        pytest.skip("check marks this scene as refused by simulate (tested above)")
    sets = [a for o in (*_without_fe(path), *SHORT) for a in ("--set", o)]
    result = runner.invoke(app, ["simulate", str(path), "--out", str(tmp_path / "run"), *sets])
    assert result.exit_code == 0, result.output[-3000:]
    summary = json.loads((tmp_path / "run" / "simulate" / "summary.json").read_text(encoding="utf-8"))
    assert summary["duration"] == pytest.approx(0.002, abs=1e-6)
