"""The Python API: load a scene, run stages in a run directory, read the results.

    import bearingsim
    scene = bearingsim.load_scene("helicopter-b-given-hinge", {"load.moment": 300})
    run = bearingsim.run(scene, "runs/demo", stages=["simulate"])
    run.summary["cage_speed_mean"], run.quasistatic["balls"], run.timeseries()["cage/speed"]

The same staged runner, cache and run-directory files as the command line
(`pipeline.staging.runner.run_stages`): a stage whose inputs are unchanged is not recomputed, and a
run directory written here is one `bearingsim render` or `bearingsim run` can continue.
Errors are raised, not mapped to exit codes: `SceneError` for a bad scene or override (it
names the key), `StageNotAvailable`, `RunDirectoryBusy`, and the solver's own
RuntimeError/ValueError with its hint.

Results come back as plain numbers and `NamedArray` (values, unit, dims,
description), which convert to xarray when it is installed (`.to_xarray()`); xarray is not a
dependency. Importing this module loads no numba, matplotlib or gmsh.
"""

from __future__ import annotations

import csv
import json
import sys
import time
import warnings
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable

import numpy as np

from .results.named_arrays import NamedArray, TimeSeries


DEFAULT_STAGES = ("report",)  # the whole pipeline, as `bearingsim run`
ProgressCallback = Callable[[str, str, float], None]  # (stage, text, fraction done)


# --- scenes --------------------------------------------------------------------------------
def load_scene(scene, overrides: Mapping[str, Any] | Iterable[str] | None = None):
    """A validated `Scene` from a scene file path, a built-in scene name, a scene's TOML text
    (``"name = 'x'\n[bearing]\n..."``), a dict (as `Scene.to_dict` gives it) or another Scene,
    with `overrides` applied.

    `overrides`: ``{"load.moment": 300, "solver.duration": 0.02}`` (dotted keys, Python
    values) or ``["load.moment=300"]`` (the command line's ``--set`` strings). Either way the
    value goes through the same TOML parsing and validation as the file, so a bad one raises
    `SceneError` naming the key, the value, what is allowed and the unit. Change a scene later
    with `Scene.replace`, which validates the same way.
    """
    from .machine.numba_cache import configure_numba_cache
    from .scene.load import load_scene as load

    configure_numba_cache()  # scene validation loads a few kernels' modules
    return load(scene, overrides)


def override_strings(overrides: Mapping[str, Any] | Iterable[str] | None) -> list[str]:
    """`{"load.moment": 300}` -> `["load.moment=300"]` (pipeline.scene.load.override_strings)."""
    from .scene.load import override_strings as strings

    return strings(overrides)


def scene_origin(scene) -> str:
    """Where a scene came from (a path or `built-in:<name>`), for the run directory's scene.toml."""
    return getattr(scene, "_origin", "a Scene object of the Python API")


# --- running -------------------------------------------------------------------------------
def run(scene, run_dir: str | Path | None = None, stages: str | Iterable[str] = DEFAULT_STAGES, *,
        overrides: Mapping[str, Any] | Iterable[str] | None = None,
        force: bool | str | Iterable[str] = False, progress: ProgressCallback | bool | None = None,
        store: str | Path | None = None) -> "Run":
    """Run `stages` of `scene` (and the stages they need) in `run_dir`; return the `Run`.

    scene:    a Scene (`load_scene`), or a built-in name / TOML path (loaded with `overrides`).
    run_dir:  the run directory [default: runs/<scene name>/, relative to the working directory].
    stages:   target stages, any of "identify", "quasistatic", "simulate", "report" [default:
              "report", i.e. everything, as `bearingsim run`]. Up-to-date stages are skipped.
    force:    True recomputes the stages named in `stages` (as `bearingsim simulate --force`);
              "all" every stage they need (as `bearingsim run --force`); or an iterable of names.
    progress: None/False silent; True shows a progress bar with ETA per stage (tqdm: a widget in a
              notebook, stderr in a terminal); or a callable (stage, text, fraction).
    store:    a stage store shared between run directories (as sweeps use; see pipeline.staging.runner).
    """
    from .staging.no_follow import named_in_python
    from .scene.load import Scene

    if not isinstance(scene, Scene) or overrides is not None:
        scene = load_scene(scene, overrides)
    run_dir = Path(run_dir) if run_dir is not None else Path("runs") / scene.name
    targets = check_stage_names(stages, "stages")
    callback = _progress_callback(progress)
    try:
        with named_in_python("run_dir"):
            outcomes = run_pipeline(scene, run_dir, targets, forced_stages(force, targets),
                                    progress=callback, store=store)
    finally:
        if isinstance(callback, StageBars):
            callback.close()
    return Run(scene, run_dir.absolute(), tuple(outcomes))  # absolute: valid after a chdir


