"""Plan a sweep, run its points on a Dask cluster, gather the table and the map.

Layout of a sweep directory (`runs/<sweep name>/` by default)::

    sweep.json          the plan: scene, axes, points (id, label, overrides)
    points/<id>/        each point's own run directory (scene.toml, stages, point.json)
    store/              stages shared between points, by key (pipeline.staging.runner)
    results.csv         one row per point (pipeline.sweep.table); results.parquet with pyarrow
    stability_map.png   class map with metal-contact contours (pipeline.sweep.stability_map)

Resuming: a point whose `point.json` is finished for the same scene hash is not run again
(failed points only with `retry_failed`); points lost with a dead worker have no record
and run again. The table is always rebuilt from the records on disk.
"""

from __future__ import annotations

import dataclasses
import json
import time
import uuid
import warnings
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable

from ..staging.artefacts import OutputRefused, atomic_write_json, mark_directory, refused_unless_usable
from ..staging.no_follow import out_name
from ..scene.load import NAME_MAX, apply_overrides, check_name, read_scene_table, resolve
from ..scene.schema import SceneError
from . import quiet_interrupt
from .point_runner import PointRequest, finished_record, run_point
from .points import SweepPoint, expand, point_table, scene_hash
from ..scene.sweep_section import MAX_POINTS, SweepSection, build_sweep_section, check_size, with_command_line
from .table import result_row, short_run_warning, write_table

PLAN_FILE, MAP_FILE = "sweep.json", "stability_map.png"
SWEEP_MARKER = ".bearingsim-sweep"
PLAN_PROGRESS_POINTS = 1000  # points between two progress lines of the planning (about 5 s)


@dataclass(frozen=True)
class SweepPlan:
    name: str
    origin: str
    sweep_dir: Path
    section: SweepSection
    points: tuple[SweepPoint, ...]
    requests: tuple[PointRequest, ...]

    @property
    def varied(self) -> list[str]:
        return list(dict.fromkeys(k for p in self.points for k, _ in p.overrides))


@dataclass(frozen=True)
class SweepStatus:
    """What the progress display shows; `eta_s` is None until a point has finished."""

    total: int
    done: int  # finished successfully, including `resumed`
    failed: int
    running: int
    resumed: int  # finished in an earlier run, skipped
    elapsed_s: float
    eta_s: float | None
    last: str = ""  # label and outcome of the latest finished point
    lost_workers: int = 0  # workers that left the cluster during the sweep
    retried: int = 0  # points that were running on a lost worker and were started again
    running_on: dict = dataclasses.field(default_factory=dict)  # worker address -> points it runs now


def plan_sweep(scene, sets: list[str] | None = None, vary: list[str] | None = None, *,
               mode: str | None = None, name: str | None = None, out: Path | None = None,
               store: Path | None = None, max_points: int = MAX_POINTS,
               figures: bool | None = None, progress: Callable[[str], None] | None = None) -> SweepPlan:
    """Validate the scene (a path, a built-in name or a Scene of the Python API), the sweep
    definition and every point; nothing is computed. A sweep of more than `max_points`
    points is refused before its points are built. `figures` (`--figures/--no-figures`)
    overrides the scene's `[sweep] figures`. `progress(text)` hears how the validation of a
    large sweep's points goes (a few milliseconds a point)."""
    from ..scene.load import Scene

    if isinstance(scene, Scene):
        table, origin = dict(scene.raw), getattr(scene, "_origin", "a Scene object of the Python API")
    else:
        table, origin = read_scene_table(scene)
    table = apply_overrides(table, list(sets or []))
    section = with_command_line(build_sweep_section(table.get("sweep", {})), list(vary or []), mode, name,
                                figures)
    check_size(section, max_points)
    base = {k: v for k, v in table.items() if k != "sweep"}
    resolve(base, origin)
    sweep_name = section.name or f"{base['name']}-sweep"
    check_name("sweep.name", sweep_name, max_length=NAME_MAX + len("-sweep"))
    sweep_dir = Path(out if out is not None else Path("runs") / sweep_name).resolve()
    store = Path(store).resolve() if store is not None else sweep_dir / "store"
    points = tuple(expand(section))
    requests = []
    for n, p in enumerate(points):
        if progress and len(points) >= PLAN_PROGRESS_POINTS and n % PLAN_PROGRESS_POINTS == 0:
            progress(f"validating the scene of every point: {n} of {len(points)}")
        t = point_table(base, p)
        requests.append(PointRequest(p.id, p.label, p.overrides, t, scene_hash(t, section.target),
                                     str(sweep_dir / "points" / p.id), str(store), section.target,
                                     section.figures))
    return SweepPlan(sweep_name, origin, sweep_dir, section, points, tuple(requests))


