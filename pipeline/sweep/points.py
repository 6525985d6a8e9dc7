"""The points of a sweep: expansion of the axes, stable ids, per-point scene tables.

A point is a set of scene overrides. Its id hashes only those overrides, so extending a
sweep keeps the ids (and finished results) of the points it already had; its scene hash
covers the whole resolved scene, so a changed base scene reruns every point.
"""

from __future__ import annotations

import hashlib
import itertools
import json
from dataclasses import dataclass
from typing import Any

import tomli_w

from ..staging.artefacts import canonical, input_key
from ..staging.provenance import package_version
from ..scene.load import apply_overrides, resolve
from ..scene.schema import SceneError
from ..scene.sweep_section import SweepSection


@dataclass(frozen=True)
class SweepPoint:
    overrides: tuple[tuple[str, Any], ...]  # (dotted scene key, value), in axis order

    @property
    def id(self) -> str:
        blob = json.dumps(sorted(self.overrides), sort_keys=True, separators=(",", ":"))
        return hashlib.sha256(blob.encode("utf-8")).hexdigest()[:12]

    @property
    def label(self) -> str:
        return ", ".join(f"{k}={_literal(v)}" for k, v in self.overrides)

    def set_args(self) -> list[str]:
        """The overrides as `--set` strings (one parser for both)."""
        return [f"{k}={_literal(v)}" for k, v in self.overrides]


def _literal(value: Any) -> str:
    """A value as the TOML literal `parse_override` reads back to the same value."""
    return tomli_w.dumps({"v": value})[len("v = "):].strip()


def expand(section: SweepSection) -> list[SweepPoint]:
    """Every point of the sweep, in order, without duplicates."""
    if section.points:
        raw = [tuple(p) for p in section.points]
    elif not section.vary:
        raise SceneError("sweep", "nothing to vary: give --vary KEY=VALUES (e.g. load.moment=0:600:13) "
                                  "or a [sweep.vary] table in the scene")
    elif section.mode == "factorial":
        keys = [a.key for a in section.vary]
        raw = [tuple(zip(keys, combo)) for combo in itertools.product(*(a.values for a in section.vary))]
    else:
        lengths = {a.key: len(a.values) for a in section.vary}
        if len(set(lengths.values())) != 1:
            raise SceneError("sweep.mode", f"'list' pairs the i-th values of every axis, so they need the "
                                           f"same number of values; got {lengths}. Use mode 'factorial' "
                                           f"for every combination")
        raw = [tuple((a.key, a.values[i]) for a in section.vary) for i in range(len(section.vary[0].values))]
    points, seen = [], set()
    for overrides in raw:
        if len({k for k, _ in overrides}) != len(overrides):
            raise SceneError("sweep", f"a point sets the same key twice: {overrides}")
        # one point per set of values: 100, 100.0 and 1e2 (or -0.0, 0.0 and 0) are one value, as in
        # the stages' keys; the point keeps the first spelling, and its id
        same = json.dumps(sorted((k, canonical(v)) for k, v in overrides), sort_keys=True)
        if same not in seen:
            seen.add(same)
            points.append(SweepPoint(overrides))
    return points


def point_table(base: dict, point: SweepPoint) -> dict:
    """The point's scene table, validated now so a bad value stops the sweep before any
    point is computed (the error names the point)."""
    table = apply_overrides(base, point.set_args())
    try:
        resolve(table, origin=f"sweep point {point.label}")
    except SceneError as exc:
        raise SceneError("", f"{exc} (in sweep point {point.label})") from None
    return table


def scene_hash(table: dict, target: str) -> str:
    """Hash of everything that decides a point's result (not its name or description)."""
    physics = {k: v for k, v in table.items() if k not in ("name", "description", "sweep")}
    return input_key(f"sweep-point:{target}", physics, package_version())