def run_pipeline(scene, run_dir: Path, targets: list[str], force: set[str] = frozenset(), *,
                 progress: ProgressCallback | None = None, store: str | Path | None = None,
                 origin: str | None = None) -> list:
    """The command line's pipeline path (`cli._pipeline`), without its console: check what
    can be checked before solving (pipeline.scene.validity), claim the run directory (new, empty
    or bearingsim's), hold its lock, log to `<run_dir>/run.log`, write scene.toml and
    versions.json, then `runner.run_stages(scene, run_dir, STAGES, targets, force)`.
    Returns the StageOutcomes; the scene's and the stages' validity warnings are issued as
    Python warnings (and logged)."""
    from .machine.numba_cache import configure_numba_cache
    from .stages.session import check_before_solving, claimed, run_log, run_stages_logged

    configure_numba_cache()  # before any kernel loads, as the command line does
    run_dir = Path(run_dir)
    notes = check_before_solving(scene, targets)
    for note in notes:
        warnings.warn(f"scene: {note.text}", stacklevel=3)
    with claimed(run_dir), run_log(run_dir):
        outcomes = run_stages_logged(scene, run_dir, targets, set(force), origin or scene_origin(scene),
                                     notes=notes, progress=progress,
                                     store=Path(store) if store is not None else None, label=" (Python API)")
    for o in outcomes:
        for w in getattr(o, "warnings", None) or ():
            text = w.get("message", w) if isinstance(w, dict) else w
            key = w.get("key") if isinstance(w, dict) else None
            warnings.warn(f"{o.name}: {key + ': ' if key else ''}{text}", stacklevel=3)
    return outcomes


def stage_names() -> list[str]:
    from .stages import STAGE_NAMES

    return list(STAGE_NAMES)


def check_stage_names(stages: str | Iterable[str], what: str) -> list[str]:
    names = [stages] if isinstance(stages, str) else list(stages)
    allowed = stage_names()
    if not names:
        raise ValueError(f"{what}: no stage given; name at least one of {', '.join(allowed)}")
    unknown = [s for s in names if s not in allowed]
    if unknown:
        raise ValueError(f"{what}: {unknown[0]!r} is not a stage; choose from {', '.join(allowed)}")
    return names


def forced_stages(force: bool | str | Iterable[str], targets: list[str]) -> set[str]:
    if force is False or force is None:
        return set()
    if force is True:
        return set(targets)
    if force == "all":
        return set(stage_names())
    return set(check_stage_names(force, "force"))


def _progress_callback(progress) -> ProgressCallback | None:
    if progress is None or progress is False:
        return None
    if progress is True:
        return StageBars()
    return progress


class StageBars:
    """`progress=True`: one progress bar per stage with its ETA (tqdm.auto: a widget in a
    notebook, a bar on stderr in a terminal). It is fed by the stages' own progress callback,
    which the time loop calls about four times a second, so it costs the integration nothing."""

    def __init__(self):
        self.bars: dict[str, Any] = {}

    def __call__(self, stage: str, text: str, fraction: float) -> None:
        from tqdm.auto import tqdm

        bar = self.bars.get(stage)
        if bar is None:
            for other in self.bars.values():
                other.close()
            bar = self.bars[stage] = tqdm(total=100, desc=f"{stage:<11}", unit="%", leave=True,
                                          bar_format="{desc} {percentage:3.0f}%|{bar}| {elapsed}<{remaining} {postfix}")
        bar.n = round(100.0 * max(0.0, min(1.0, fraction)), 1)
        bar.set_postfix_str(text, refresh=False)
        bar.refresh()
        if fraction >= 1.0:
            bar.close()

    def close(self) -> None:
        for bar in self.bars.values():
            bar.close()


