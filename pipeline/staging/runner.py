"""The staged pipeline: identify -> quasistatic -> simulate -> report.

Each stage is a function of the scene that reads and writes artefacts in the run
directory. Its cache key hashes exactly the scene inputs it depends on plus the keys of
the stages it reads from (and the code version), so an unchanged stage is skipped and a
changed input is never served from a stale cache. Stages a scene does not need are left
out entirely.

A finished stage is checked against the model's validity (pipeline.scene.validity): an error
discards the result (ValidityError), warnings are logged and stored with it. Its manifest
records a checksum of every file, so a damaged cached result is recomputed; a stage whose
inputs changed removes the results downstream of it that were computed from the old ones.
"""

from __future__ import annotations

import contextlib
import logging
import os
import shutil
import time
from contextvars import ContextVar
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

from . import result_checks
from ..scene import validity
from .artefacts import (atomic_write_json, cache_state, foreign_files, input_key, read_manifest,
                        remove_stage_dir, stage_files, staged_directory)
from .stage_store import claim_store_directory
from .provenance import code_version
from ..scene.load import Scene

log = logging.getLogger("bearingsim")


class StageNotAvailable(RuntimeError):
    """A stage that a later issue provides; raised instead of pretending to compute."""


@dataclass(frozen=True)
class Stage:
    name: str
    depends: tuple[str, ...]
    needed: Callable[[Scene], bool]
    inputs: Callable[[Scene], dict]
    compute: Callable[["StageContext"], dict]
    summary: str


@dataclass
class StageContext:
    """What a stage's compute function gets: the scene, where to write, what it reads."""

    scene: Scene
    out_dir: Path  # temporary directory, swapped in on success
    run_dir: Path
    upstream: dict[str, Path] = field(default_factory=dict)  # stage name -> finished dir
    progress: Callable[[str, float], None] = lambda text, fraction: None


@dataclass
class StageOutcome:
    name: str
    status: str  # "computed" | "cached" | "from store" | "not needed"
    key: str | None = None
    wall_time: float = 0.0
    info: dict = field(default_factory=dict)
    warnings: list[dict] = field(default_factory=list)  # validity warnings (level, key, message)


def stage_key(stage: Stage, scene: Scene, upstream_keys: dict[str, str]) -> str:
    inputs = {"scene": stage.inputs(scene), "upstream": upstream_keys}
    return input_key(stage.name, inputs, code_version())


def _warnings(manifest: dict | None) -> list[dict]:
    return [f for f in (manifest or {}).get("validity", []) if isinstance(f, dict) and f.get("level") == "warning"]


def run_stages(
    scene: Scene,
    run_dir: Path,
    stages: list[Stage],
    targets: list[str],
    force: set[str] = frozenset(),
    progress: Callable[[str, str, float], None] | None = None,
    store: Path | None = None,
    store_stages: frozenset[str] | set[str] | None = None,
) -> list[StageOutcome]:
    """Run `targets` (stage names, in order) and whatever they need, caching by input key.

    `store`: optional directory shared by many run directories (the points of a sweep).
    A stage whose key is in the store is linked from it instead of recomputed, and a
    computed stage is published to it (see `_via_store`). `store_stages`: the stages
    that go through the store (None: all of them).
    """
    by_name = {s.name: s for s in stages}
    order = _closure(by_name, targets)
    keys: dict[str, str] = {}
    not_needed: set[str] = set()
    outcomes = []
    for name in order:
        stage = by_name[name]
        if not stage.needed(scene):
            log.info("stage %s: not needed by this scene", name)
            outcomes.append(StageOutcome(name, "not needed"))
            not_needed.add(name)
            continue
        up = {d: keys[d] for d in stage.depends if d in keys}
        key = stage_key(stage, scene, up)
        keys[name] = key
        stage_dir = run_dir / name
        state, damaged = cache_state(stage_dir, key)
        if name not in force and state == "fresh":
            log.info("stage %s: up to date (key %s), skipped", name, key[:12])
            manifest = read_manifest(stage_dir)
            outcomes.append(StageOutcome(name, "cached", key, info=manifest.get("info", {}),
                                         warnings=_warnings(manifest)))
            _log_warnings(name, outcomes[-1].warnings)
            continue
        if state == "damaged":
            log.warning("stage %s: the cached result is damaged (%s changed or missing since the stage "
                        "wrote it): recomputing", name, ", ".join(damaged[:5]))
        if store is None or (store_stages is not None and name not in store_stages):
            outcomes.append(compute_stage(stage, scene, run_dir, key, up, progress))
        else:
            outcomes.append(_via_store(stage, scene, run_dir, key, up, progress, Path(store), name in force))
        if state == "damaged":
            outcomes[-1].warnings.insert(0, {"level": "warning", "key": "", "message": (
                f"the cached result was damaged ({', '.join(damaged[:5])} changed or missing since the stage "
                f"wrote it): recomputed")})
        _note_removed(outcomes[-1], drop_stale_dependents(run_dir, stages, keys, not_needed))
    if outcomes:
        _note_removed(outcomes[-1], drop_stale_dependents(run_dir, stages, keys, not_needed))
    return outcomes


