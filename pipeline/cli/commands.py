"""`bearingsim` command line: scenes in, run directories out.

Stdout carries only what a command is asked to print (a table, or JSON with `--json`);
progress and log lines go to stderr and to `<run dir>/run.log`. `run` and `simulate` end
with the run's verdict (`summary.json` `verdict`) on stderr, after the stage lines.
"""

from __future__ import annotations

import contextlib
import errno
import json
import logging
import math
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Annotated, Optional

import typer

from .options import flat_options
from ..console import explain, finding_lines, make_console, styled
from ..machine.numba_cache import configure_numba_cache

# before any kernel is compiled or loaded: the cache keyed by the dynamics sources
configure_numba_cache()

from ..staging.artefacts import OutputRefused, RunDirectoryBusy  # noqa: E402
from .interrupts import interruption, stop_on_sigterm  # noqa: E402
from ..staging.runner import StageNotAvailable
from ..scene.schema import SceneError

app = typer.Typer(
    add_completion=False,
    no_args_is_help=True,
    help="Ball-bearing dynamics under high moment load: FE hinge identification, "
         "quasi-static equilibrium, HHT-alpha multibody simulation, cage burn-zone prediction.",
)
out_console = make_console()
err_console = make_console(stderr=True)

EXIT_SCENE, EXIT_UNAVAILABLE, EXIT_FAILED, EXIT_INTERRUPTED = 2, 3, 1, 130
EXIT_NOT_SIMULABLE = 4  # check: valid for the quasi-static stage, refused by simulate and run


def _print_version(value: bool) -> None:
    if value:
        from ..staging.provenance import package_version

        out_console.print(f"bearingsim {package_version()}", highlight=False, markup=False)
        raise typer.Exit()


@app.callback()
def _root(version: Annotated[bool, typer.Option("--version", is_eager=True, callback=_print_version,
                                                help="Print bearingsim's version and exit.")] = False) -> None:
    """Ball-bearing dynamics under high moment load: FE hinge identification, quasi-static
    equilibrium, HHT-alpha multibody simulation, cage burn-zone prediction."""


def _literal(text: str) -> str:
    """Help text shown as written: typer renders help as rich markup, which swallows units and
    defaults in square brackets ("[s]", "[default: ...]")."""
    from rich.markup import escape

    return escape(text)


SceneArg = Annotated[str, typer.Argument(help="Scene TOML file, or the name of a built-in scene (see `bearingsim scenes`).")]
OutOpt = Annotated[Optional[Path], typer.Option("--out", help=_literal("Run directory [default: runs/<scene name>/]."))]
ForceOpt = Annotated[bool, typer.Option("--force", help="Recompute even when cached results are up to date.")]
NoStoreOpt = Annotated[bool, typer.Option(
    "--no-store", help="Do not share the FE identification through the user's stage store "
                       "(~/.cache/bearingsim/stages): compute it in this run directory only.")]
SetOpt = Annotated[Optional[list[str]], typer.Option(
    "--set", metavar="KEY=VALUE",
    help="Override a scene key for this run (repeatable), e.g. --set load.moment=250.")]


def _load(scene: str, overrides: list[str] | None):
    from ..scene.load import load_scene

    _print_cache_notes()
    return load_scene(scene, overrides or [])


def _print_cache_notes() -> None:
    """What checking the kernel cache found (pipeline.machine.numba_cache): damaged files removed,
    a cache folder that could not be made."""
    from ..machine.numba_cache import cache_notes

    for note in cache_notes():
        err_console.print(styled(("warning:", "yellow"), f" {note}"), highlight=False, soft_wrap=True)


def _kernel_cache_failure(exc: BaseException) -> str | None:
    """The message for a failure while numba read its cache (a damaged file the start-up check did
    not catch), naming the cache and what to do; None for any other failure. The next start reads
    every cache file again."""
    from ..machine.kernel_cache import cache_directory
    from ..machine.numba_cache import forget_checks, from_kernel_cache, is_own_cache

    cache = cache_directory()
    if cache is None or not from_kernel_cache(exc):
        return None
    forget_checks(cache)
    again = "run the command again: damaged files are then found and removed" if is_own_cache(cache) else \
        "delete the folder (NUMBA_CACHE_DIR): the kernels then compile again"
    return (f"the kernel cache {cache} cannot be read ({type(exc).__name__}: {exc}); {again} (about a minute of "
            f"compiling)")


def _run_dir(scene, out: Path | None) -> Path:
    return Path(out) if out is not None else Path("runs") / scene.name


def _fail(code: int, message: str) -> None:
    err_console.print(styled(("error:", "bold red"), f" {message}"), highlight=False, soft_wrap=True)
    raise typer.Exit(code)


def _print_findings(findings, prefix: str = "") -> None:
    for line in finding_lines(findings, prefix):
        err_console.print(line, highlight=False, soft_wrap=True)


