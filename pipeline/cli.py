"""`bearingsim` command line: scenes in, run directories out.

Stdout carries only what a command is asked to print (a table, or JSON with `--json`);
progress and log lines go to stderr and to `<run dir>/run.log`.
"""

from __future__ import annotations

import json
import logging
import sys
from pathlib import Path
from typing import Annotated, Optional

import typer
from rich.console import Console

from .runner import StageNotAvailable
from .schema import SceneError

app = typer.Typer(
    add_completion=False,
    no_args_is_help=True,
    help="Ball-bearing dynamics under high moment load: FE hinge identification, "
         "quasi-static equilibrium, HHT-alpha multibody simulation, cage burn-zone prediction.",
)
out_console = Console()
err_console = Console(stderr=True)

EXIT_SCENE, EXIT_UNAVAILABLE, EXIT_FAILED = 2, 3, 1

SceneArg = Annotated[str, typer.Argument(help="Scene TOML file, or the name of a built-in scene (see `bearingsim scenes`).")]
OutOpt = Annotated[Optional[Path], typer.Option("--out", help="Run directory [default: runs/<scene name>/].")]
ForceOpt = Annotated[bool, typer.Option("--force", help="Recompute even when cached results are up to date.")]
SetOpt = Annotated[Optional[list[str]], typer.Option(
    "--set", metavar="KEY=VALUE",
    help="Override a scene key for this run (repeatable), e.g. --set load.moment=250.")]


def _load(scene: str, overrides: list[str] | None):
    from .scene import load_scene

    return load_scene(scene, overrides or [])


def _run_dir(scene, out: Path | None) -> Path:
    return Path(out) if out is not None else Path("runs") / scene.name


def _fail(code: int, message: str) -> None:
    err_console.print(f"[bold red]error:[/] {message}", highlight=False)
    raise typer.Exit(code)


def _pipeline(scene_arg: str, overrides, out, targets: list[str], force: set[str], quiet: bool = False):
    """Load, validate, then run `targets` with progress on stderr; map errors to exit codes."""
    from .scene import read_scene_table

    try:
        scene = _load(scene_arg, overrides)
    except SceneError as exc:
        _fail(EXIT_SCENE, f"scene: {exc}")
    from .provenance import attach_run_log, write_run_provenance
    from .runner import run_stages
    from .stages import STAGES

    run_dir = _run_dir(scene, out)
    handler = attach_run_log(run_dir)
    try:
        write_run_provenance(run_dir, scene.raw, read_scene_table(scene_arg)[1])
        logging.getLogger("bearingsim").info("bearingsim %s: targets %s", scene.name, targets)
        with _StageProgress(quiet) as bar:
            outcomes = run_stages(scene, run_dir, STAGES, targets, force, progress=bar.update)
    except StageNotAvailable as exc:
        _fail(EXIT_UNAVAILABLE, f"{exc}. Results so far are in {run_dir}/")
    except SceneError as exc:
        _fail(EXIT_SCENE, f"scene: {exc}")
    except (RuntimeError, ValueError, ArithmeticError) as exc:
        logging.getLogger("bearingsim").exception("stage failed")
        _fail(EXIT_FAILED, f"{type(exc).__name__}: {exc}\n(full log: {run_dir / 'run.log'})")
    finally:
        logging.getLogger("bearingsim").removeHandler(handler)
        handler.close()
    if not quiet:
        for o in outcomes:
            extra = f" in {o.wall_time:.2f} s" if o.status == "computed" else ""
            err_console.print(f"  {o.name:<12} {o.status}{extra}", highlight=False)
        err_console.print(f"results: {run_dir}/", highlight=False)
    return scene, run_dir, outcomes


class _StageProgress:
    """A rich progress bar per stage on stderr (silent with --json or when quiet)."""

    def __init__(self, quiet: bool):
        self.quiet = quiet
        self.tasks: dict[str, int] = {}

    def __enter__(self):
        if not self.quiet:
            from rich.progress import (BarColumn, Progress, TextColumn, TimeElapsedColumn,
                                       TimeRemainingColumn)

            self.progress = Progress(TextColumn("{task.fields[stage]:<12}"), BarColumn(),
                                     TextColumn("{task.description}"), TimeElapsedColumn(),
                                     TextColumn("ETA"), TimeRemainingColumn(),
                                     console=err_console, transient=True)
            self.progress.__enter__()
        return self

    def update(self, stage: str, text: str, fraction: float) -> None:
        if self.quiet:
            return
        if stage not in self.tasks:
            self.tasks[stage] = self.progress.add_task(text, total=1.0, stage=stage)
        self.progress.update(self.tasks[stage], description=text, completed=max(0.0, min(1.0, fraction)))

    def __exit__(self, *exc):
        if not self.quiet:
            self.progress.__exit__(*exc)
        return False


