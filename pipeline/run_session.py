"""One run of the staged pipeline in a run directory: what the command line and the Python API
share. Both check what can be checked before solving, claim the run directory (new, empty or
bearingsim's own), hold its lock, log to `<run_dir>/run.log`, write scene.toml and
versions.json, then run the stages. How a failure reaches the user (exit codes on the console,
exceptions in Python) is the caller's business.
"""

from __future__ import annotations

import contextlib
import logging
from pathlib import Path

log = logging.getLogger("bearingsim")


def check_before_solving(scene, targets: list[str]) -> list:
    """The scene's warnings (pipeline.validity findings); raises on what would make the
    requested stages meaningless or impossible (SceneError subclasses)."""
    from .runner import closure
    from .stages import STAGES
    from .validity import raise_errors, run_findings, scene_findings

    notes = raise_errors(scene_findings(scene))
    raise_errors(run_findings(scene, set(closure(STAGES, targets))))
    return notes


@contextlib.contextmanager
def claimed(run_dir: Path):
    """Claim `run_dir` (new, empty or bearingsim's, else OutputRefused) and hold its lock
    (RunDirectoryBusy when another process writes it)."""
    from .artefacts import claim_run_directory, run_directory_lock

    claim_run_directory(run_dir)
    with run_directory_lock(run_dir):
        yield run_dir


@contextlib.contextmanager
def run_log(run_dir: Path):
    """Log the bearingsim logger to `<run_dir>/run.log` while the block runs (OSError when the
    directory cannot take it): a caller's own error handlers inside the block log there too."""
    from .provenance import attach_run_log

    handler = attach_run_log(run_dir)
    try:
        yield
    finally:
        log.removeHandler(handler)
        handler.close()


def run_stages_logged(scene, run_dir: Path, targets: list[str], force: set[str], origin: str, *,
                      notes=(), progress=None, store: Path | None = None, store_stages=None,
                      label: str = "") -> list:
    """Inside `claimed(run_dir)` and `run_log(run_dir)`: log what runs, drop a killed run's
    temporaries, write the provenance (scene.toml, versions.json), run the stages. Returns
    the StageOutcomes."""
    from .artefacts import sweep_stale_temporaries
    from .provenance import write_run_provenance
    from .runner import run_stages
    from .stages import STAGES

    log.info("bearingsim %s: targets %s%s", scene.name, targets, label)
    for f in notes:
        log.warning("scene: %s", f.text)
    stale = sweep_stale_temporaries(run_dir)
    if stale:
        log.info("removed temporaries of an earlier, killed run: %s", ", ".join(stale))
    write_run_provenance(run_dir, scene.raw, origin)
    return run_stages(scene, run_dir, STAGES, targets, set(force), progress=progress, store=store,
                      store_stages=store_stages)