def unfinished(plan: SweepPlan, retry_failed: bool = False) -> tuple[dict[str, dict], list[PointRequest]]:
    """(records of finished points by id, requests still to run)."""
    records, todo = {}, []
    for req in plan.requests:
        rec = finished_record(Path(req.run_dir), req.scene_hash, req.target)
        if rec is not None and (rec["status"] == "done" or not retry_failed):
            records[req.point_id] = rec
        else:
            todo.append(req)
    return records, todo


def run_sweep(plan: SweepPlan, client, *, progress: Callable[[SweepStatus], None] | None = None,
              retry_failed: bool = False, poll_s: float = 0.5,
              point_function: Callable[[PointRequest], dict] = run_point) -> list[dict | None]:
    """Run the plan's unfinished points on `client` (a distributed.Client); return one record
    per point, in plan order. Per-point failures are records, never exceptions. `client` is
    not used (may be None) when every point has finished before. OutputRefused when the sweep
    directory is not bearingsim's (`claim_sweep_directory`)."""
    claim_sweep_directory(plan.sweep_dir)
    _write_plan(plan)
    records, todo = unfinished(plan, retry_failed)
    resumed = sum(1 for r in records.values() if r["status"] == "done")
    token = uuid.uuid4().hex[:8]  # fresh task keys: a reused client must not serve old results
    futures = {client.submit(point_function, req, key=task_key(req, token), pure=False): req for req in todo}
    t0, last, last_table = time.perf_counter(), "", time.perf_counter()
    finished_now = 0
    workers = WorkerWatch(client)
    try:
        while True:
            for fut in [f for f in futures if f.done()]:
                req = futures.pop(fut)
                records[req.point_id] = _outcome(fut, req)
                finished_now += 1
                last = f"{req.label}: {records[req.point_id]['status']}"
            workers.poll({f.key for f in futures})
            if progress is not None:
                status = _status(plan, records, futures, client, resumed, finished_now, t0, last)
                progress(dataclasses.replace(status, lost_workers=workers.lost, retried=workers.retried,
                                             running_on=workers.busy))
            if not futures:
                break
            if time.perf_counter() - last_table > 15.0:  # partial table for long sweeps
                write_table(table_rows(plan, records), plan.sweep_dir)
                last_table = time.perf_counter()
            time.sleep(poll_s)
    finally:
        for fut in futures:
            fut.cancel()
    return [records.get(req.point_id) for req in plan.requests]


def task_key(req: PointRequest, token: str) -> str:
    """The Dask task key of a point: its values first, so the dashboard and the scheduler's
    logs say which point a task is (`bearingsim-point-load.moment=300_speed.inner_rpm=2000-
    <point id>-<token>`)."""
    values = "_".join(f"{k}={v}" for k, v in (part.split("=", 1) for part in req.label.split(", ")))
    values = "".join(c if c.isalnum() or c in "._=+" else "~" for c in values)[:120]
    return f"bearingsim-point-{values}-{req.point_id}-{token}"