def _note_removed(outcome: StageOutcome, removed: list[str]) -> None:
    """Say on the console, not only in run.log, which results a changed input removed."""
    if removed:
        outcome.warnings.append({"level": "warning", "key": "", "message": (
            f"removed {', '.join(f'{r}/' for r in removed)}: computed from the previous {outcome.name} "
            f"result, which these inputs replaced; run {removed[-1]} again to recompute it")})


def drop_stale_dependents(run_dir: Path, stages: list[Stage], keys: dict[str, str],
                          not_needed: set[str] = frozenset()) -> list[str]:
    """Remove stage folders computed from upstream results that are no longer the current
    ones (`keys`: stage -> current key): an old report/ must not stay beside new results.
    Only folders bearingsim wrote (with a manifest) are removed. Returns their names."""
    removed: list[str] = []
    for stage in stages:
        if stage.name in keys:
            continue  # computed or checked in this run: current by construction
        manifest = read_manifest(Path(run_dir) / stage.name)
        if not manifest:
            continue
        upstream = manifest.get("upstream") or {}
        stale = [d for d, k in upstream.items()
                 if (d in keys and keys[d] != k) or d in not_needed or d in removed]
        if not stale:
            continue
        if remove_stage_dir(Path(run_dir) / stage.name):
            log.info("stage %s: removed, it was computed from an older %s", stage.name, " and ".join(stale))
            removed.append(stage.name)
        else:
            log.warning("stage %s: kept although computed from an older %s: it holds files bearingsim "
                        "did not write (%s); move them out and run the stage again", stage.name,
                        " and ".join(stale), ", ".join(foreign_files(Path(run_dir) / stage.name)[:3]))
    return removed


def _log_warnings(name: str, warnings: list[dict]) -> None:
    for w in warnings:
        log.warning("stage %s: %s%s", name, f"{w.get('key')}: " if w.get("key") else "", w.get("message"))


def closure(stages: list[Stage], targets: list[str]) -> list[str]:
    """Names of the stages that running `targets` involves (needed or not), in order."""
    return _closure({s.name: s for s in stages}, targets)


def _closure(by_name: dict[str, Stage], targets: list[str]) -> list[str]:
    """Targets plus their dependencies, in pipeline order."""
    wanted: set[str] = set()

    def visit(n: str) -> None:
        if n not in wanted:
            wanted.add(n)
            for d in by_name[n].depends:
                visit(d)

    for t in targets:
        visit(t)
    return [n for n in by_name if n in wanted]


def compute_stage(stage, scene, run_dir, key, up, progress) -> StageOutcome:
    """Compute one stage into `run_dir/<stage>` (atomic swap) whatever its cache says;
    `up` maps upstream stage names to their keys. Also used by `render` to redo `report`."""
    log.info("stage %s: computing (key %s)", stage.name, key[:12])
    t0 = time.perf_counter()
    report = (lambda text, f: progress(stage.name, text, f)) if progress else (lambda text, f: None)
    with staged_directory(run_dir / stage.name) as tmp:
        ctx = StageContext(scene, tmp, run_dir, {d: run_dir / d for d in up}, report)
        try:
            info = stage.compute(ctx) or {}
        except Exception as exc:
            finding = result_checks.failure_finding(stage.name, scene, exc)
            if finding is None:
                raise
            log.error("stage %s: result outside the model's validity: %s", stage.name, finding.text)
            raise validity.ValidityError([finding]) from exc
        wall = time.perf_counter() - t0
        findings = result_checks.stage_findings(stage.name, scene, tmp)
        for f in findings:
            if f.level == "error":
                log.error("stage %s: result outside the model's validity: %s", stage.name, f.text)
        validity.raise_errors(findings)  # a meaningless result is discarded with the temporary
        result_checks.annotate(stage.name, tmp, findings)
        warnings = [f.to_json() for f in findings]
        atomic_write_json(tmp / "stage.json", {
            "stage": stage.name, "status": "done", "key": key, "upstream": up,
            "inputs": stage.inputs(scene), "wall_time_s": wall,
            "finished": time.strftime("%Y-%m-%dT%H:%M:%S%z"), "info": info,
            "validity": warnings, "files": stage_files(tmp),
        })
    log.info("stage %s: done in %.2f s", stage.name, wall)
    report(f"done in {wall:.1f} s", 1.0)  # a progress display ends the stage's bar here
    _log_warnings(stage.name, warnings)
    return StageOutcome(stage.name, "computed", key, wall, info, warnings)