def _pipeline(scene_arg: str, overrides, out, targets: list[str], force: set[str], quiet: bool = False,
              shared: bool = True):
    """Load, validate, then run `targets` with progress on stderr; map errors to exit codes.

    Everything that can be checked without solving is checked before any file is written:
    the scene (pipeline.scene.validity), what the stages to run need, and that the run directory
    is bearingsim's to write (new, empty or marked by it)."""
    from ..stages.session import check_before_solving, claimed

    try:
        scene = _load(scene_arg, overrides)
        notes = check_before_solving(scene, targets)
    except SceneError as exc:
        _fail(EXIT_SCENE, f"scene: {explain(exc)}")
    _print_findings(notes)
    run_dir = _run_dir(scene, out)
    with contextlib.ExitStack() as held:
        try:
            held.enter_context(claimed(run_dir))
        except OutputRefused as exc:
            _fail(EXIT_SCENE, str(exc))
        except RunDirectoryBusy as exc:
            _fail(EXIT_FAILED, str(exc))
        except OSError as exc:
            from .os_errors import describe_os_error

            _fail(EXIT_FAILED, f"cannot claim {run_dir}/: {describe_os_error(exc, run_dir)}")
        outcomes = _run_locked(scene, scene_arg, run_dir, targets, force, quiet, notes, shared)
    if not quiet:
        for o in outcomes:
            extra = (f" in {o.wall_time:.2f} s" if o.status == "computed"
                     else " (reused: same inputs as an earlier run)" if o.status == "from store" else "")
            if o.status == "computed" and o.info.get("kernel_load_time", 0.0) > 5.0:
                # numba compiles the kernels on a machine's first run (and after a code change)
                extra += f", of which {o.info['kernel_load_time']:.0f} s compiling the force kernels (once)"
            err_console.print(f"  {o.name:<12} {o.status}{extra}", highlight=False)
    for o in outcomes:
        _print_findings(o.warnings, f"{o.name}: ")
    if not quiet:
        err_console.print(f"results: {run_dir}/", highlight=False, soft_wrap=True)
    return scene, run_dir, outcomes


def _run_locked(scene, scene_arg, run_dir, targets, force, quiet, notes=(), shared=True):
    """The stages of `_pipeline`, run while it holds the run directory's lock."""
    from ..stages.session import run_log

    with contextlib.ExitStack() as logged:
        try:
            logged.enter_context(run_log(run_dir))
        except OutputRefused as exc:
            _fail(EXIT_SCENE, str(exc))
        except OSError as exc:
            from .os_errors import describe_os_error

            if exc.errno in (errno.ENOSPC, getattr(errno, "EDQUOT", errno.ENOSPC)):
                _fail(EXIT_FAILED, describe_os_error(exc, run_dir))
            _fail(EXIT_SCENE, f"--out {run_dir}: cannot write run.log there ({exc.strerror or exc}); give a "
                              "writable directory")
        return _run_stages_reported(scene, scene_arg, run_dir, targets, force, quiet, notes, shared)


def _run_stages_reported(scene, scene_arg, run_dir, targets, force, quiet, notes, shared=True):
    """The stages, with every failure logged to run.log and mapped to an exit code; on a cold
    kernel cache the dynamic run's kernels compile meanwhile in a second process
    (`compile_ahead`)."""
    from . import compile_ahead
    from ..staging.runner import closure
    from ..stages import STAGES

    child = compile_ahead.start(scene, closure(STAGES, targets))
    try:
        return _run_stages_with_exit_codes(scene, scene_arg, run_dir, targets, force, quiet, notes, shared)
    finally:
        compile_ahead.stop(child)


def _run_stages_with_exit_codes(scene, scene_arg, run_dir, targets, force, quiet, notes, shared):
    from ..staging.artefacts import SHARED_STAGES, shared_store_dir
    from ..stages.session import run_stages_logged
    from ..scene.load import read_scene_table

    log = logging.getLogger("bearingsim")
    hint = ("\nnote: " + "\nnote: ".join(f.text for f in notes)) if notes else ""
    try:
        with _StageProgress(quiet) as bar:
            return run_stages_logged(scene, run_dir, targets, force, read_scene_table(scene_arg)[1],
                                     notes=notes, progress=bar.update,
                                     store=shared_store_dir() if shared else None, store_stages=SHARED_STAGES)
    except KeyboardInterrupt as exc:
        how, code = interruption(exc)
        log.warning("interrupted %s(%s); finished stages are kept, the interrupted one left nothing behind",
                    "by the user " if how == "Ctrl-C" else "", how)
        _fail(code, f"interrupted ({how}): finished stages are kept in {run_dir}/, the "
                    "interrupted stage left nothing; run the same command again to continue")
    except StageNotAvailable as exc:
        _fail(EXIT_UNAVAILABLE, f"{exc}. Results so far are in {run_dir}/")
    except OutputRefused as exc:
        log.error("%s", exc)
        _fail(EXIT_SCENE, str(exc))
    except SceneError as exc:
        log.error("scene: %s", exc)
        _fail(EXIT_SCENE, f"scene: {explain(exc)}")
    except (RuntimeError, ValueError, ArithmeticError) as exc:
        log.exception("stage failed")
        _fail(EXIT_FAILED, _kernel_cache_failure(exc) or
              f"{type(exc).__name__}: {explain(exc)}{hint}\n(full log: {run_dir / 'run.log'})")
    except MemoryError:
        from .os_errors import MEMORY_HINT

        log.exception("out of memory")
        _fail(EXIT_FAILED, f"out of memory{hint}; {MEMORY_HINT} (full log: {run_dir / 'run.log'})")
    except OSError as exc:
        from ..machine.kernel_cache import cache_directory
        from ..machine.numba_cache import from_kernel_cache
        from .os_errors import describe_os_error

        log.exception("file error")
        if exc.filename is None and from_kernel_cache(exc):  # numba writing a compiled kernel
            exc.filename = str(cache_directory())
        _fail(EXIT_FAILED, f"{describe_os_error(exc, run_dir)}{hint}\n(full log: {run_dir / 'run.log'})")
    except Exception as exc:  # noqa: BLE001 - a defect: the traceback goes to run.log, not the screen
        cache_failure = _kernel_cache_failure(exc)
        log.exception("kernel cache unreadable" if cache_failure else "internal error")
        _fail(EXIT_FAILED, cache_failure or f"internal error {type(exc).__name__}: {exc} (a defect of bearingsim; "
                                            f"the traceback is in {run_dir / 'run.log'})")


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
        if fraction >= 1.0:  # the stage finished: a full bar, and its clock stops
            self.progress.stop_task(self.tasks[stage])

    def __exit__(self, *exc):
        if not self.quiet:
            self.progress.__exit__(*exc)
        return False


