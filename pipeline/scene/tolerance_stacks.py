"""Which tolerance stacks are bearings: each stack through the scene's own validation.

A stack of `[tolerances]` deviations is the scene with some of its values moved (dimensions as
drawn, part temperatures, loads). It is a bearing the model covers only if the scene with those
values passes the same checks as any scene: each key's range and the model's sizes
(`schema.check_number`), the ring and cage geometry (`BearingGeometry`, `CageGeometry` and
`check_fits`, as drawn and grown to the part temperatures) and the geometry findings of
`validity` (clearance beyond the groove's limit, a land off its ring, a cage that does not fit).
Those checks run here on the parts the stack changes only (tens of microseconds a stack, where
loading the whole scene takes milliseconds); tests/test_tolerances.py holds them to loading the
stack's scene in full.

`stack_values` turns a stack into scene keys and values (what `--set` would take);
`stack_problem` names the first check a stack fails; `range_problem` refuses, before anything is
sampled, a tolerance whose range reaches impossible values (docs/reliability.md).
"""

from __future__ import annotations

import dataclasses
import functools
import math
import types
from typing import Any

from ...dynamics import thermal as th
from .schema import SceneError, check_number

# the part temperature a temperature deviation moves, and its [thermal] key
PART_TEMPERATURES = {f"{part}_temperature": part for part in ("inner_ring", "outer_ring", "ball", "cage")}
# how far a normal deviation is taken to reach: a manufacturing tolerance is stated as +-3 sd
NORMAL_REACH = 3.0


def is_form2(scene) -> bool:
    table = scene.raw.get("bearing", {})
    return isinstance(table, dict) and "pitch_diameter" in table


def stack_values(scene, stack: dict[str, float]) -> dict[str, float]:
    """The scene keys a stack sets and their values: dimensions as drawn [m], part temperatures
    [degC] and loads [N, N.m]."""
    b, c, t = scene.nominal.bearing, scene.nominal.cage, scene.temperatures
    out: dict[str, float] = {}
    if "cage_outside_diameter" in stack or "cage_bore_diameter" in stack:
        od = c.outside_diameter + stack.get("cage_outside_diameter", 0.0)
        bore = c.bore_diameter + stack.get("cage_bore_diameter", 0.0)
        out["cage.mean_diameter"], out["cage.radial_thickness"] = 0.5 * (od + bore), 0.5 * (od - bore)
    simple = {"pocket_diameter": ("cage.pocket_diameter", c.pocket_diameter if c is not None else math.nan),
              "outer_land_diameter": ("bearing.outer_shoulder_diameter", b.outer_shoulder_diameter),
              "inner_land_diameter": ("bearing.inner_shoulder_diameter", b.inner_shoulder_diameter),
              "ball_diameter": ("bearing.ball_diameter", b.ball_diameter),
              "diametral_clearance": ("bearing.diametral_clearance" if is_form2(scene)
                                      else "bearing.outer_groove_center_diameter",
                                      b.diametral_clearance if is_form2(scene) else b.outer_groove_center_diameter),
              "moment": ("load.moment", scene.load.moment), "axial": ("load.axial", scene.load.axial)}
    for name, (key, nominal) in simple.items():
        if name in stack:
            out[key] = (math.nan if nominal is None else nominal) + stack[name]
    if "pocket_circle_eccentricity" in stack:  # floored at 0: a run-out has no sign
        out["cage.pocket_circle_eccentricity"] = max(0.0, c.pocket_circle_eccentricity + stack["pocket_circle_eccentricity"])
    for name, part in PART_TEMPERATURES.items():
        if name in stack:
            out[f"thermal.{part}_degC"] = getattr(t, part) + stack[name]
    return out


def _field(cls: type, name: str) -> dataclasses.Field:
    return next(f for f in dataclasses.fields(cls) if f.name == name)


def _key_meta(scene, key: str) -> dict:
    """The metadata (unit, range) of a scene key a stack sets."""
    return _meta(is_form2(scene), key)


@functools.lru_cache(maxsize=None)
def _meta(form2: bool, key: str) -> dict:
    from ...dynamics.geometry import BearingGeometry, CageGeometry

    from .sections import CatalogueBearing, Load, Thermal

    section, name = key.split(".", 1)
    cls = {"bearing": CatalogueBearing if form2 else BearingGeometry, "cage": CageGeometry,
           "load": Load, "thermal": Thermal}[section]
    return dict(_field(cls, name).metadata)


