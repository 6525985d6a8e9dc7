"""Sweep progress on stderr: points done / running / failed and an ETA (rich)."""

from __future__ import annotations

from collections import Counter

from .driver import SweepStatus


def format_duration(seconds: float | None) -> str:
    if seconds is None:
        return "--"
    seconds = int(round(seconds))
    h, rest = divmod(seconds, 3600)
    m, s = divmod(rest, 60)
    return f"{h}:{m:02d}:{s:02d}" if h else f"{m}:{s:02d}"


def status_line(s: SweepStatus) -> str:
    resumed = f" ({s.resumed} from an earlier run)" if s.resumed else ""
    lost = ""
    if s.lost_workers:
        lost = (f", {s.lost_workers} worker{'s' if s.lost_workers > 1 else ''} lost"
                f" ({s.retried} point{'s' if s.retried != 1 else ''} retried)")
    return (f"{s.done}/{s.total} done{resumed}, {s.running} running, {s.failed} failed{lost}, "
            f"elapsed {format_duration(s.elapsed_s)}, ETA {format_duration(s.eta_s)}")


class SweepProgress:
    """A progress bar (or plain lines when stderr is not a terminal)."""

    def __init__(self, console, quiet: bool = False):
        self.console, self.quiet = console, quiet
        self._counts = None

    def __enter__(self):
        if not self.quiet and self.console.is_terminal:
            from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn

            self.progress = Progress(TextColumn("sweep"), BarColumn(), MofNCompleteColumn(),
                                     TextColumn("{task.description}"), console=self.console, transient=True)
            self.progress.__enter__()
            self.task = None
        return self

    def update(self, s: SweepStatus) -> None:
        if self.quiet:
            return
        line = status_line(s)
        if not self.console.is_terminal:  # logs and CI: one line per change of counts
            counts = (s.done, s.failed, s.running, s.lost_workers, s.retried)
            if counts != self._counts:
                self._counts = counts
                self.console.print(f"sweep: {line}" + (f" | last: {s.last}" if s.last else ""),
                                   highlight=False, soft_wrap=True)
            return
        if self.task is None:
            self.task = self.progress.add_task(line, total=s.total)
        self.progress.update(self.task, completed=s.done + s.failed, description=line)

    def __exit__(self, *exc):
        if not self.quiet and self.console.is_terminal:
            self.progress.__exit__(*exc)
        return False


def class_counts(rows: list[dict]) -> str:
    counts = Counter(r["cage_class"] for r in rows)
    return ", ".join(f"{n} {c}" for c, n in counts.most_common())


def print_results(rows: list[dict], varied: list[str], console) -> None:
    """One line per point: its values, status, class and metal-contact fraction."""
    from rich.table import Table

    from ..console import styled
    from .table import short_run_warning

    errors = any(r.get("error") for r in rows)
    table = Table("point", *varied, "status", "cage class", "metal contact", *(["error"] if errors else []), box=None)
    for r in rows:
        metal = r.get("cage_metal_contact_fraction")
        short = r.get("too_short_to_settle") in (True, "True")
        table.add_row(r["point_id"], *(str(r.get(k)) for k in varied), r["status"],
                      r["cage_class"] + (" (too short to settle)" if short else ""),
                      "" if metal is None else f"{metal:.3f}", *([(r.get("error") or "")[:60]] if errors else []))
    console.print(table)
    warning = short_run_warning(rows)
    if warning:
        console.print(styled(("warning:", "bold yellow"), f" {warning}"), highlight=False, soft_wrap=True)
