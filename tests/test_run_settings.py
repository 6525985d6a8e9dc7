"""One definition per setting: the scene's `[physics]` table is built straight into the
model's `ModelOptions` and `[solver]` into the integrator's `HHTSettings` (plus the run's
`duration`), so every key the scene accepts reaches the code that uses it; a key the
dynamic run cannot honour is refused by name."""

from __future__ import annotations

import dataclasses

import pytest

from bearingsim.dynamics.bearing import ModelOptions
from bearingsim.dynamics.multibody.settings import HHTSettings, JacobianReuse
from bearingsim.pipeline.scene.load import load_scene
from bearingsim.pipeline.scene.schema import SceneError

SCENE = "helicopter-b-given-hinge"


def test_the_scene_builds_the_settings_objects_themselves():
    s = load_scene(SCENE, ["solver.max_step=1e-6", "solver.max_newton_iter=5", "solver.reuse_jacobian=step",
                           "physics.pocket_restitution=0.6"])
    assert isinstance(s.solver, HHTSettings) and isinstance(s.physics, ModelOptions)
    assert (s.solver.max_step, s.solver.max_newton_iter, s.solver.reuse_jacobian) == (1e-6, 5, JacobianReuse.STEP)
    assert s.physics.pocket_restitution == 0.6


def test_every_integrator_setting_is_a_scene_key_with_a_doc():
    """No field defined twice: the [solver] table has exactly the integrator's fields plus
    `duration`, each with its meaning (docs/scenes.md is generated from them)."""
    from bearingsim.pipeline.scene.sections import SolverSettings

    names = [f.name for f in dataclasses.fields(SolverSettings)]
    assert names == [f.name for f in dataclasses.fields(HHTSettings)] + ["duration"]
    for cls in (SolverSettings, ModelOptions):
        assert all(f.metadata.get("doc") for f in dataclasses.fields(cls)), cls


@pytest.mark.parametrize("override, needles", [
    ("solver.reuse_jacobian=sometimes", ["solver.reuse_jacobian", "sometimes", "adaptive"]),
    ("solver.rtol=1.5", ["solver.rtol", "1.5", "< 1"]),
    ("solver.max_step=0.9", ["max_step", "duration"]),
    ("physics.cage_race_lands=3", ["physics.cage_race_lands", "3", "<= 2"]),
])
def test_bad_settings_are_refused_with_the_key(override, needles):
    with pytest.raises(SceneError) as info:
        load_scene(SCENE, [override])
    for needle in needles:
        assert needle in str(info.value)


def test_settings_built_in_code_are_checked_against_the_same_metadata():
    with pytest.raises(ValueError, match=r"physics.traction = 'magic' is not allowed"):
        ModelOptions(traction="magic")
    with pytest.raises(ValueError, match=r"physics.min_film = -1.0 \[m\] is out of range; allowed: gt 0"):
        ModelOptions(min_film=-1.0)
    with pytest.raises(ValueError, match=r"solver.newton_tol = 0.0 \[-\] is out of range"):
        HHTSettings(newton_tol=0.0)
    assert HHTSettings(reuse_jacobian="newton").reuse_jacobian is JacobianReuse.NEWTON


@pytest.mark.parametrize("override, key", [
    ("physics.centrifugal=false", "physics.centrifugal"),
])
def test_the_dynamic_run_refuses_what_it_cannot_honour(override, key):
    from bearingsim.pipeline.stages.simulate import check_dynamic_physics

    with pytest.raises(SceneError, match=key):
        check_dynamic_physics(load_scene(SCENE, [override]))
    check_dynamic_physics(load_scene(SCENE))  # the scene as it is runs


def test_a_film_without_a_lubricant_is_refused_by_the_dynamic_run():
    from bearingsim.pipeline.stages.simulate import check_dynamic_physics

    dry = load_scene("deep-groove-209")
    assert dry.lubricant is None and not dry.physics.ehd_film  # the dry default
    with pytest.raises(SceneError, match="physics.ehd_film"):
        check_dynamic_physics(load_scene("deep-groove-209", ["physics.ehd_film=true"]))


def test_a_model_cannot_be_built_without_centrifugal_force():
    from .bearing_fixtures import reference_model

    with pytest.raises(ValueError, match="physics.centrifugal"):
        reference_model(options=ModelOptions(traction="coulomb", cage_race="dry", centrifugal=False))