# --- results -------------------------------------------------------------------------------
@dataclass(frozen=True)
class Run:
    """A run directory and its scene; results are read from its files when asked for.

    `outcomes` are the StageOutcomes of the `run()` call that made it (empty from
    `open_run`); `stages` is what the directory holds now.
    """

    scene: Any
    run_dir: Path
    outcomes: tuple = field(default=())

    def stage_dir(self, stage: str) -> Path:
        return Path(self.run_dir) / stage

    def __repr__(self) -> str:
        """One line: the scene, the directory, the stages it holds and the verdict."""
        from .results.run_display import run_repr

        return run_repr(self)

    def _repr_html_(self) -> str:
        """A notebook's display: the verdict, its key numbers and the cage orbit."""
        from .results.run_display import run_html

        return run_html(self)

    @property
    def plot(self) -> "RunPlots":
        """The run's figures as matplotlib Figures: `run.plot.orbit()`, `.speed()`,
        `.impacts()`, `.burn_zone()`, `.load_distribution()`, `.animate(path)`; the report
        draws the same ones."""
        return RunPlots(self)

    @property
    def problems(self) -> list[str]:
        """What makes the directory's results other than its scene's, as computed: a stage computed
        from other inputs than scene.toml's, a stage file changed or missing since the stage wrote it
        (a missing figure is drawn again by `bearingsim render`). Empty when all is as computed."""
        from .stages import STAGES
        from .stages.consistency import check_run_directory, mismatch_message

        checks = check_run_directory(self.run_dir, self.scene, STAGES)
        out = [m for m in [mismatch_message(self.run_dir, checks)] if m]
        for c in checks:
            if c.damaged_data:
                out.append(f"{self.stage_dir(c.name)}: {', '.join(c.damaged_data[:5])} changed or went missing since the "
                           f"{c.name} stage wrote it: not the results as computed")
            if c.damaged_figures:
                out.append(f"{self.stage_dir(c.name)}: figures {', '.join(c.damaged_figures[:5])} changed or went "
                           f"missing; `bearingsim render {self.run_dir}` draws them again")
        return out

    @property
    def stages(self) -> dict[str, str]:
        """Stage name -> "done" for every finished stage in the directory, plus the status of
        this call's outcomes ("computed", "cached", "not needed", ...)."""
        from .staging.artefacts import read_manifest

        this_call = {o.name: o.status for o in self.outcomes}
        status = {}
        for name in stage_names():
            manifest = read_manifest(self.stage_dir(name))
            if name in this_call:
                status[name] = this_call[name]
            elif manifest and manifest.get("status") == "done":
                status[name] = "done"
        return status

    def _file(self, stage: str, filename: str) -> Path:
        """`<run_dir>/<stage>/<filename>`, or FileNotFoundError saying how to make it."""
        path = self.stage_dir(stage) / filename
        if not path.is_file():
            raise FileNotFoundError(
                f"{path} does not exist: stage {stage!r} has not run in {self.run_dir}; "
                f"run it with bearingsim.run(scene, {str(self.run_dir)!r}, stages=[{stage!r}])")
        return path

    def _json(self, stage: str, filename: str) -> dict:
        return json.loads(self._file(stage, filename).read_text(encoding="utf-8"))

    @property
    def summary(self) -> dict:
        """`simulate/summary.json`: the run's metrics (docs/outputs.md, docs/model.md §11), verdict, counters."""
        return self._json("simulate", "summary.json")

    @property
    def quasistatic(self) -> dict:
        """`quasistatic/quasistatic.json`: per-ball loads and angles ("balls"), inner-race
        displacement and tilt, 5x5 "stiffness" in "stiffness_order", units, crush screen."""
        from .stages.quasistatic import RESULT_FILE

        return self._json("quasistatic", RESULT_FILE)

    def quasistatic_arrays(self) -> dict[str, NamedArray]:
        """The per-ball quantities of `quasistatic` as NamedArrays over dimension "ball",
        and "stiffness" (5x5, dims ("force", "displacement") in (x, y, z, rx, ry) order)."""
        qs = self.quasistatic
        units = qs.get("units", {})
        unit_of = {"azimuth": "azimuth", "inner_load": "load", "outer_load": "load",
                   "inner_contact_angle": "contact_angle", "outer_contact_angle": "contact_angle",
                   "max_pressure_inner": "pressure", "max_pressure_outer": "pressure",
                   "truncation_margin_inner": "truncation_margin", "truncation_margin_outer": "truncation_margin"}
        out = {}
        for name, kind in unit_of.items():
            values = np.array([np.nan if b[name] is None else b[name] for b in qs["balls"]], dtype=float)
            out[name] = NamedArray(values, units.get(kind, ""), ("ball",), f"quasi-static {name.replace('_', ' ')}", name)
        out["stiffness"] = NamedArray(np.array(qs["stiffness"], dtype=float), units.get("stiffness", ""),
                                      ("force", "displacement"),
                                      f"bearing stiffness, order {', '.join(qs['stiffness_order'])}", "stiffness")
        return out

    @property
    def hinge(self) -> dict | None:
        """{"source", "translational" (H_u 3x3) [N/m], "bending" (H_psi, 2) [N.m/rad]} of the
        scene ("given") or of identify/hinge.toml ("fe"); None for hinge.source = "none"."""
        from .stiffness_export import hinge_of

        return hinge_of(self.scene, self.stage_dir("identify"))

    def timeseries(self, names: str | Iterable[str] | None = None) -> TimeSeries:
        """`simulate/timeseries.h5` as name -> NamedArray (all series, or only `names`: one
        name or several)."""
        from .results.timeseries import read_timeseries

        if isinstance(names, str):
            names = [names]
        path = self._file("simulate", "timeseries.h5")
        names = None if names is None else list(names)
        wanted = names if names is None or "time" in names else [*names, "time"]  # the coordinate
        series, attrs = read_timeseries(path, wanted)
        time = series["time"].data if "time" in series else None
        arrays = {n: NamedArray(s.data, s.units, s.dims, s.description, n) for n, s in series.items()
                  if names is None or n in names}
        return TimeSeries(arrays, attrs, path, time=time)

    def impacts(self) -> dict[str, NamedArray]:
        """`simulate/impacts.csv` as column name -> NamedArray over dimension "impact"."""
        path = self._file("simulate", "impacts.csv")
        with open(path, newline="", encoding="utf-8") as fh:
            rows = list(csv.reader(fh))
        out = {}
        for j, header in enumerate(rows[0]):
            name, _, unit = header.partition(" [")
            values = np.array([float(r[j]) for r in rows[1:]], dtype=float)
            if name == "ball":
                values = values.astype(int)
            out[name] = NamedArray(values, unit.rstrip("]"), ("impact",), f"ball-pocket impact: {name.replace('_', ' ')}", name)
        return out

    @property
    def report(self) -> Path | None:
        """The HTML report, when the report stage has run."""
        path = self.stage_dir("report") / "report.html"
        return path if path.is_file() else None

    def stiffness(self, speeds_rpm: Iterable[float] | None = None, write: bool = True):
        """Bearing and hinge stiffness over inner-ring speeds (see
        `export_stiffness`)."""
        from .stiffness_export import stiffness_table

        if write:
            return export_stiffness(self.scene, self.run_dir, speeds_rpm)
        return stiffness_table(self.scene, speeds_rpm, identify_dir=self.stage_dir("identify"))


