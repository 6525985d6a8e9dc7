"""What a sweep varies: `--vary` strings and the scene's `[sweep]` table.

Syntax of one axis (command line ``--vary KEY=VALUES``, or ``KEY = VALUES`` in
``[sweep.vary]``):

- ``load.moment=0:600:13`` — 13 evenly spaced values from 0 to 600, both ends included;
- ``speed.inner_rpm=2000,3060,6000`` — the listed values (TOML literals; a bare word is a
  string, e.g. ``physics.cage_race=hybrid,dry``);
- in TOML, an array (``"load.moment" = [0, 300, 600]``) or the range string.

``mode = "factorial"`` (default) runs every combination of the axes; ``mode = "list"``
pairs the i-th values of all axes (they must have the same length), or takes the explicit
``points = [{ "load.moment" = 100, "speed.inner_rpm" = 3000 }, ...]``.
"""

from __future__ import annotations

import dataclasses
import math
import tomllib
from dataclasses import dataclass, field
from typing import Any

from .schema import SceneError, build
from .cage_classes import CageClassThresholds

NOT_VARIABLE = ("name", "description", "sweep")
# A sweep larger than this is refused unless asked for (`--max-points`): 10 000 points of the
# reference bearing take days on one worker. One axis may never list more
# values than MAX_AXIS_VALUES (they are held in memory before the limit can be checked).
MAX_POINTS = 10_000
MAX_AXIS_VALUES = 10_000_000


@dataclass(frozen=True)
class Axis:
    """One varied scene key and its values, in sweep order."""

    key: str  # dotted scene key, e.g. "load.moment"
    values: tuple[Any, ...]


@dataclass(frozen=True)
class SweepSection:
    """`[sweep]`: how to vary a scene. The physics of each point is the scene's own."""

    name: str | None = field(default=None, metadata={"doc": "sweep directory name [default: <scene>-sweep]"})
    mode: str = field(default="factorial", metadata={"choices": ("factorial", "list"), "doc": "factorial: every combination of the varied values; list: the i-th values together, or explicit points"})
    target: str = field(default="simulate", metadata={
        "choices": ("simulate",), "doc": "stage each point runs to (its summary.json feeds the table)"})
    figures: bool = field(default=True, metadata={
        "doc": "draw each point's figures (PNG); false skips them (scene key output.figures = false "
               "in every point), which saves their drawing time; results and table are the same"})
    map_x: str | None = field(default=None, metadata={"doc": "scene key on the map's x axis [default: load.moment]"})
    map_y: str | None = field(default=None, metadata={"doc": "scene key on the map's y axis [default: speed.inner_rpm]"})
    thresholds: CageClassThresholds = field(default_factory=CageClassThresholds)
    vary: tuple[Axis, ...] = ()
    points: tuple[tuple[tuple[str, Any], ...], ...] = ()  # explicit listed points (mode = "list")


def _toml_value(text: str) -> Any:
    try:
        return tomllib.loads(f"v = {text}")["v"]
    except tomllib.TOMLDecodeError:
        return text.strip()


def parse_range(key: str, text: str) -> tuple[float, ...]:
    """`start:stop:count` -> `count` evenly spaced floats, both ends included."""
    parts = text.split(":")
    try:
        start, stop, count = float(parts[0]), float(parts[1]), _toml_value(parts[2])
    except (IndexError, ValueError):
        raise SceneError(key, f"bad range {text!r}: write start:stop:count, e.g. 0:600:13") from None
    if len(parts) != 3 or isinstance(count, bool) or not isinstance(count, int) or count < 1:
        raise SceneError(key, f"bad range {text!r}: write start:stop:count with an integer count >= 1")
    if count > MAX_AXIS_VALUES:
        raise SceneError(key, f"bad range {text!r}: {count} values; one axis may have at most "
                              f"{MAX_AXIS_VALUES} (and a whole sweep {MAX_POINTS} points unless --max-points says more)")
    if not (math.isfinite(start) and math.isfinite(stop)):
        raise SceneError(key, f"bad range {text!r}: start and stop must be finite numbers")
    if count == 1:
        return (start,)
    step = (stop - start) / (count - 1)
    # 12 significant digits: 0:0.003:4 gives 0.001, not 0.0010000000000000002
    return tuple(float(f"{start + i * step:.12g}") for i in range(count))


