"""One sweep point = one normal pipeline run in its own run directory.

Runs on a Dask worker. Whatever happens inside the point (bad physics, solver giving up,
a bug) is caught and written to the point's record `point.json` with the message; only
the death of the worker process itself escapes, and then nothing is written, so a rerun
simply runs the point again. The record is written atomically after the stage results
it points to, so a record on disk always means a finished point.
"""

from __future__ import annotations

import json
import logging
import os
import socket
import threading
import time
import traceback
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..staging.artefacts import SWEEP_POINT_RECORD, atomic_write_json

RECORD_FILE = SWEEP_POINT_RECORD  # the staging layer refuses such a folder to runs of their own
NO_FIGURES = "output.figures=false"  # scene override of a point whose sweep skips figures
log = logging.getLogger("bearingsim")


@dataclass(frozen=True)
class PointRequest:
    """Everything a worker needs; plain data, so it pickles to any worker."""

    point_id: str
    label: str
    overrides: tuple[tuple[str, Any], ...]
    table: dict  # the point's validated scene table
    scene_hash: str
    run_dir: str  # must be reachable from the worker (shared file system for remote ones)
    store: str | None  # shared stage store (see pipeline.staging.runner.run_stages)
    target: str = "simulate"
    figures: bool = True  # False: the point runs with output.figures = false (no PNGs)


def read_record(run_dir: Path) -> dict | None:
    try:
        return json.loads((Path(run_dir) / RECORD_FILE).read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None


def finished_record(run_dir: Path, scene_hash: str, target: str = "simulate") -> dict | None:
    """The point's record if it finished (done or failed) for exactly this scene; a done
    record also needs its summary on disk."""
    record = read_record(run_dir)
    if not record or record.get("scene_hash") != scene_hash:
        return None
    if record.get("status") == "done" and not (Path(run_dir) / target / "summary.json").is_file():
        return None
    return record if record.get("status") in ("done", "failed") else None


def prepare_worker() -> str:
    """Point numba at this machine's per-user kernel cache (pipeline.machine.numba_cache) before any
    kernel loads; returns it. A worker started by an outside `dask worker` has not been
    through the command line, which does this for local clusters; the compile lock of
    pipeline.machine.kernel_cache then makes the workers of one machine compile once."""
    from ..machine.numba_cache import configure_numba_cache

    configure_numba_cache()
    return os.environ["NUMBA_CACHE_DIR"]


def run_point(request: PointRequest, stages=None) -> dict:
    """Run the point's pipeline to `request.target`; return (and save) its record.
    `stages` replaces the pipeline's stages (tests)."""
    prepare_worker()
    run_dir = Path(request.run_dir)
    done = finished_record(run_dir, request.scene_hash, request.target)
    if done is not None and done["status"] == "done":  # a rescheduled task that had finished
        return done
    remove_stale_temporaries(run_dir)
    t0, cpu0 = time.perf_counter(), time.process_time()
    record: dict[str, Any] = {
        "point_id": request.point_id, "label": request.label,
        "overrides": dict(request.overrides), "scene_hash": request.scene_hash,
        "worker": f"{socket.gethostname()}:{os.getpid()}",
    }
    handler = _attach_point_log(run_dir)
    try:
        record.update(_run_pipeline(request, run_dir, stages), status="done", error=None)
    except Exception as exc:  # noqa: BLE001 - any failure of one point is data, not fatal
        log.error("sweep point %s failed:\n%s", request.label, traceback.format_exc())
        record.update(status="failed", error=f"{type(exc).__name__}: {exc}", summary=None)
    finally:
        log.removeHandler(handler)
        handler.close()
    # CPU time of the worker process (its threads run other points only with threads > 1)
    record.update(wall_time_s=time.perf_counter() - t0, cpu_time_s=time.process_time() - cpu0,
                  finished=time.strftime("%Y-%m-%dT%H:%M:%S%z"))
    atomic_write_json(run_dir / RECORD_FILE, record)
    return record


def _run_pipeline(request: PointRequest, run_dir: Path, stages) -> dict:
    from ..staging.provenance import write_run_provenance
    from ..staging.runner import run_stages
    from ..scene.load import resolve

    if stages is None:
        from ..stages import STAGES as stages
    scene = resolve(point_run_table(request), origin=f"sweep point {request.label}")
    write_run_provenance(run_dir, scene.raw, f"sweep point {request.label}")
    from ..staging.runner import STORE_ADVICE

    store = Path(request.store) if request.store else None
    advice = STORE_ADVICE.set("give the sweep a writable stage store with --store (store= in Python)")
    try:
        outcomes = run_stages(scene, run_dir, stages, [request.target], store=store)
    finally:
        STORE_ADVICE.reset(advice)
    summary = json.loads((run_dir / request.target / "summary.json").read_text(encoding="utf-8"))
    # the stages' validity warnings (quasistatic.json, summary.json), for the results table
    validity = [f"{o.name}: {w['key']}: {w['message']}" if w.get("key") else f"{o.name}: {w['message']}"
                for o in outcomes for w in o.warnings]
    return {"summary": summary, "stages": {o.name: o.status for o in outcomes}, "validity": validity}


def point_run_table(request: PointRequest) -> dict:
    """The scene table the point runs: its own, plus `output.figures = false` when the sweep
    skips figures. Not part of the point's scene hash: figures are output, so switching them
    does not rerun finished points (the stage keys, which hash the scene, do change)."""
    if request.figures:
        return request.table
    from ..scene.load import apply_overrides

    return apply_overrides(request.table, [NO_FIGURES])


def remove_stale_temporaries(run_dir: Path) -> None:
    """Half-written stage directories (`.<stage>.*.tmp`) left by a worker killed while it ran
    this point: a point runs on one worker at a time, so no live run owns them (also called
    once a local cluster stopped by an interruption has closed)."""
    import shutil

    for tmp in Path(run_dir).glob(".*.tmp"):
        if tmp.is_dir():
            shutil.rmtree(tmp, ignore_errors=True)


def _attach_point_log(run_dir: Path) -> logging.Handler:
    """`<run dir>/run.log` of this point only: threads of one worker run other points."""
    from ..staging.provenance import attach_run_log

    handler = attach_run_log(run_dir)
    thread = threading.get_ident()
    handler.addFilter(lambda record: record.thread == thread)
    return handler