@app.command()
def scenes(name: Annotated[Optional[str], typer.Argument(
        help="Print this built-in scene's TOML, to start a scene of your own from it "
             "(bearingsim scenes helicopter-b > my-bearing.toml).")] = None) -> None:
    """List the built-in scenes with one-line descriptions, or print one of them."""
    from rich.table import Table

    from ..scene.load import builtin_scene_names, builtin_scene_text, read_scene_table

    if name is not None:
        try:
            sys.stdout.write(builtin_scene_text(name))
        except SceneError as exc:
            _fail(EXIT_SCENE, f"scene: {explain(exc)}")
        return

    table = Table("scene", "description", box=None)
    for name in builtin_scene_names():
        table.add_row(name, read_scene_table(name)[0].get("description", ""))
    out_console.print(table)


@app.command()
def lubricants() -> None:
    """List the built-in lubricants: viscosity at 40 and 100 °C, model, alpha*, source."""
    from .libraries import print_lubricants

    print_lubricants(out_console)


@app.command()
def materials() -> None:
    """List the built-in materials (cage, ball, race) with their values and sources."""
    from .libraries import print_materials

    print_materials(out_console)


@app.command()
def check(scene: SceneArg, set_: SetOpt = None) -> None:
    """Validate a scene and print it resolved, with units and the derived geometry. Exit code 4:
    the scene is valid for the quasi-static stage, but simulate and run would refuse it (the
    first lines say why)."""
    from .scene_tables import print_scene

    from ..stages.session import fe_findings
    from ..scene.validity import raise_errors, run_findings, scene_findings

    try:
        resolved = _load(scene, set_)
        notes = raise_errors(scene_findings(resolved)) + raise_errors(fe_findings(resolved))
        _check_sweep_table(scene, set_)
    except SceneError as exc:
        _fail(EXIT_SCENE, f"scene: {explain(exc)}")
    refusals = [f for f in run_findings(resolved, {"simulate"}) if f.level == "error"]
    if refusals:  # first, before the tables: what a user about to simulate must know
        err_console.print("simulate and run would refuse this scene (the quasi-static stage runs): "
                          + "; ".join(f.text for f in refusals), highlight=False, soft_wrap=True)
    try:
        print_scene(resolved, out_console)  # the lubricant's viscosity is a compiled kernel's
    except Exception as exc:  # noqa: BLE001 - only a damaged kernel cache is answered here
        message = _kernel_cache_failure(exc)
        if message is None:
            raise
        _fail(EXIT_FAILED, message)
    _print_findings(notes)
    if refusals:
        raise typer.Exit(EXIT_NOT_SIMULABLE)


def _check_sweep_table(scene: str, overrides) -> None:
    """Every point of the scene's own [sweep] table, validated as `sweep` would (SceneError)."""
    from ..scene.load import apply_overrides, read_scene_table
    from ..sweep.driver import plan_sweep

    table = apply_overrides(read_scene_table(scene)[0], list(overrides or []))
    sweep = table.get("sweep")
    if isinstance(sweep, dict) and ("vary" in sweep or "points" in sweep):
        plan_sweep(scene, overrides)


@app.command()
def quasistatic(scene: SceneArg, json_: Annotated[bool, typer.Option("--json", help="Print the result as one JSON object on stdout.")] = False,
                out: OutOpt = None, force: ForceOpt = False, set_: SetOpt = None) -> None:
    """Static equilibrium: ball loads, contact angles, inner-race displacement, stiffness."""
    from ..figures.worker import prestart

    prestart()  # matplotlib loads in a second process while this one loads the scene and solves

    from ..staging.artefacts import dumps_json

    run_dir, result = _quasistatic_result(scene, set_, out, force, json_)
    if json_:
        sys.stdout.write(dumps_json(result) + "\n")
    else:
        from .scene_tables import print_quasistatic

        print_quasistatic(result, out_console)