class WorkerWatch:
    """Workers that leave the cluster and the points they were running (which Dask starts
    again elsewhere): what the progress line reports as lost workers and retried points."""

    def __init__(self, client):
        self.client, self.lost, self.retried = client, 0, 0
        self.busy: dict[str, int] = {}  # worker -> our points it runs now
        self._workers: set[str] | None = None
        self._running: dict[str, set] = {}

    def poll(self, keys: set) -> None:
        try:
            workers = set(self.client.scheduler_info()["workers"])
            running = {w: {k for k in tasks if k in keys} for w, tasks in self.client.processing().items()}
        except Exception:  # noqa: BLE001 - progress must never break a sweep
            return
        if self._workers is not None:
            gone = self._workers - workers
            self.lost += len(gone)
            self.retried += sum(len(self._running.get(w, set()) & keys) for w in gone)
        self._workers, self._running = workers, running
        self.busy = {w: len(k) for w, k in running.items() if k}


def _outcome(fut, req: PointRequest) -> dict:
    """The record a point returned, or (not saved: the point reruns next time) why its
    task ended without one — a worker that died with it, or a cancelled task."""
    if fut.status == "finished":
        return fut.result()
    exc = fut.exception() if fut.status == "error" else None
    message = f"{type(exc).__name__}: {exc}" if exc is not None else f"task {fut.status}"
    return {"point_id": req.point_id, "label": req.label, "status": "failed", "summary": None,
            "error": f"not finished, reruns next time: {message}", "scene_hash": req.scene_hash,
            "lost": True}


def _status(plan, records, futures, client, resumed, finished_now, t0, last) -> SweepStatus:
    done = sum(1 for r in records.values() if r and r.get("status") == "done")
    failed = sum(1 for r in records.values() if r and r.get("status") != "done")
    running = _running(client, {f.key for f in futures})
    elapsed = time.perf_counter() - t0
    remaining = len(plan.requests) - len(records)
    eta = elapsed / finished_now * remaining if finished_now else None
    return SweepStatus(len(plan.requests), done, failed, running, resumed, elapsed, eta, last)


def _running(client, keys: set) -> int:
    """Tasks of ours being run: a worker may hold more than it has threads (queued)."""
    try:
        processing, threads = client.processing(), client.nthreads()
    except Exception:  # noqa: BLE001 - progress must never break a sweep
        return 0
    return sum(min(threads.get(w, 1), sum(1 for k in tasks if k in keys)) for w, tasks in processing.items())


def run_in_process(plan: SweepPlan, *, progress: Callable[[SweepStatus], None] | None = None,
                   retry_failed: bool = False,
                   point_function: Callable[[PointRequest], dict] = run_point) -> list[dict | None]:
    """`run_sweep` without Dask: the unfinished points one after the other in this process
    (a notebook's or a test's small sweep; the same records, table, resuming and refusal of a
    folder that is not bearingsim's)."""
    claim_sweep_directory(plan.sweep_dir)
    _write_plan(plan)
    records, todo = unfinished(plan, retry_failed)
    resumed = sum(1 for r in records.values() if r["status"] == "done")
    t0, last = time.perf_counter(), ""
    for n, req in enumerate(todo):
        if progress is not None:
            progress(_status(plan, records, {}, None, resumed, n, t0, last))
        records[req.point_id] = point_function(req)
        last = f"{req.label}: {records[req.point_id]['status']}"
    if progress is not None:
        progress(_status(plan, records, {}, None, resumed, len(todo), t0, last))
    return [records.get(req.point_id) for req in plan.requests]


def table_rows(plan: SweepPlan, records: dict) -> list[dict]:
    """The table's rows; a varied key that a point leaves out (list mode) has the value of the
    point's scene."""
    limits = plan.section.thresholds
    varied = plan.varied
    return [result_row(p, records.get(p.id), Path(req.run_dir), limits,
                       {**{k: _table_value(req.table, k) for k in varied}, **dict(p.overrides)})
            for p, req in zip(plan.points, plan.requests)]