class RunPlots:
    """The figures of one run (pipeline.render.run_plots), each a matplotlib Figure that
    Jupyter shows inline and `fig.savefig(...)` writes; FileNotFoundError naming the stage to
    run when the run lacks what a figure needs."""

    def __init__(self, run: Run):
        self._run = run

    def __repr__(self) -> str:
        return "RunPlots: orbit(), speed(), impacts(), burn_zone(), load_distribution(polar=True), animate(path)"

    def _dir(self, stage: str, filename: str) -> Path:
        return self._run._file(stage, filename).parent

    def orbit(self):
        """The cage-centre orbit behind the verdict (start-up grey, settled window coloured,
        guide and film clearance, loaded sector, thinnest film)."""
        from .render.run_plots import orbit_figure

        return _drawn(orbit_figure(self._run.scene, self._dir("simulate", "timeseries.h5")), "the cage orbit")

    def speed(self):
        """Cage speed against time, its settled mean and the epicyclic speed."""
        from .render.run_plots import speed_figure

        qs = self._run.stage_dir("quasistatic")
        return _drawn(speed_figure(self._run.scene, self._dir("simulate", "timeseries.h5"),
                                   qs if qs.is_dir() else None), "the cage speed")

    def impacts(self):
        """Ball–pocket impacts: peak force against time and against orbital position."""
        from .render.run_plots import impacts_figure

        return impacts_figure(self._run.scene, self._dir("simulate", "impacts.csv"))

    def burn_zone(self):
        """The polar burn map of the guiding land, centred on its hot sector."""
        from .render.run_plots import burn_zone_figure

        sim = self._dir("simulate", "timeseries.h5")
        return burn_zone_figure(self._run.scene, simulate_dir=sim)

    def load_distribution(self, polar: bool = True):
        """The quasi-static ball loads round the bearing (`polar=False`: loads, contact angles
        and the crush screen against azimuth)."""
        from .render.run_plots import load_distribution_figure

        return load_distribution_figure(self._run.scene, self._dir("quasistatic", "quasistatic.json"), polar)

    def animate(self, path: str | Path, frames: int = 120, fps: int = 15) -> Path:
        """The cage orbit with the balls in their pockets as an animation: `.gif` (Pillow) or
        `.mp4` (needs ffmpeg). Returns the path written."""
        from .render.animation import write_cage_animation

        return write_cage_animation(self._run.scene, self._dir("simulate", "timeseries.h5"), Path(path), frames, fps)