def _quasistatic_result(scene: str, overrides, out, force: bool, quiet: bool) -> tuple[Path, dict]:
    """Run (or reuse) the quasi-static stage and read its result file."""
    from ..stages.quasistatic import RESULT_FILE

    _, run_dir, _ = _pipeline(scene, overrides, out, ["quasistatic"], {"quasistatic"} if force else set(), quiet=quiet)
    path = run_dir / "quasistatic" / RESULT_FILE
    try:
        return run_dir, json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError) as exc:
        _fail(EXIT_FAILED, f"cannot read {path}: {exc}; run again with --force")


@app.command()
def tolerances(scene: SceneArg,
               tolerance_file: Annotated[Optional[Path], typer.Option(
                   "--tolerances", metavar="FILE",
                   help=_literal("TOML file whose [tolerances] table replaces the scene's (docs/scenes.md)."))] = None,
               samples: Annotated[Optional[int], typer.Option("--samples", help="Stacks to sample (100 to 1 000 000).")] = None,
               seed: Annotated[Optional[int], typer.Option("--seed", help="Seed of the sampling (reproducible).")] = None,
               json_: Annotated[bool, typer.Option("--json", help="Print the analysis as one JSON object on stdout.")] = False,
               out: Annotated[Optional[Path], typer.Option("--out", help=_literal(
                   "Run directory [default: runs/<scene name>-tolerances/, apart from the scene's own run, "
                   "whose dynamic results a changed quasi-static stage would make stale]."))] = None,
               force: ForceOpt = False, set_: SetOpt = None) -> None:
    """Crush probability over tolerance stacks: P(free/pressed/crushed), margin distribution, drivers."""
    from ..stages.quasistatic import SAMPLES_FILE, TOLERANCE_FIGURE
    from .tolerance_tables import print_tolerances, tolerance_overrides

    try:
        overrides = list(set_ or []) + tolerance_overrides(tolerance_file, samples, seed)
        resolved = _load(scene, overrides)
        if resolved.tolerances is None:
            raise SceneError("tolerances", "the scene has no [tolerances] table: give one in the scene or with "
                                           "--tolerances FILE (docs/scenes.md, section [tolerances])")
    except SceneError as exc:
        _fail(EXIT_SCENE, f"scene: {explain(exc)}")
    if out is None:
        out = Path("runs") / f"{resolved.name}-tolerances"
    run_dir, result = _quasistatic_result(scene, overrides, out, force, json_)
    if json_:
        from ..staging.artefacts import dumps_json

        sys.stdout.write(dumps_json(result["crush_probability"]) + "\n")
        return
    print_tolerances(result, out_console)
    err_console.print(f"written: {run_dir / 'quasistatic' / SAMPLES_FILE}, "
                      f"{run_dir / 'quasistatic' / TOLERANCE_FIGURE}", highlight=False, soft_wrap=True)


@app.command()
def warmup(scenes: Annotated[Optional[list[str]], typer.Argument(
        help=_literal("Scenes to compile for (files or built-in names) [default: every built-in scene]."))] = None) -> None:
    """Compile the force kernels once for this machine (container images, cluster nodes): later runs start warm."""
    from ..machine.kernel_cache import cache_directory
    from .warmup import warm_up

    def report(row: dict) -> None:
        err_console.print(f"  {row['scene']:<28} {row['status']}"
                          + (f" in {row['seconds']:.1f} s" if row["seconds"] > 0 else ""), highlight=False)

    try:
        warm_up(scenes, report)
    except SceneError as exc:
        _fail(EXIT_SCENE, f"scene: {explain(exc)}")
    err_console.print(f"kernels cached in {cache_directory()}/", highlight=False, soft_wrap=True)


@app.command()
def stiffness(scene: SceneArg,
              speeds: Annotated[Optional[str], typer.Option(
                  "--speeds", metavar="RPM,...",
                  help=_literal("Inner-ring speeds [rev/min]: a,b,c or start:stop:count [default: the scene's speed.inner_rpm]."))] = None,
              out: OutOpt = None, set_: SetOpt = None) -> None:
    """Bearing (5x5) and hinge stiffness over inner-ring speeds: CSV + JSON for rotordynamics codes (ROSS)."""
    from ..api import export_stiffness
    from ..stiffness_export import CSV_FILE, JSON_FILE, STIFFNESS_DIR, parse_speeds

    try:
        resolved = _load(scene, set_)
        speed_list = parse_speeds(speeds) if speeds else None
    except SceneError as exc:
        _fail(EXIT_SCENE, f"scene: {explain(exc)}")
    from ..staging.no_follow import named_on_command_line

    run_dir = _run_dir(resolved, out)
    try:
        with named_on_command_line():
            table = export_stiffness(resolved, run_dir, speed_list)
    except SceneError as exc:
        _fail(EXIT_SCENE, f"scene: {explain(exc)}")
    except OutputRefused as exc:
        _fail(EXIT_SCENE, str(exc))
    except RunDirectoryBusy as exc:
        _fail(EXIT_FAILED, str(exc))
    except StageNotAvailable as exc:
        _fail(EXIT_UNAVAILABLE, str(exc))
    except (RuntimeError, ValueError, ArithmeticError) as exc:
        _fail(EXIT_FAILED, f"{type(exc).__name__}: {explain(exc)}")
    out_console.print(table.markdown(), highlight=False, soft_wrap=True, markup=False)
    if not table.converged.all():
        err_console.print("warning: the quasi-static solve did not converge at some speeds (column converged)",
                          highlight=False)
    err_console.print(f"written: {run_dir / STIFFNESS_DIR / CSV_FILE}, {run_dir / STIFFNESS_DIR / JSON_FILE}",
                      highlight=False, markup=False)


