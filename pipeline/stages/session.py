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
    """The scene's warnings (pipeline.scene.validity findings); raises on what would make the
    requested stages meaningless or impossible (SceneError subclasses)."""
    from ..staging.runner import closure
    from . import STAGES
    from ..scene.validity import raise_errors, run_findings, scene_findings

    notes = raise_errors(scene_findings(scene))
    stages = set(closure(STAGES, targets))
    raise_errors(run_findings(scene, stages))
    if "identify" in stages:
        notes += raise_errors(fe_findings(scene))
    return notes


# Triangles of the FE section beyond which identification takes hours and gigabytes: the default
# mesh of helicopter-b has ~7 800 (0.9 s to mesh); a uniform mesh of 1 mm has 24 000.
FE_TRIANGLES_ERROR, FE_TRIANGLES_WARNING = 2e6, 2e5
EQUILATERAL_AREA = 0.433  # sqrt(3)/4: area of an equilateral triangle of side 1


def fe_findings(scene) -> list:
    """What the FE identification would refuse (the [fe] geometry against the bearing ring)
    and the size of its mesh, for a scene whose hinge comes from the FE model."""
    from ...meshes.housing import section_rectangles

    from .identify import ring_seat
    from ..scene.validity import error, warning

    if scene.hinge.source != "fe" or scene.fe is None:
        return []
    ring = ring_seat(scene)
    try:
        scene.fe.validate(ring)
    except ValueError as exc:
        return [error("", str(exc))]
    fe = scene.fe
    area = sum((r1 - r0) * (z1 - z0) for parts in section_rectangles(fe.housing_geometry(ring)).values()
               for r0, r1, z0, z1 in parts)
    triangles = area / (EQUILATERAL_AREA * fe.mesh_size ** 2)  # uniform mesh: fewer than refined
    smallest = (area / (EQUILATERAL_AREA * FE_TRIANGLES_ERROR)) ** 0.5
    text = (f"{fe.mesh_size:.6g} m gives at least {triangles:.3g} triangles in the {area * 1e4:.3g} cm^2 "
            f"meridian section (uniform; fe.edge_refinement < 1 adds more)")
    if triangles > FE_TRIANGLES_ERROR:
        return [error("fe.mesh_size", f"{text}, more than the {FE_TRIANGLES_ERROR:.0e} identify accepts (the "
                                      f"default mesh of helicopter-b has about 7800); allowed >= {smallest:.3g} m [m]")]
    if triangles > FE_TRIANGLES_WARNING:
        return [warning("fe.mesh_size", f"{text}, over 25 times the default mesh of helicopter-b: expect a "
                                        f"long identification [m]")]
    return []


@contextlib.contextmanager
def claimed(run_dir: Path):
    """Claim `run_dir` (new, empty or bearingsim's, else OutputRefused) and hold its lock
    (RunDirectoryBusy when another process writes it)."""
    from ..staging.artefacts import claim_run_directory, run_directory_lock

    claim_run_directory(run_dir)
    with run_directory_lock(run_dir):
        yield run_dir


@contextlib.contextmanager
def run_log(run_dir: Path):
    """Log the bearingsim logger to `<run_dir>/run.log` while the block runs (OSError when the
    directory cannot take it): a caller's own error handlers inside the block log there too."""
    from ..staging.provenance import attach_run_log

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
    from ..staging.artefacts import sweep_stale_temporaries
    from ..staging.provenance import write_run_provenance
    from ..staging.runner import run_stages
    from . import STAGES

    log.info("bearingsim %s: targets %s%s", scene.name, targets, label)
    for f in notes:
        log.warning("scene: %s", f.text)
    stale = sweep_stale_temporaries(run_dir)
    if stale:
        log.info("removed temporaries of an earlier, killed run: %s", ", ".join(stale))
    write_run_provenance(run_dir, scene.raw, origin)
    return run_stages(scene, run_dir, STAGES, targets, set(force), progress=progress, store=store,
                      store_stages=store_stages)
