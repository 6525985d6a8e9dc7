"""Typer commands that take a settings object (pipeline/cli/options.py): every field of the
dataclass is an option of its own, with its name, default and help, and the command receives
the dataclass built from them."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Annotated, Optional

import typer
from typer.main import get_command
from typer.testing import CliRunner

from bearingsim.pipeline.cli.commands import app
from bearingsim.pipeline.cli.options import flat_options

runner = CliRunner()


@dataclass(frozen=True)
class Knobs:
    count: Annotated[int, typer.Option("--count", min=1, help="How many.")] = 3
    label: Annotated[Optional[str], typer.Option("--label", help="A label.")] = None
    loud: Annotated[bool, typer.Option("--loud/--quiet", help="Say it loudly.")] = False


def _toy_app():
    seen = []
    toy = typer.Typer()

    @toy.command()
    @flat_options
    def go(target: Annotated[str, typer.Argument(help="What to go to.")], knobs: Knobs) -> None:
        """Go somewhere."""
        seen.append((target, knobs))

    @toy.command()
    def other() -> None:  # a second command, so that `go` keeps its name on the command line
        pass

    return toy, seen


def test_the_fields_arrive_as_the_dataclass():
    toy, seen = _toy_app()
    assert runner.invoke(toy, ["go", "there"]).exit_code == 0
    assert runner.invoke(toy, ["go", "home", "--count", "5", "--label", "x", "--loud"]).exit_code == 0
    assert seen == [("there", Knobs()), ("home", Knobs(count=5, label="x", loud=True))]


def test_the_fields_are_options_with_their_checks_and_help():
    toy, seen = _toy_app()
    result = runner.invoke(toy, ["go", "there", "--count", "0"])
    assert result.exit_code == 2 and not seen  # min=1 of the field's typer.Option
    result = runner.invoke(toy, ["go", "--help"], env={"COLUMNS": "200"})
    assert result.exit_code == 0
    for text in ("--count", "How many.", "--label", "--loud", "--quiet", "Go somewhere."):
        assert text in result.output


def test_sweep_keeps_its_options():
    # the options, defaults and order of `bearingsim sweep` as they were when the command took one
    # parameter per option (its `--help` before the change, written out here)
    expected = [
        ("scene", [], None), ("vary", ["--vary"], None), ("mode", ["--mode"], None), ("set_", ["--set"], None),
        ("name", ["--name"], None), ("out", ["--out"], None), ("store", ["--store"], None),
        ("workers", ["--workers"], 2), ("scheduler", ["--scheduler"], None),
        ("retry_failed", ["--retry-failed"], False), ("dry_run", ["--dry-run"], False),
        ("max_points", ["--max-points"], 10_000), ("figures", ["--figures"], None),
    ]
    params = get_command(app).commands["sweep"].params
    assert [(p.name, [o for o in p.opts if o.startswith("--")], p.default) for p in params] == expected
    assert params[-1].secondary_opts == ["--no-figures"]