def _drawn(fig, what: str):
    if fig is None:
        raise ValueError(f"no {what}: the run has no cage series (the scene has no [cage])")
    return fig


def open_run(run_dir: str | Path) -> Run:
    """A `Run` of an existing run directory (its scene from `<run_dir>/scene.toml`). When
    scene.toml does not describe the results (edited, or written by a later command with other
    inputs) or a stage's files changed since it wrote them, a UserWarning says so (`Run.problems`)."""
    run_dir = Path(run_dir)
    scene_file = run_dir / "scene.toml"
    if not scene_file.is_file():
        raise FileNotFoundError(f"{run_dir} is not a run directory: it has no scene.toml")
    run = Run(load_scene(scene_file), run_dir.absolute())
    for problem in run.problems:
        warnings.warn(problem, stacklevel=2)
    return run


# --- stiffness export ----------------------------------------------------------------------
def export_stiffness(scene, run_dir: str | Path | None = None, speeds_rpm: Iterable[float] | float | None = None,
                     *, progress=None) -> StiffnessTable:
    """The stiffness table of `scene` written to `<run_dir>/stiffness/` (stiffness.csv,
    stiffness.json). Runs (or reuses, by its cache key) the identify stage first when the
    hinge is identified by FE. `scene`: a Scene or a scene name/path."""
    from .staging.artefacts import claim_run_directory, run_directory_lock
    from .staging.no_follow import named_in_python
    from .scene.load import Scene
    from .stiffness_export import STIFFNESS_DIR, check_speeds, stiffness_table, table_inputs, write_stiffness_table

    if not isinstance(scene, Scene):
        scene = load_scene(scene)
    run_dir = Path(run_dir) if run_dir is not None else Path("runs") / scene.name
    check_speeds(speeds_rpm, scene)  # a bad list fails before the FE stage runs
    if scene.hinge.source == "fe":
        run(scene, run_dir, ["identify"], progress=progress)
    table = stiffness_table(scene, speeds_rpm, identify_dir=run_dir / "identify")
    with named_in_python("run_dir"):
        claim_run_directory(run_dir)  # never write into a folder that is not a run directory
        with run_directory_lock(run_dir):
            write_stiffness_table(table, run_dir / STIFFNESS_DIR, table_inputs(scene, table))
    return table
