"""`bearingsim.sweep`: a parameter sweep from Python, as `bearingsim sweep` runs it.

    import bearingsim
    result = bearingsim.sweep("helicopter-b-given-hinge", vary={"load.moment": [200, 430, 600]},
                              overrides={"solver.duration": 0.05})
    result.rows        # one dict per point: varied values, cage_class, risk, metrics, warnings
    result.map         # stability_map.png
    result.to_pandas() # the same table as a DataFrame (pandas needed)

The same plan, per-point run directories, shared stage store, resuming, results.csv and map
as the command line (`pipeline.sweep.driver`); see docs/outputs.md "Sweeps from Python".
"""

from __future__ import annotations

import base64
import html
import sys
import warnings
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np


@dataclass(frozen=True)
class SweepResult:
    """A finished sweep: its table (`rows`, as results.csv holds them), the varied keys, the
    stability map and the sweep directory."""

    rows: list[dict[str, Any]]
    varied: list[str]
    table: Path
    map: Path | None
    sweep_dir: Path

    def column(self, name: str) -> np.ndarray:
        """One column over the points (None where a point has no value)."""
        if self.rows and name not in self.rows[0]:
            raise KeyError(f"no column {name!r}; columns: {', '.join(self.rows[0])}")
        return np.array([r.get(name) for r in self.rows], dtype=object)

    def to_pandas(self):
        """The table as a pandas DataFrame (pandas is not a dependency of bearingsim)."""
        try:
            import pandas
        except ImportError:
            raise ImportError("to_pandas() needs pandas: pip install pandas (the rows are in .rows)") from None
        return pandas.DataFrame(self.rows)

    @property
    def plot(self) -> "SweepPlots":
        """`sweep.plot.map()`: the stability map as a matplotlib Figure (a line plot for one
        varied key)."""
        return SweepPlots(self)

    def __repr__(self) -> str:
        from collections import Counter

        classes = Counter(r.get("cage_class") for r in self.rows)
        counts = ", ".join(f"{n} {c}" for c, n in classes.most_common())
        short = sum(1 for r in self.rows if r.get("too_short_to_settle") in (True, "True"))
        if short:
            counts += f"; {short} too short to settle"
        return f"SweepResult({len(self.rows)} points over {', '.join(self.varied)}: {counts}; {self.sweep_dir})"

    def _repr_html_(self) -> str:
        columns = ["status", *self.varied, "cage_class", "risk", "too_short_to_settle", "cage_metal_contact_fraction",
                   "warnings"]
        head = "".join(f"<th>{html.escape(c)}</th>" for c in columns)
        body = "".join("<tr>" + "".join(f"<td>{html.escape(_cell(r.get(c)))}</td>" for c in columns) + "</tr>"
                       for r in self.rows)
        figure = ""
        if self.map is not None and Path(self.map).is_file():
            data = base64.b64encode(Path(self.map).read_bytes()).decode("ascii")
            figure = f'<img style="max-width:520px" alt="stability map" src="data:image/png;base64,{data}">'
        return (f"<div><b>sweep</b> <code>{html.escape(str(self.sweep_dir))}</code>"
                f"<table><tr>{head}</tr>{body}</table>{figure}</div>")


class SweepPlots:
    """The figures of a sweep, each a matplotlib Figure."""

    def __init__(self, result: SweepResult):
        self._result = result

    def map(self, x: str | None = None, y: str | None = None):
        """The cage-stability map: a line plot of the metal-contact fraction and the mean
        eccentricity over the one varied key, else the class map over two (`x`, `y`)."""
        from .stability_map import stability_map_figure

        return stability_map_figure(self._result.rows, self._result.varied, map_x=x, map_y=y)


def _cell(value) -> str:
    if value is None:
        return ""
    return f"{value:.4g}" if isinstance(value, float) else str(value)