def _via_store(stage, scene, run_dir, key, up, progress, store: Path, force: bool) -> StageOutcome:
    """Link a finished stage from the content-addressed store `store/<stage>/<key>/`, or
    compute it and publish it there. One lock per key: runs on several workers that need
    the same stage (e.g. one FE identification for a whole sweep) compute it once; the
    others wait for the lock and then link the published result. A store that is not
    bearingsim's (`claim_store_directory`) is not used."""
    entry = store / stage.name / key
    try:
        claim_store_directory(store)
        entry.parent.mkdir(parents=True, exist_ok=True)
        if not os.access(entry.parent, os.W_OK | os.X_OK):
            raise PermissionError(13, "not writable by this user")
    except OSError as exc:
        return _without_store(compute_stage(stage, scene, run_dir, key, up, progress), store, exc)
    with contextlib.ExitStack() as held:
        try:
            held.enter_context(_store_lock(entry.with_name(f".{key}.lock")))
        except OSError as exc:  # a link or a special file planted in the store, or no locking there
            return _without_store(compute_stage(stage, scene, run_dir, key, up, progress), store, exc)
        if not force and cache_state(entry, key)[0] == "fresh":
            with staged_directory(run_dir / stage.name) as tmp:
                shutil.copytree(entry, tmp, dirs_exist_ok=True, copy_function=_link_or_copy)
            log.info("stage %s: linked from store %s (key %s)", stage.name, store, key[:12])
            manifest = read_manifest(entry)
            _log_warnings(stage.name, _warnings(manifest))
            return StageOutcome(stage.name, "from store", key, info=manifest.get("info", {}),
                                warnings=_warnings(manifest))
        outcome = compute_stage(stage, scene, run_dir, key, up, progress)
        try:
            with staged_directory(entry) as tmp:  # atomic: readers never see a partial entry
                shutil.copytree(run_dir / stage.name, tmp, dirs_exist_ok=True, copy_function=_link_or_copy)
        except OSError as exc:  # the run's own result is complete: only the sharing failed
            return _without_store(outcome, store, exc)
        return outcome


def _without_store(outcome: StageOutcome, store: Path, exc: OSError) -> StageOutcome:
    """`outcome` of a stage computed in the run directory only, with a warning that names the
    unusable store and what to do."""
    reason = (f"{exc.filename} {exc.strerror}" if exc.filename and exc.strerror else exc.strerror or str(exc))
    message = (f"the stage store {store} cannot be used ({reason}): {outcome.name} was computed in this "
               f"run directory only; {STORE_ADVICE.get()}")
    log.warning("stage %s: %s", outcome.name, message)
    outcome.warnings.insert(0, {"level": "warning", "key": "", "message": message})
    return outcome


# what to do about an unusable store, in the words of whoever chose it (the sweep: --store)
STORE_ADVICE: ContextVar[str] = ContextVar(
    "store_advice", default="set BEARINGSIM_STAGE_STORE to a writable directory, or pass --no-store")


def _link_or_copy(src, dst) -> None:
    """Hard link (stage files are written once and replaced whole, never edited in place);
    copy where links are impossible (another file system, Windows shares)."""
    try:
        Path(dst).hardlink_to(src)
    except OSError:
        shutil.copy2(src, dst)


@contextlib.contextmanager
def _store_lock(path: Path):
    """Exclusive lock on `path` (pipeline.machine.file_lock: never through a link), released on
    exit or when the process dies."""
    from ..machine.file_lock import exclusive_lock

    with exclusive_lock(path):
        yield