def stack_problem(scene, values: dict[str, float]) -> tuple[str, str] | None:
    """(key, message) of the first check of the scene the stack's `values` fail; None when the
    stack is a bearing the model covers."""
    from . import validity

    for key, value in values.items():
        try:
            check_number(key, value, _key_meta(scene, key))
        except SceneError as exc:
            return key, str(exc)
    try:
        bearing, cage = _drawn_parts(scene, values)
        if cage is not None:
            cage.check_fits(bearing)
    except ValueError as exc:
        return _first_key(values, "bearing"), str(exc)
    drawn = types.SimpleNamespace(bearing=bearing, cage=cage, raw=scene.raw)  # what the geometry checks read
    errors = [f for f in validity.geometry_findings(drawn) if f.level == "error"]
    if errors:
        return errors[0].key, errors[0].text
    temperatures = dataclasses.replace(scene.temperatures, **{
        part: values[f"thermal.{part}_degC"] for part in PART_TEMPERATURES.values() if f"thermal.{part}_degC" in values})
    try:
        grown = th.operating_bearing(bearing, temperatures, scene.expansion)
        if cage is not None:
            th.operating_cage(cage, temperatures, scene.expansion).check_fits(grown)
    except ValueError as exc:
        return "thermal", f"at the operating temperatures: {exc}"
    return None


def _first_key(values: dict[str, float], default: str) -> str:
    return next((k for k in values if k.startswith(("bearing.", "cage."))), default)


def _drawn_parts(scene, values: dict[str, float]):
    """The bearing and cage as drawn with the stack's values (ValueError from their own checks)."""
    from ...dynamics.geometry import BearingGeometry

    from .sections import CatalogueBearing
    from .schema import build

    def moved(section: str) -> dict[str, float]:
        return {k.split(".", 1)[1]: v for k, v in values.items() if k.startswith(section + ".")}

    b, c = scene.nominal.bearing, scene.nominal.cage
    if moved("bearing"):
        if is_form2(scene):
            catalogue = build(CatalogueBearing, scene.raw["bearing"], "bearing")
            b = BearingGeometry.from_catalogue(**(dataclasses.asdict(catalogue) | moved("bearing")))
        else:
            b = dataclasses.replace(b, **moved("bearing"))
    if c is not None and moved("cage"):
        c = dataclasses.replace(c, **moved("cage"))
    return b, c


def range_problem(scene, deviation, unit: str) -> SceneError | None:
    """A SceneError when the range of one tolerance (a `tolerance_section.Deviation`), the other
    quantities at their nominal values, reaches values the scene refuses: a uniform range at
    either end, a normal one at +-NORMAL_REACH sd. It names the end, what fails there and the
    allowed end (where the stacks stop being bearings, found by bisection); `unit` is the
    quantity's."""
    name = deviation.name
    ends = ([("lower", deviation.lower), ("upper", deviation.upper)] if deviation.kind == "uniform"
            else [("sd", -NORMAL_REACH * deviation.sd), ("sd", NORMAL_REACH * deviation.sd)])
    for label, end in ends:
        if stack_problem(scene, stack_values(scene, {name: end})) is None:
            continue
        edge, (key, message) = _edge(scene, name, end)
        if label == "sd":
            at = f"sd = {deviation.sd:g} {unit} reaches {end:+g} {unit} at {NORMAL_REACH:g} sd"
            allowed = f"sd < {abs(edge) / NORMAL_REACH:.4g}"
        else:
            at = f"{label} = {end:g} {unit}"
            allowed = f"{label} {'>' if end < 0 else '<'} {edge:.4g}"
        return SceneError(f"tolerances.{name}", f"{at} takes the stacks past what the scene allows: beyond a "
                                                f"deviation of {edge:.4g} {unit}, {message}; allowed {allowed} [{unit}]")
    return None


def _edge(scene, name: str, end: float, steps: int = 60) -> tuple[float, tuple[str, str]]:
    """The deviation between 0 (the scene itself, valid) and `end` (invalid) where the stack
    stops passing the scene's checks, and the check it fails just beyond."""
    good, bad = 0.0, end
    problem = stack_problem(scene, stack_values(scene, {name: end}))
    for _ in range(steps):
        mid = 0.5 * (good + bad)
        found = stack_problem(scene, stack_values(scene, {name: mid}))
        if found is None:
            good = mid
        else:
            bad, problem = mid, found
    # the failure shown at a round deviation just past the edge (-200.1, not -200.00000000000003)
    shown = float(f"{bad:.4g}")
    if stack_problem(scene, stack_values(scene, {name: shown})) is None:
        shown += math.copysign(10.0 ** (math.floor(math.log10(abs(shown))) - 3), end) if shown else end
    return good, stack_problem(scene, stack_values(scene, {name: shown})) or problem


def invalid_stacks(scene, deviations: dict[str, Any], n: int) -> tuple[list[bool], dict[str, int]]:
    """For n sampled stacks ({quantity: deviations (n,)}): whether each fails the scene's checks,
    and how many fail on each key."""
    bad, reasons = [], {}
    names = list(deviations)
    for i in range(n):
        problem = stack_problem(scene, stack_values(scene, {k: float(deviations[k][i]) for k in names}))
        bad.append(problem is not None)
        if problem is not None:
            reasons[problem[0]] = reasons.get(problem[0], 0) + 1
    return bad, reasons