def _table_value(table: dict, key: str) -> Any:
    """The value of dotted `key` in a scene table (None where the table leaves it to its default)."""
    value: Any = table
    for part in key.split("."):
        if not isinstance(value, dict) or part not in value:
            return None
        value = value[part]
    return value


def gather(plan: SweepPlan, records: list[dict | None], warn: bool = True,
           stacklevel: int = 2) -> dict[str, Path]:
    """Write the results table and the stability map; returns {"table": ..., "map": ...}.
    When points ran too short to settle, the map's title says so and (with `warn`) a Python
    warning is issued, `stacklevel` as `warnings.warn` takes it (from gather's caller)."""
    from .stability_map import plot_stability_map

    rows = table_rows(plan, {req.point_id: rec for req, rec in zip(plan.requests, records)})
    paths = write_table(rows, plan.sweep_dir)
    s = plan.section
    short = short_run_warning(rows)
    title = f"{plan.name}: cage motion\n(contours: metal-contact fraction)"
    if short:
        # two short lines: the map of a small sweep is narrower than one long line
        title += "\nRUN TOO SHORT TO SETTLE:\nclasses show a start-up transient, not a regime"
        if warn:
            warnings.warn(f"sweep {plan.name}: {short}", stacklevel=stacklevel + 1)
    out = plot_stability_map(rows, plan.varied, plan.sweep_dir / MAP_FILE, map_x=s.map_x, map_y=s.map_y,
                             title=title)
    return {"table": paths[0], **({"parquet": paths[1]} if len(paths) > 1 else {}), "map": out}