def vary_strings(vary: Mapping[str, Any] | Iterable[str] | str) -> list[str]:
    """`{"load.moment": [0, 300]}` -> `["load.moment=0,300"]`; `{"k": "0:600:4"}` keeps the
    range; strings (the command line's `--vary`) pass through."""
    from ..scene.load import _toml_literal

    if isinstance(vary, str):
        return [vary]
    if not isinstance(vary, Mapping):
        return [str(v) for v in vary]
    out = []
    for key, values in vary.items():
        if isinstance(values, str):
            out.append(f"{key}={values}")
            continue
        if isinstance(values, np.ndarray):
            values = values.tolist()
        if not isinstance(values, (list, tuple)):
            values = [values]
        out.append(f"{key}=" + ",".join(_toml_literal(key, v) for v in values))
    return out


def sweep(scene, vary: Mapping[str, Any] | Iterable[str] | str, *,
          overrides: Mapping[str, Any] | Iterable[str] | None = None, mode: str | None = None,
          name: str | None = None, out: str | Path | None = None, workers: int = 2,
          scheduler: str | None = None, client=None, retry_failed: bool = False,
          progress: bool = False, figures: bool | None = None) -> SweepResult:
    """Run `scene` at every point of `vary` and return the table and the map.

    scene:     a Scene (`bearingsim.load_scene`), a built-in name or a TOML path.
    vary:      {"load.moment": [0, 300, 600], "speed.inner_rpm": "2000:6000:3"} (values or a
               `start:stop:count` range per dotted scene key), or `--vary` strings.
    overrides: changes to the base scene, as `bearingsim.load_scene` takes them.
    mode:      "factorial" (every combination, the default) or "list" (the i-th values together).
    out:       the sweep directory [default: runs/<scene name>-sweep/].
    workers:   local Dask worker processes; 0 runs the points one after the other in this
               process, without Dask (a notebook's small sweep).
    scheduler: address of a running Dask scheduler (instead of a local cluster); or give a
               `distributed.Client` as `client`.
    Finished points of an earlier call are reused (`retry_failed` reruns failed ones).
    """
    from ..scene.load import override_strings
    from ..staging.no_follow import named_in_python
    from .driver import (check_scheduler_address, dask_client, gather, plan_sweep, replaced_sweep, run_in_process,
                         run_sweep, sweep_directory_lock, unfinished)
    from .table import read_table

    if scheduler is not None:
        check_scheduler_address(scheduler)
    plan = plan_sweep(scene, override_strings(overrides), vary_strings(vary), mode=mode, name=name,
                      out=Path(out) if out is not None else None, figures=figures)
    with named_in_python("out"), sweep_directory_lock(plan):  # messages name this function's argument
        replaced = replaced_sweep(plan)
        if replaced:
            warnings.warn(replaced, stacklevel=2)
        report = _StatusPrinter() if progress else None
        if (workers == 0 and client is None and scheduler is None) or not unfinished(plan, retry_failed)[1]:
            records = run_in_process(plan, progress=report, retry_failed=retry_failed)
        elif client is not None:
            records = run_sweep(plan, client, progress=report, retry_failed=retry_failed)
        else:
            with dask_client(scheduler, workers) as made:
                if progress and getattr(made, "dashboard_link", None):
                    print(f"Dask dashboard: {made.dashboard_link}", file=sys.stderr, flush=True)
                records = run_sweep(plan, made, progress=report, retry_failed=retry_failed)
        paths = gather(plan, records, stacklevel=2)  # the warning points at the user's call of sweep()
    return SweepResult(read_table(paths["table"]), plan.varied, paths["table"], paths.get("map"), plan.sweep_dir)


class _StatusPrinter:
    """`progress=True`: a bar of the points done (tqdm.auto: a notebook widget, or stderr), with
    the ETA, the failed and running points and the workers running them."""

    def __init__(self):
        self.bar = None

    def __call__(self, status) -> None:
        from tqdm.auto import tqdm

        if self.bar is None:
            self.bar = tqdm(total=status.total, desc="sweep", unit="point")
        self.bar.n = status.done + status.failed
        workers = ", ".join(f"{w.rsplit('/', 1)[-1]}: {n}" for w, n in sorted(status.running_on.items()))
        self.bar.set_postfix_str(f"{status.failed} failed, {status.running} running"
                                 + (f" on {workers}" if workers else "")
                                 + (f", {status.resumed} from an earlier run" if status.resumed else "")
                                 + (f"; last {status.last}" if status.last else ""), refresh=False)
        self.bar.refresh()
        if status.done + status.failed >= status.total:
            self.bar.close()