RefineOpt = Annotated[bool, typer.Option(
    "--refine", help="Also identify on a once-refined discretisation (mesh_size halved; a mesh: every "
                     "tetrahedron split into eight) and report the change of H: the same as "
                     "--set fe.refinement_check=true.")]


@app.command()
def identify(scene: SceneArg, out: OutOpt = None, set_: SetOpt = None, no_store: NoStoreOpt = False,
             refine: RefineOpt = False) -> None:
    """Rerun only the FE hinge identification stage (its cache is ignored)."""
    if refine:
        set_ = [*(set_ or []), "fe.refinement_check=true"]
    try:
        resolved = _load(scene, set_)
    except SceneError as exc:
        _fail(EXIT_SCENE, f"scene: {exc}")
    if resolved.hinge.source != "fe":
        _fail(EXIT_SCENE, f"scene: hinge.source: is {resolved.hinge.source!r}; identification runs only "
                          "for hinge.source = 'fe' (try --set hinge.source=fe)")
    _, run_dir, _ = _pipeline(scene, set_, out, ["identify"], {"identify"}, shared=not no_store)
    if refine:
        _print_refinement(run_dir / "identify" / "hinge.toml")


def _print_refinement(hinge_file: Path) -> None:
    """The change of each hinge term on the refined discretisation, on stdout."""
    import tomllib

    refinement = tomllib.loads(hinge_file.read_text(encoding="utf-8")).get("refinement", {})
    changes = refinement.get("relative_change", {})
    out_console.print(f"refinement ({refinement.get('what')}, {refinement.get('dofs')} dofs): change of H "
                      "(scene - refined) / refined: " + ", ".join(f"{k} {v:+.3%}" for k, v in changes.items()),
                      highlight=False, soft_wrap=True, markup=False)


@app.command()
def simulate(scene: SceneArg, out: OutOpt = None, force: ForceOpt = False, set_: SetOpt = None,
             no_store: NoStoreOpt = False) -> None:
    """Dynamic run (and the stages it needs): cage orbit, speed, impacts, contact forces."""
    _, run_dir, _ = _pipeline(scene, set_, out, ["simulate"], {"simulate"} if force else set(), shared=not no_store)
    _print_verdict(run_dir)


@app.command()
def run(scene: SceneArg, out: OutOpt = None, force: ForceOpt = False, set_: SetOpt = None,
        no_store: NoStoreOpt = False) -> None:
    """Full pipeline: identify -> quasistatic -> simulate -> report (cached stages are skipped;
    the FE identification is shared between run directories with the same FE inputs)."""
    from ..stages import STAGE_NAMES

    _, run_dir, _ = _pipeline(scene, set_, out, ["report"], set(STAGE_NAMES) if force else set(),
                              shared=not no_store)
    _print_verdict(run_dir)