def is_own_sweep_dir(sweep_dir: Path) -> bool:
    """A directory bearingsim made a sweep directory: its marker, or (sweeps of older
    versions) a sweep.json holding a plan."""
    if (sweep_dir / SWEEP_MARKER).is_file():
        return True
    try:
        plan = json.loads((sweep_dir / PLAN_FILE).read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return False
    return isinstance(plan, dict) and {"name", "scene", "axes", "points"} <= set(plan)


def claim_sweep_directory(sweep_dir: Path) -> None:
    """Make sure `sweep_dir` may be written (new, empty or a sweep bearingsim wrote) and mark
    it; anything else raises OutputRefused before a file is written: the table, the plan and
    the map would replace a user's files of the same names."""
    sweep_dir = Path(sweep_dir)
    with refused_unless_usable(sweep_dir):
        if sweep_dir.exists() and not sweep_dir.is_dir():
            raise OutputRefused(f"{out_name(sweep_dir)}: exists and is not a directory; give a new or empty "
                                f"directory, e.g. {out_name(sweep_dir.with_name(sweep_dir.name + '-sweep'))}")
        if sweep_dir.is_dir() and not is_own_sweep_dir(sweep_dir) and any(sweep_dir.iterdir()):
            raise OutputRefused(
                f"{out_name(sweep_dir)}: the directory holds files that are not a bearingsim sweep (no "
                f"{SWEEP_MARKER} marker); bearingsim never writes into a folder of yours, so that none of "
                f"your files ({PLAN_FILE}, results.csv, {MAP_FILE}) is replaced. Give a new or empty "
                f"directory, e.g. {out_name(sweep_dir / 'sweep')}")
        mark_directory(sweep_dir, SWEEP_MARKER, "bearingsim sweep directory: its plan, table, map and points "
                                                "are replaced by bearingsim")


@contextmanager
def sweep_directory_lock(plan: SweepPlan):
    """Claim the sweep's folder and its stage store (OutputRefused when either is not
    bearingsim's) and hold the sweep folder's lock while the block runs: two sweeps writing one
    folder would write their tables over each other (RunDirectoryBusy for the second)."""
    from ..machine.file_lock import LockBusy, NotALockFile, exclusive_lock
    from ..staging.artefacts import RunDirectoryBusy
    from ..staging.stage_store import claim_store_directory
    from ..staging.no_follow import refused_special_file

    claim_sweep_directory(plan.sweep_dir)
    if plan.requests and plan.requests[0].store:
        with refused_unless_usable(Path(plan.requests[0].store)):
            claim_store_directory(Path(plan.requests[0].store))
    try:
        with exclusive_lock(plan.sweep_dir / ".lock", wait=False):
            yield
    except LockBusy:
        raise RunDirectoryBusy(f"another bearingsim sweep is writing {plan.sweep_dir}/; wait for it to finish, "
                               f"or give this sweep its own directory with {out_name()}") from None
    except NotALockFile as exc:
        raise refused_special_file(exc.path, exc.what) from None


def replaced_sweep(plan: SweepPlan) -> str | None:
    """What running `plan` replaces: the table and map of another plan in the same sweep
    directory (its point folders stay, and rerunning its command restores them); None when the
    directory holds no plan or the same points."""
    try:
        earlier = json.loads((plan.sweep_dir / PLAN_FILE).read_text(encoding="utf-8"))
        ids = {p["id"] for p in earlier.get("points", [])}
    except (OSError, ValueError, TypeError, KeyError):
        return None
    if not ids or ids == {p.id for p in plan.points}:
        return None
    return (f"{plan.sweep_dir}/ holds another sweep ({len(ids)} points); this one replaces its results table "
            f"and map (its point folders stay in points/, and running its command again restores them). "
            f"Give this sweep its own folder with {out_name()}, or another name, to keep both")


def _write_plan(plan: SweepPlan) -> None:
    s = plan.section
    atomic_write_json(plan.sweep_dir / PLAN_FILE, {
        "name": plan.name, "scene": plan.origin, "mode": s.mode, "target": s.target, "figures": s.figures,
        "axes": {a.key: list(a.values) for a in s.vary},
        "thresholds": dataclasses.asdict(s.thresholds),
        "points": [{"id": p.id, "label": p.label, "overrides": dict(p.overrides), "run_dir": r.run_dir}
                   for p, r in zip(plan.points, plan.requests)],
    })


def check_scheduler_address(address: str) -> None:
    """SceneError (key `--scheduler`) unless `address` reads as a Dask scheduler address,
    `[tcp|tls|ws|wss|ucx]://host:port` or `host:port`: checked before any point is planned,
    instead of a ValueError from inside the client."""
    try:
        from distributed.comm import get_address_host_port
    except ImportError:
        return  # dask_client says how to install the extra
    try:
        host, port = get_address_host_port(address)
    except (ValueError, TypeError) as exc:
        reason = str(exc)
    else:
        if host and 0 < port < 65536:
            return
        reason = f"port {port} is not 1 to 65535" if host else "no host"
    raise SceneError("--scheduler", f"{address!r} is not a Dask scheduler address ({reason}); give the address "
                                    "the scheduler printed, e.g. tcp://host:8786")


@contextmanager
def dask_client(scheduler: str | None = None, workers: int = 2):
    """A client of the scheduler at `scheduler`, or of a local cluster of `workers`
    single-threaded worker processes (numba kernels hold the GIL)."""
    try:
        from distributed import Client, LocalCluster
    except ImportError as exc:  # the `sweep` extra is optional
        raise RuntimeError("sweeps need dask.distributed: install the extra with "
                           "`pip install 'bearingsim[sweep]'` (or `pip install '.[sweep]'` in a checkout)") from exc

    if scheduler:
        with quiet_interrupt.quiet_on_interrupt(), Client(scheduler) as client:
            yield client
        return
    with quiet_interrupt.quiet_on_interrupt():
        # the preload: the workers go down quietly on Ctrl-C too
        with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=":0",
                          preload=[quiet_interrupt.__name__]) as cluster, Client(cluster) as client:
            yield client