def _check_key(key: str, where: str) -> str:
    parts = key.split(".")
    if not key or any(not p for p in parts) or parts[0] in NOT_VARIABLE:
        raise SceneError(where, f"{key!r} is not a scene key a sweep can vary; give a dotted key of a "
                                f"physics or solver table, e.g. load.moment or speed.inner_rpm")
    return key


def parse_values(key: str, value: Any, where: str) -> tuple[Any, ...]:
    """An axis' values from a TOML value (array or range string) or command-line text."""
    if isinstance(value, list):
        values = tuple(value)
    elif isinstance(value, str) and ":" in value:
        values = parse_range(where, value)
    elif isinstance(value, str):
        values = tuple(_toml_value(v) for v in value.split(","))
    else:
        values = (value,)
    if not values or any(v == "" for v in values):
        raise SceneError(where, f"no values for {key!r}: give a list (a,b,c) or a range start:stop:count")
    return values


def parse_vary(text: str) -> Axis:
    """`--vary load.moment=0:600:13` -> Axis("load.moment", (0.0, 50.0, ..., 600.0))."""
    if "=" not in text:
        raise SceneError("--vary", f"expected KEY=VALUES (e.g. load.moment=0:600:13), got {text!r}")
    key, values = (s.strip() for s in text.split("=", 1))
    _check_key(key, f"--vary {text}")
    return Axis(key, parse_values(key, values, f"--vary {key}"))


def _parse_points(points: Any) -> tuple[tuple[tuple[str, Any], ...], ...]:
    if not isinstance(points, list) or not all(isinstance(p, dict) and p for p in points):
        raise SceneError("sweep.points", 'expected a list of tables, e.g. [{ "load.moment" = 100 }]')
    return tuple(tuple((_check_key(k, f"sweep.points[{i}]"), v) for k, v in p.items())
                 for i, p in enumerate(points))


def build_sweep_section(table: Any) -> SweepSection:
    """Validate a scene's `[sweep]` table; raises SceneError naming the key."""
    if not isinstance(table, dict):
        raise SceneError("sweep", f"expected a table, got {table!r}")
    scalars = {k: v for k, v in table.items() if k not in ("vary", "points")}
    section = build(SweepSection, scalars, "sweep")
    vary = table.get("vary", {})
    if not isinstance(vary, dict):
        raise SceneError("sweep.vary", 'expected a table of KEY = VALUES, e.g. "load.moment" = "0:600:13"')
    axes = tuple(Axis(_check_key(k, f"sweep.vary.{k}"), parse_values(k, v, f"sweep.vary.{k}"))
                 for k, v in vary.items())
    points = _parse_points(table["points"]) if "points" in table else ()
    if points and (axes or section.mode != "list"):
        raise SceneError("sweep.points", 'explicit points need mode = "list" and no [sweep.vary]')
    return dataclasses.replace(section, vary=axes, points=points)


def with_command_line(section: SweepSection, vary: list[str], mode: str | None,
                      name: str | None, figures: bool | None = None) -> SweepSection:
    """Command-line `--vary` replaces the scene's whole point definition (vary and points);
    thresholds and map axes stay the scene's. `figures` (`--figures/--no-figures`), when
    given, replaces the scene's `figures`."""
    changes: dict[str, Any] = {}
    if figures is not None:
        changes["figures"] = bool(figures)
    if vary:
        changes.update(vary=tuple(parse_vary(v) for v in vary), points=())
    if mode is not None:
        if mode not in ("factorial", "list"):
            raise SceneError("--mode", f"{mode!r} is not allowed: choose 'factorial' or 'list'")
        changes["mode"] = mode
    if name is not None:
        changes["name"] = name
    return dataclasses.replace(section, **changes)


def point_count(section: SweepSection) -> int:
    """How many points `section` defines (before duplicates are removed)."""
    if section.points:
        return len(section.points)
    if not section.vary:
        return 0
    if section.mode == "factorial":
        return math.prod(len(a.values) for a in section.vary)
    return max(len(a.values) for a in section.vary)


def check_size(section: SweepSection, max_points: int = MAX_POINTS) -> None:
    """Refuse a sweep of more than `max_points` points before any point is built."""
    n = point_count(section)
    if n > max_points:
        axes = " x ".join(f"{len(a.values)} of {a.key}" for a in section.vary) or f"{n} listed points"
        raise SceneError("", f"the sweep has {n} points ({axes}), more than the limit of {max_points} "
                             f"(at ~40 s per point of the reference bearing, {n * 40 / 86400:.3g} days on one "
                             f"worker); give fewer values, or raise the limit with --max-points {n}")