def _print_verdict(run_dir: Path) -> None:
    """The verdict of the run's summary.json on stderr (nothing when the run has no summary)."""
    from ..results.verdict import verdict_lines

    try:
        summary = json.loads((run_dir / "simulate" / "summary.json").read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return
    for line in verdict_lines(summary):
        err_console.print(line, highlight=False, markup=False, soft_wrap=True)


@app.command()
def render(run_dir: Annotated[Path, typer.Argument(help="A run directory written by `bearingsim run`.")],
           show: Annotated[bool, typer.Option("--show", help="Open an interactive window when a display is available.")] = False,
           animate: Annotated[bool, typer.Option("--animate", help=_literal(
               "Also write the cage orbit with the balls in their pockets as an animation: <run>/animation/"
               "cage_orbit.gif (.mp4 too when ffmpeg is installed)."))] = False) -> None:
    """Regenerate renders and the report from saved results (never re-solves)."""
    from ..render.offscreen import display_available
    from ..staging.artefacts import RUN_MARKER, is_own_run_dir, run_directory_lock

    if not is_own_run_dir(run_dir):  # checked before anything is written: not even run.log or .lock
        _fail(EXIT_SCENE, f"{run_dir} is not a run directory bearingsim wrote (no {RUN_MARKER} marker, no resolved "
                          "scene.toml beside versions.json); nothing was written there. Give the directory "
                          "`bearingsim run SCENE` printed, e.g. runs/helicopter-b")
    if show and not display_available():
        err_console.print("no display (DISPLAY / WAYLAND_DISPLAY unset): rendering off-screen only", highlight=False)
        show = False
    elif not show:
        err_console.print("rendering off-screen", highlight=False)
    with contextlib.ExitStack() as held:
        try:  # as a run holds it: no stage is replaced while the report is drawn from it
            held.enter_context(run_directory_lock(run_dir))
        except RunDirectoryBusy as exc:
            _fail(EXIT_FAILED, str(exc))
        except OutputRefused as exc:
            _fail(EXIT_SCENE, str(exc))
        except OSError as exc:
            _fail(EXIT_SCENE, _render_cannot_write(run_dir, exc))
        outcome = _render_locked(run_dir, show)
        err_console.print(f"  report       computed in {outcome.wall_time:.2f} s", highlight=False)
        err_console.print(f"report: {run_dir / 'report' / outcome.info['report']}", highlight=False, markup=False)
        if animate:
            _write_animation(run_dir)


def _render_cannot_write(run_dir: Path, exc: OSError) -> str:
    return (f"{run_dir}: cannot write the report there ({exc.strerror or exc}); render needs a run directory it "
            f"may write (its report/ is redrawn): copy it, e.g. cp -r {run_dir} {run_dir}-copy")


def _render_locked(run_dir: Path, show: bool):
    """`render` while it holds the run directory's lock: run.log, then the report stage."""
    from ..staging.provenance import attach_run_log
    from ..stages.report import SceneNotOfResults, StageResultsDamaged, render_run

    log = logging.getLogger("bearingsim")
    try:
        handler = attach_run_log(run_dir)
    except OSError as exc:  # OutputRefused too: a link or a special file in run.log's place
        _fail(EXIT_SCENE, str(exc) if isinstance(exc, OutputRefused) else _render_cannot_write(run_dir, exc))
    try:
        return render_run(run_dir, show=show)
    except KeyboardInterrupt as exc:
        how, code = interruption(exc)
        log.warning("render interrupted (%s); the report was left as it was", how)
        _fail(code, f"interrupted ({how}): {run_dir / 'report'}/ is left as it was; run render again")
    except SceneError as exc:
        _fail(EXIT_SCENE, f"scene: {explain(exc)}")
    except (FileNotFoundError, OutputRefused, StageResultsDamaged, SceneNotOfResults) as exc:
        log.error("render refused: %s", exc)
        _fail(EXIT_SCENE, str(exc))
    except PermissionError as exc:
        log.error("render failed: %s", exc)
        _fail(EXIT_SCENE, _render_cannot_write(run_dir, exc))
    except OSError as exc:
        from .os_errors import describe_os_error

        log.exception("render failed")
        _fail(EXIT_FAILED, f"{describe_os_error(exc, run_dir)}\n(full log: {run_dir / 'run.log'})")
    except (RuntimeError, ValueError, ArithmeticError) as exc:
        log.exception("render failed")
        _fail(EXIT_FAILED, f"{type(exc).__name__}: {exc}\n(full log: {run_dir / 'run.log'})")
    finally:
        log.removeHandler(handler)
        handler.close()


def _write_animation(run_dir: Path) -> None:
    """`render --animate`: the animation beside the report, in <run>/animation/."""
    from ..render.animation import ANIMATION_DIR, write_cage_animations
    from ..scene.load import load_scene

    try:
        paths = write_cage_animations(load_scene(run_dir / "scene.toml"), run_dir / "simulate", run_dir / ANIMATION_DIR)
    except (ValueError, OSError) as exc:
        _fail(EXIT_FAILED, f"animation: {exc}")
    err_console.print("animation: " + ", ".join(str(p) for p in paths), highlight=False, markup=False)


@app.command()
def bench(scene: SceneArg,
          quick: Annotated[bool, typer.Option("--quick", help="CI-sized variant (~1-2 min): short window, few tolerances, coarse FE meshes.")] = False,
          out: Annotated[Optional[Path], typer.Option("--out", help=_literal("Where the tables and plots go [default: runs/<scene name>/bench/]."))] = None,
          fe: Annotated[bool, typer.Option("--fe/--no-fe", help="Also the FE identification study (scenes with hinge.source = 'fe').")] = True,
          set_: SetOpt = None) -> None:
    """Error against run time: work-precision of the dynamic solver (and of the FE hinge identification)."""
    from ..studies.command import run_bench

    try:
        resolved = _load(scene, set_)
    except SceneError as exc:
        _fail(EXIT_SCENE, f"scene: {exc}")
    out = out or _run_dir(resolved, None) / "bench"
    _claim_study(out)
    identify_dir = None
    if resolved.hinge.source == "fe":
        _, run_dir, _ = _pipeline(scene, set_, None, ["identify"], set())
        identify_dir = run_dir / "identify"
    try:
        paths, table = run_bench(resolved, identify_dir, quick, out, fe,
                                 progress=lambda text: err_console.print(text, highlight=False))
    except (RuntimeError, ValueError) as exc:
        _fail(EXIT_FAILED, f"{type(exc).__name__}: {exc}")
    out_console.print(table, highlight=False, markup=False, soft_wrap=True)
    err_console.print("written: " + ", ".join(str(p) for p in paths), highlight=False, markup=False)


def _claim_study(out: Path) -> None:
    """Refuse (exit 2) an --out that is not new, empty or a study folder bearingsim wrote,
    before the study runs."""
    from ..studies import claim_study_directory

    try:
        claim_study_directory(out)
    except OutputRefused as exc:
        _fail(EXIT_SCENE, str(exc))


@app.command()
def stability(cases: Annotated[Optional[list[str]], typer.Argument(help=_literal("Case names [default: all]; see pipeline/scenes/stability/."))] = None,
              window: Annotated[float, typer.Option("--window", help=_literal("Simulated window per case [s]."))] = 0.010,
              wall_budget: Annotated[float, typer.Option("--wall-budget", help=_literal("Wall-clock budget per case [s]."))] = 180.0,
              out: Annotated[Path, typer.Option("--out", help="Where the table and plot go.")] = Path("runs/stability")) -> None:
    """Stability suite: stiff and extreme cases, each a pass or a clearly reported refusal."""
    from ..studies.stability import MIN_SAMPLES, MIN_WINDOW, case_names, markdown_table, run_suite, write_suite

    for option, value, least, example in (("--window", window, MIN_WINDOW, "0.01"),
                                          ("--wall-budget", wall_budget, 0.0, "180")):
        if not (math.isfinite(value) and value >= least and value > 0.0) or value > 1e30:
            floor = f" of at least {least:g} s ({MIN_SAMPLES} samples)" if least else ""
            _fail(EXIT_SCENE, f"{option}: is {value:g} s; give a positive finite time in seconds{floor}, e.g. "
                              f"{option} {example}")
    unknown = [c for c in cases or [] if c not in case_names()]
    if unknown:
        _fail(EXIT_SCENE, f"unknown stability case {unknown[0]!r}; cases: {', '.join(case_names())}")
    _claim_study(out)
    results = run_suite(cases or None, window, wall_budget,
                        progress=lambda text: err_console.print(text, highlight=False))
    paths = write_suite(results, out)
    out_console.print(markdown_table(results), highlight=False, markup=False, soft_wrap=True)
    err_console.print("written: " + ", ".join(str(p) for p in paths), highlight=False, markup=False)
    if any(r.status == "garbage" for r in results):
        _fail(EXIT_FAILED, "a case finished with an unphysical state (see the table): a defect to report")


@dataclass(frozen=True)
class SweepOptions:
    """The options of `bearingsim sweep`, one field an option, in the order of its help."""

    vary: Annotated[Optional[list[str]], typer.Option(
        "--vary", metavar="KEY=VALUES",
        help=_literal("Vary a scene key (repeatable): start:stop:count or a,b,c, e.g. --vary "
                      "load.moment=0:600:13. Replaces the scene's [sweep] points."))] = None
    mode: Annotated[Optional[str], typer.Option(
        "--mode", help="factorial (every combination, default) or list (i-th values together).")] = None
    set_: SetOpt = None
    name: Annotated[Optional[str], typer.Option("--name", help=_literal("Sweep name [default: <scene>-sweep]."))] = None
    out: Annotated[Optional[Path], typer.Option("--out", help=_literal("Sweep directory [default: runs/<sweep name>/]."))] = None
    store: Annotated[Optional[Path], typer.Option(
        "--store", help=_literal("Shared stage store [default: <sweep dir>/store]; share one between sweeps."))] = None
    workers: Annotated[int, typer.Option("--workers", min=1, help="Worker processes of the local cluster.")] = 2
    scheduler: Annotated[Optional[str], typer.Option(
        "--scheduler", metavar="ADDRESS", help="Use a running Dask scheduler (e.g. tcp://host:8786); "
                                               "its workers must see the sweep directory.")] = None
    retry_failed: Annotated[bool, typer.Option("--retry-failed", help="Rerun points that failed before.")] = False
    dry_run: Annotated[bool, typer.Option("--dry-run", help="Validate and list the points, with those an earlier run finished; run nothing.")] = False
    max_points: Annotated[int, typer.Option(
        "--max-points", min=1, help="Refuse sweeps of more points than this (a guard against a typo "
                                    "in a range).")] = 10_000
    figures: Annotated[Optional[bool], typer.Option(
        "--figures/--no-figures", help="Draw each point's PNG figures (default: the scene's sweep.figures, "
                                       "else yes); --no-figures saves their drawing time.")] = None


@app.command()
@flat_options
def sweep(scene: SceneArg, options: SweepOptions) -> None:
    """Parameter sweep on Dask: one pipeline run per point, a results table and a cage-stability map."""
    from ..sweep.console import class_counts, print_results
    from ..sweep.driver import (check_scheduler_address, gather, plan_sweep, replaced_sweep, sweep_directory_lock,
                                table_rows, unfinished)
    from ..sweep.table import read_table

    o = options
    try:
        if o.scheduler is not None:
            check_scheduler_address(o.scheduler)
    except SceneError as exc:  # a bad option, not a bad scene
        _fail(EXIT_SCENE, str(exc))
    try:
        plan = plan_sweep(scene, o.set_, o.vary, mode=o.mode, name=o.name, out=o.out, store=o.store,
                          max_points=o.max_points, figures=o.figures,
                          progress=lambda text: err_console.print(f"sweep: {text}", highlight=False))
    except SceneError as exc:
        _fail(EXIT_SCENE, f"scene: {explain(exc)}")
    replaced = replaced_sweep(plan)
    if o.dry_run:
        # what a run would do: the points an earlier run finished are kept, with their results
        kept, todo = unfinished(plan, o.retry_failed)
        print_results(table_rows(plan, kept), plan.varied, out_console)
        err_console.print(f"{len(plan.points)} points, {len(kept)} finished in an earlier run (kept), {len(todo)} "
                          f"to run; sweep directory {plan.sweep_dir}/", highlight=False, markup=False, soft_wrap=True)
        if replaced:
            err_console.print(f"warning: {replaced}", highlight=False, markup=False, soft_wrap=True)
        return
    with contextlib.ExitStack() as held:
        try:
            held.enter_context(sweep_directory_lock(plan))
        except OutputRefused as exc:
            _fail(EXIT_SCENE, str(exc))
        except RunDirectoryBusy as exc:
            _fail(EXIT_FAILED, str(exc))
        if replaced:
            err_console.print(styled(("warning:", "bold yellow"), f" {replaced}"), highlight=False, soft_wrap=True)
        err_console.print(f"sweep {plan.name}: {len(plan.points)} points on "
                          f"{o.scheduler or f'a local cluster of {o.workers} workers'}", highlight=False, soft_wrap=True)
        records = _run_sweep_points(plan, o)
        paths = gather(plan, records, warn=False)  # the table below prints the short-run warning
    rows = read_table(paths["table"])
    print_results(rows, plan.varied, out_console)
    err_console.print(f"classes: {class_counts(rows)}\nresults: {paths['table']}\nmap: {paths['map']}", highlight=False, markup=False)
    failed = [r for r in records if r is not None and r.get("status") == "failed" and not r.get("lost")]
    if failed:  # failed points are results (their error is in the table): exit 0, said plainly
        err_console.print(styled(("warning:", "bold yellow"), f" {len(failed)} of {len(records)} points failed "
                                 f"(column error of {paths['table']}); rerun with --retry-failed to run them again"),
                          highlight=False, soft_wrap=True)
    unfinished = [r for r in records if r is None or r.get("lost")]
    if unfinished:
        _fail(EXIT_FAILED, f"{len(unfinished)} points did not finish (worker lost); rerun the same command "
                           "to run only those")


def _run_sweep_points(plan, o: SweepOptions) -> list:
    """Run the points of `plan` that are not finished, on a Dask cluster (`--scheduler`, or a
    local one of `--workers`), or none when every point finished before; the records of all."""
    from ..sweep.console import SweepProgress
    from ..sweep.driver import dask_client, run_sweep, unfinished

    try:
        if not unfinished(plan, o.retry_failed)[1]:  # all points finished before: no cluster needed
            return run_sweep(plan, None, retry_failed=o.retry_failed)
        with dask_client(o.scheduler, o.workers) as client, SweepProgress(err_console) as bar:
            if getattr(client, "dashboard_link", None):
                err_console.print(f"Dask dashboard: {client.dashboard_link}", highlight=False)
            return run_sweep(plan, client, progress=bar.update, retry_failed=o.retry_failed)
    except KeyboardInterrupt as exc:
        how, code = interruption(exc)
        if not o.scheduler:  # the local cluster is closed: no worker writes the points any more
            from ..sweep.point_runner import remove_stale_temporaries

            for request in plan.requests:
                remove_stale_temporaries(Path(request.run_dir))
        _fail(code, f"interrupted ({how}): finished points are kept in {plan.sweep_dir / 'points'}/ (an "
                    "interrupted point keeps only its finished stages and is run again); run the same command "
                    "again to run only the others")
    except OutputRefused as exc:
        _fail(EXIT_SCENE, str(exc))
    except OSError as exc:
        _fail(EXIT_FAILED, f"cannot reach the Dask scheduler {o.scheduler!r}: {exc}" if o.scheduler else str(exc))
    except RuntimeError as exc:  # e.g. the optional dask extra is not installed
        _fail(EXIT_FAILED, str(exc))


def main() -> None:
    """The console script and `python -m bearingsim`: SIGTERM becomes a logged interruption
    (exit 143, the running stage's temporary folder removed) before the commands run."""
    stop_on_sigterm()
    command = typer.main.get_command(app)
    _flags_without_metavar(command)
    command(prog_name="bearingsim")


def _flags_without_metavar(command) -> None:
    """Show boolean flags as flags (`--force`), not as options taking a value (`--force <bool>`):
    the help of every command, its --help included."""
    import types

    for param in getattr(command, "params", ()):
        if getattr(param, "is_flag", False):
            param.metavar = ""
    plain_help = command.get_help_option

    def help_option(self, ctx):
        option = plain_help(ctx)
        if option is not None:
            option.metavar = ""
        return option

    command.get_help_option = types.MethodType(help_option, command)
    for sub in getattr(command, "commands", {}).values():
        _flags_without_metavar(sub)
