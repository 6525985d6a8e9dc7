"""Whether a run directory's scene.toml describes its results, and which of their files changed.

Each finished stage's manifest records the inputs it was computed from and the keys of the
upstream results it read. A stage whose recorded inputs are not the ones the directory's
scene.toml gives, or which read another upstream result than the directory holds, was computed
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
    key: str  # recorded in its manifest ("" when the manifest cannot be read)
    differences: list[str] = field(default_factory=list)  # "load.moment: 430 computed, 100 in scene.toml"
    damaged_data: list[str] = field(default_factory=list)
    damaged_figures: list[str] = field(default_factory=list)

    @property
    def of_the_scene(self) -> bool:
        return not self.differences


def check_run_directory(run_dir: Path, scene, stages) -> list[StageCheck]:
    """Every finished stage of `run_dir` among `stages` (the pipeline's, in order), checked
    against `scene` (the directory's scene.toml) and against its manifest's checksums.

    A stage is of the scene when the inputs its manifest records are the scene's (whatever
    version of bearingsim computed it: the key also hashes the code version), and when it was
    computed from the upstream results the directory holds (the upstream keys it records). A
    manifest of an older version without recorded inputs is held to the key alone."""
    from ..staging.artefacts import canonical, damaged_files, read_manifest
    from ..staging.runner import stage_key

    manifests: dict[str, dict] = {}
    out = []
    for stage in stages:
        stage_dir = Path(run_dir) / stage.name
        manifest = read_manifest(stage_dir)
        if manifest is None and stage_dir.is_dir():  # a stage folder always holds its manifest
            out.append(StageCheck(stage.name, "", damaged_data=["stage.json (unreadable or missing)"]))
            continue
        if not manifest or manifest.get("status") != "done" or not manifest.get("key"):
            continue
        check = StageCheck(stage.name, manifest["key"])
        recorded = manifest.get("inputs")
        if not stage.needed(scene):
            check.differences = ["the scene does not need this stage (hinge.source or the [cage] differ)"]
        elif recorded is not None:
            if canonical(recorded) != canonical(stage.inputs(scene)):
                check.differences = input_differences(recorded, stage.inputs(scene)) or ["its recorded inputs differ"]
        else:
            upstream = {d: manifests[d]["key"] for d in stage.depends if d in manifests}
            if stage_key(stage, scene, upstream) != manifest["key"]:
                check.differences = ["its recorded key differs (a manifest of an older version, without inputs)"]
        for d, k in (manifest.get("upstream") or {}).items():
            if d in manifests and manifests[d]["key"] != k:
                check.differences.append(f"computed from another {d} result than the one in {d}/")
        for name in damaged_files(stage_dir, manifest):
            (check.damaged_figures if name.endswith(FIGURE_SUFFIX) else check.damaged_data).append(name)
        manifests[stage.name] = manifest
        out.append(check)
    return out


def input_differences(recorded, current, limit: int = 5) -> list[str]:
    """The dotted inputs that differ between a manifest's `inputs` and the scene's, as
    "key: <recorded> computed, <current> in scene.toml" (at most `limit`)."""
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
