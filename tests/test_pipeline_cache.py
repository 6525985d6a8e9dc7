"""Stage caching: a second run skips, a changed input reruns exactly the dependent stages,
a failing stage leaves nothing half-written, and unneeded stages are left out."""

from __future__ import annotations

import copy
import dataclasses

import pytest

from bearingsim.pipeline.scene.load import variant

from bearingsim.pipeline.staging.artefacts import atomic_write_json, read_manifest
from bearingsim.pipeline.staging.runner import Stage, run_stages
from bearingsim.pipeline.scene.load import read_scene_table, resolve


@pytest.fixture()
def scene():
    table, _ = read_scene_table("helicopter-b-given-hinge")
    table = copy.deepcopy(table)
    table.pop("lubricant", None)
    table["physics"].update(traction="coulomb", cage_race="dry")  # a dry scene
    return resolve(table)


def make_stages(calls: list[str], fail: set[str] = frozenset()) -> list[Stage]:
    """Three stand-in stages shaped like the real ones (identify/quasistatic -> simulate)."""

    def compute(name):
        def run(ctx):
            calls.append(name)
            atomic_write_json(ctx.out_dir / "result.json", {"stage": name})
            if name in fail:
                raise RuntimeError(f"{name} failed on purpose")
            return {"ok": True}
        return run

    return [
        Stage("identify", (), lambda s: s.hinge.source == "fe",
              lambda s: {"fe": None}, compute("identify"), ""),
        Stage("quasistatic", (), lambda s: True,
              lambda s: {"load": dataclasses.asdict(s.load), "bearing": dataclasses.asdict(s.bearing)},
              compute("quasistatic"), ""),
        Stage("simulate", ("identify", "quasistatic"), lambda s: True,
              lambda s: {"solver": dataclasses.asdict(s.solver)}, compute("simulate"), ""),
    ]


def statuses(outcomes):
    return {o.name: o.status for o in outcomes}


def test_second_run_skips_everything(scene, tmp_path):
    calls: list[str] = []
    stages = make_stages(calls)
    first = run_stages(scene, tmp_path, stages, ["simulate"])
    assert statuses(first) == {"identify": "not needed", "quasistatic": "computed", "simulate": "computed"}
    second = run_stages(scene, tmp_path, stages, ["simulate"])
    assert statuses(second) == {"identify": "not needed", "quasistatic": "cached", "simulate": "cached"}
    assert calls == ["quasistatic", "simulate"]
    assert not (tmp_path / "identify").exists(), "a stage the scene does not need wrote files"


def test_changed_input_reruns_exactly_dependents(scene, tmp_path):
    calls: list[str] = []
    stages = make_stages(calls)
    run_stages(scene, tmp_path, stages, ["simulate"])
    calls.clear()
    # a numerical setting: only simulate depends on it
    s2 = scene.replace(**{"solver.duration": 0.05})
    assert statuses(run_stages(s2, tmp_path, stages, ["simulate"]))["quasistatic"] == "cached"
    assert calls == ["simulate"]
    calls.clear()
    # a load: quasistatic depends on it, and simulate through quasistatic's key
    s3 = s2.replace(**{"load.moment": 250.0})
    run_stages(s3, tmp_path, stages, ["simulate"])
    assert calls == ["quasistatic", "simulate"]
    calls.clear()
    # going back to the first inputs is never served from the stale directory
    run_stages(scene, tmp_path, stages, ["simulate"])
    assert calls == ["quasistatic", "simulate"]


def test_force_recomputes(scene, tmp_path):
    calls: list[str] = []
    stages = make_stages(calls)
    run_stages(scene, tmp_path, stages, ["simulate"])
    calls.clear()
    run_stages(scene, tmp_path, stages, ["simulate"], force={"quasistatic"})
    assert calls == ["quasistatic"]  # same key: simulate stays valid


def test_failed_stage_leaves_previous_result_intact(scene, tmp_path):
    calls: list[str] = []
    run_stages(scene, tmp_path, make_stages(calls), ["simulate"])
    key_before = read_manifest(tmp_path / "simulate")["key"]
    s2 = scene.replace(**{"solver.duration": 0.05})
    with pytest.raises(RuntimeError, match="on purpose"):
        run_stages(s2, tmp_path, make_stages(calls, fail={"simulate"}), ["simulate"])
    assert read_manifest(tmp_path / "simulate")["key"] == key_before
    leftovers = [p.name for p in tmp_path.iterdir() if p.name.startswith(".")]
    assert leftovers == [], f"temporary files left behind: {leftovers}"
    # and the changed scene is not served from the old result
    calls.clear()
    run_stages(s2, tmp_path, make_stages(calls), ["simulate"])
    assert calls == ["simulate"]


def test_identify_runs_only_when_hinge_is_fe(scene, tmp_path):
    calls: list[str] = []
    fe_scene = variant(scene, hinge=dataclasses.replace(
        scene.hinge, source="fe", translational=None, bending=None))
    out = run_stages(fe_scene, tmp_path, make_stages(calls), ["simulate"])
    assert statuses(out)["identify"] == "computed"
    assert calls[0] == "identify"


def test_upstream_rerun_invalidates_downstream(scene, tmp_path):
    """The FE inputs reach simulate only through identify's key."""
    calls: list[str] = []
    fe_scene = variant(scene, hinge=dataclasses.replace(
        scene.hinge, source="fe", translational=None, bending=None))
    stages = make_stages(calls)
    run_stages(fe_scene, tmp_path, stages, ["simulate"])
    calls.clear()
    changed = [dataclasses.replace(stages[0], inputs=lambda s: {"fe": {"mesh_size": 0.002}})] + stages[1:]
    run_stages(fe_scene, tmp_path, changed, ["simulate"])
    assert calls == ["identify", "simulate"]


def test_progress_ends_each_computed_stage_at_one(scene, tmp_path):
    """A stage's last progress call is 1.0, so a progress bar finishes (and its clock stops)
    instead of staying at the stage's last message (the quasi-static one stopped at 70 %)."""
    calls: list[str] = []
    seen: list[tuple[str, str, float]] = []
    run_stages(scene, tmp_path, make_stages(calls), ["simulate"], progress=lambda *a: seen.append(a))
    last = {}
    for stage, text, fraction in seen:
        last[stage] = (text, fraction)
    assert set(last) == {"quasistatic", "simulate"}
    assert all(fraction == 1.0 and text.startswith("done in ") for text, fraction in last.values())
