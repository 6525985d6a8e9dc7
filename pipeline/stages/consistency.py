"""Whether a run directory's scene.toml describes its results, and which of their files changed.

Each finished stage's manifest records the key of the inputs it was computed from. The scene in
scene.toml gives, stage by stage, the keys a run of it would compute (as the runner chains them,
each stage's key holding its upstream stages'); a stage whose recorded key differs was computed
from other inputs: scene.toml was edited by hand, or written by a later command with other
`--set` values that did not recompute that stage (`stiffness`, an interrupted `simulate`).
`render` refuses such a directory and `open_run` flags it (docs/reliability.md).

A stage's figures (its PNGs) are drawings of its data: one deleted or changed is drawn again by
`render` (pipeline.render.stage_figures); any other file changed or missing is damaged data.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path

FIGURE_SUFFIX = ".png"


@dataclass
class StageCheck:
    """One finished stage of a run directory against the directory's scene."""

    name: str
    key: str  # recorded in its manifest
    expected: str | None  # what the scene gives (None: the scene does not need the stage)
    differences: list[str] = field(default_factory=list)  # "load.moment: 430 computed, 100 in scene.toml"
    damaged_data: list[str] = field(default_factory=list)
    damaged_figures: list[str] = field(default_factory=list)

    @property
    def of_the_scene(self) -> bool:
        return self.expected == self.key


def check_run_directory(run_dir: Path, scene, stages) -> list[StageCheck]:
    """Every finished stage of `run_dir` among `stages` (the pipeline's, in order), checked
    against `scene` (the directory's scene.toml) and against its manifest's checksums."""
    from ..staging.artefacts import damaged_files, read_manifest
    from ..staging.runner import stage_key

    keys: dict[str, str] = {}
    out = []
    for stage in stages:
        expected = None
        if stage.needed(scene):
            expected = stage_key(stage, scene, {d: keys[d] for d in stage.depends if d in keys})
            keys[stage.name] = expected
        stage_dir = Path(run_dir) / stage.name
        manifest = read_manifest(stage_dir)
        if manifest is None and stage_dir.is_dir():  # a stage folder always holds its manifest
            out.append(StageCheck(stage.name, "", expected, damaged_data=["stage.json (unreadable or missing)"]))
            continue
        if not manifest or manifest.get("status") != "done" or not manifest.get("key"):
            continue
        check = StageCheck(stage.name, manifest["key"], expected)
        if not check.of_the_scene:
            check.differences = input_differences(manifest.get("inputs"), stage.inputs(scene) if expected else None)
        for name in damaged_files(Path(run_dir) / stage.name, manifest):
            (check.damaged_figures if name.endswith(FIGURE_SUFFIX) else check.damaged_data).append(name)
        out.append(check)
    return out


def input_differences(recorded, current, limit: int = 5) -> list[str]:
    """The dotted inputs that differ between a manifest's `inputs` and the scene's, as
    "key: <recorded> computed, <current> in scene.toml" (at most `limit`)."""
    if current is None:
        return ["the scene does not need this stage (hinge.source or the [cage] differ)"]
    if recorded is None:
        return []  # a manifest of an older version: the key alone says they differ
    from ..staging.artefacts import canonical

    a, b = _flat(canonical(recorded)), _flat(canonical(current))
    out = []
    for key in sorted(set(a) | set(b)):
        if a.get(key, "absent") != b.get(key, "absent"):
            shown = key.removeprefix("scene.")
            out.append(f"{shown}: {_shown(a.get(key))} computed, {_shown(b.get(key))} in scene.toml")
    return out[:limit] + ([f"and {len(out) - limit} more"] if len(out) > limit else [])


def _flat(obj, prefix: str = "") -> dict:
    if isinstance(obj, dict):
        out = {}
        for k, v in obj.items():
            out.update(_flat(v, f"{prefix}{k}."))
        return out
    return {prefix.rstrip("."): json.dumps(obj, sort_keys=True)}


def _shown(value) -> str:
    """A flattened value as the scene file writes it (430, not 430.0)."""
    if value is None:
        return "absent"
    number = json.loads(value)
    if isinstance(number, float):
        return f"{number:.10g}"
    return value


def mismatch_message(run_dir: Path, checks: list[StageCheck]) -> str | None:
    """The refusal for a scene.toml that does not describe the stages (None when it does)."""
    wrong = [c for c in checks if not c.of_the_scene and c.key and c.name != "report"]
    if not wrong:
        return None
    first = wrong[0]
    what = "; ".join(first.differences) or "its recorded key differs"
    return (f"{Path(run_dir) / 'scene.toml'} does not describe the results in {run_dir}: the {first.name} stage was "
            f"computed from other inputs ({what}); scene.toml was edited, or written by a later command with other "
            f"inputs that did not recompute {', '.join(c.name for c in wrong)}. render draws only results with "
            f"the scene they were computed from: recompute them from scene.toml with `bearingsim run "
            f"{Path(run_dir) / 'scene.toml'} --out {run_dir}`, or run the scene they came from into it again")