@app.command()
def scenes() -> None:
    """List the built-in scenes with one-line descriptions."""
    from rich.table import Table

    from .scene import builtin_scene_names, read_scene_table

    table = Table("scene", "description", box=None)
    for name in builtin_scene_names():
        table.add_row(name, read_scene_table(name)[0].get("description", ""))
    out_console.print(table)


@app.command()
def check(scene: SceneArg, set_: SetOpt = None) -> None:
    """Validate a scene and print it resolved, with units and the derived geometry."""
    from .scene_report import print_scene

    try:
        resolved = _load(scene, set_)
    except SceneError as exc:
        _fail(EXIT_SCENE, f"scene: {exc}")
    print_scene(resolved, out_console)


@app.command()
def quasistatic(scene: SceneArg, json_: Annotated[bool, typer.Option("--json", help="Print the result as one JSON object on stdout.")] = False,
                out: OutOpt = None, force: ForceOpt = False, set_: SetOpt = None) -> None:
    """Static equilibrium: ball loads, contact angles, inner-race displacement, stiffness."""
    from .stages.quasistatic import RESULT_FILE

    _, run_dir, _ = _pipeline(scene, set_, out, ["quasistatic"], {"quasistatic"} if force else set(), quiet=json_)
    result = json.loads((run_dir / "quasistatic" / RESULT_FILE).read_text())
    if json_:
        sys.stdout.write(json.dumps(result) + "\n")
    else:
        from .scene_report import print_quasistatic

        print_quasistatic(result, out_console)


@app.command()
def identify(scene: SceneArg, out: OutOpt = None, set_: SetOpt = None) -> None:
    """Rerun only the FE hinge identification stage (its cache is ignored)."""
    try:
        resolved = _load(scene, set_)
    except SceneError as exc:
        _fail(EXIT_SCENE, f"scene: {exc}")
    if resolved.hinge.source != "fe":
        _fail(EXIT_SCENE, f"scene: hinge.source: is {resolved.hinge.source!r}; identification runs only "
                          "for hinge.source = 'fe' (try --set hinge.source=fe)")
    _pipeline(scene, set_, out, ["identify"], {"identify"})


@app.command()
def simulate(scene: SceneArg, out: OutOpt = None, force: ForceOpt = False, set_: SetOpt = None) -> None:
    """Dynamic run (and the stages it needs): cage orbit, speed, impacts, contact forces."""
    _pipeline(scene, set_, out, ["simulate"], {"simulate"} if force else set())


@app.command()
def run(scene: SceneArg, out: OutOpt = None, force: ForceOpt = False, set_: SetOpt = None) -> None:
    """Full pipeline: identify -> quasistatic -> simulate -> report (cached stages are skipped)."""
    from .stages import STAGE_NAMES

    _pipeline(scene, set_, out, ["report"], set(STAGE_NAMES) if force else set())


@app.command()
def render(run_dir: Annotated[Path, typer.Argument(help="A run directory written by `bearingsim run`.")],
           show: Annotated[bool, typer.Option("--show", help="Open an interactive window when a display is available.")] = False) -> None:
    """Regenerate renders and the report from saved results (never re-solves)."""
    _fail(EXIT_UNAVAILABLE, "render is not implemented yet (issue 8: FE deflection and burn-zone renders)")


@app.command()
def bench(scene: SceneArg,
          quick: Annotated[bool, typer.Option("--quick", help="CI-sized variant.")] = False) -> None:
    """Error against run time of the dynamic solver for a scene (work-precision study)."""
    _fail(EXIT_UNAVAILABLE, "bench is not implemented yet (issue 9: error against run time); "
                            "component benchmarks run as `python -m pipeline.bench.<name>`")


def main() -> None:  # pragma: no cover - console entry point
    app()
