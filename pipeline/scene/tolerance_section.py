"""The `[tolerances]` table of a scene: what may vary, how, and how many stacks (docs/scenes.md).

Validated when the scene loads; the analysis itself is pipeline.quasistatic.tolerances (docs/model.md §10.2).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from .schema import SceneError, check_number, shown_number

# name -> (unit, description); a deviation is added to the scene's value
QUANTITIES: dict[str, tuple[str, str]] = {
    "pocket_diameter": ("m", "cage pocket diameter d_p"),
    "cage_outside_diameter": ("m", "cage outside diameter (mean_diameter + radial_thickness)"),
    "cage_bore_diameter": ("m", "cage bore (mean_diameter - radial_thickness)"),
    "outer_land_diameter": ("m", "outer-ring land diameter (bearing.outer_shoulder_diameter)"),
    "inner_land_diameter": ("m", "inner-ring land diameter (bearing.inner_shoulder_diameter)"),
    "ball_diameter": ("m", "ball diameter D (pocket clearance and internal clearance)"),
    "diametral_clearance": ("m", "diametral (internal) clearance P_d, through the outer groove's curvature-centre diameter"),
    "pocket_circle_eccentricity": ("m", "cage run-out e_r (sampled value = scene value + deviation, floored at 0)"),
    "inner_ring_temperature": ("K", "inner-ring temperature"),
    "outer_ring_temperature": ("K", "outer-ring temperature"),
    "ball_temperature": ("K", "ball temperature"),
    "cage_temperature": ("K", "cage temperature"),
    "moment": ("N.m", "moment about +y"),
    "axial": ("N", "thrust along +z"),
}
MAX_SAMPLES = 1_000_000


@dataclass(frozen=True)
class Deviation:
    """One varied quantity: uniform on [lower, upper] or normal with standard deviation sd."""

    name: str
    kind: str  # "uniform" | "normal"
    lower: float = 0.0
    upper: float = 0.0
    sd: float = 0.0

    def sample(self, rng: np.random.Generator, n: int) -> np.ndarray:
        """n deviations, Latin hypercube: one in each of n equally likely strata, in random order
        (scipy.stats.qmc, seeded by `rng`)."""
        from scipy.stats import norm, qmc

        try:
            lhs = qmc.LatinHypercube(d=1, rng=rng)
        except TypeError:  # scipy < 1.15 names it seed
            lhs = qmc.LatinHypercube(d=1, seed=rng)
        u = np.clip(lhs.random(n)[:, 0], 1e-12, 1.0 - 1e-12)  # inside (0, 1): a finite normal quantile
        if self.kind == "uniform":
            return self.lower + (self.upper - self.lower) * u
        return self.sd * norm.ppf(u)

    def describe(self) -> str:
        unit = QUANTITIES[self.name][0]
        if self.kind == "uniform":
            return f"uniform {self.lower:+.4g} … {self.upper:+.4g} {unit}"
        return f"normal, sd {self.sd:.4g} {unit}"


@dataclass(frozen=True)
class ToleranceSpec:
    samples: int
    seed: int
    deviations: tuple[Deviation, ...]


def _number(key: str, value: Any, unit: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise SceneError(key, f"expected a finite number [{unit}], got {shown_number(value)}")
    return check_number(key, value, {"unit": unit})  # the sizes the model computes with


def build_tolerance_spec(table: Any, scene=None) -> ToleranceSpec:
    """Validate `[tolerances]` (module docstring); errors name the key, value, range and unit."""
    if not isinstance(table, dict):
        raise SceneError("tolerances", f"expected a table, got {table!r}")
    samples = table.get("samples", 10_000)
    if isinstance(samples, bool) or not isinstance(samples, int) or not 100 <= samples <= MAX_SAMPLES:
        raise SceneError("tolerances.samples", f"{shown_number(samples)} is out of range: allowed an integer from 100 to "
                                               f"{MAX_SAMPLES} [-]")
    seed = table.get("seed", 0)
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise SceneError("tolerances.seed", f"{shown_number(seed)}: expected a whole number >= 0 [-]")
    out = []
    for name, spec in table.items():
        if name in ("samples", "seed"):
            continue
        key = f"tolerances.{name}"
        if name not in QUANTITIES:
            raise SceneError(key, f"unknown quantity; allowed: samples, seed, {', '.join(QUANTITIES)}")
        unit = QUANTITIES[name][0]
        if not isinstance(spec, dict) or not spec:
            raise SceneError(key, f"expected a table {{ lower = …, upper = … }} (uniform) or {{ sd = … }} (normal) "
                                  f"of deviations from the scene's value [{unit}], got {spec!r}")
        keys = set(spec)
        if keys == {"lower", "upper"}:
            lo, hi = _number(f"{key}.lower", spec["lower"], unit), _number(f"{key}.upper", spec["upper"], unit)
            if not lo < hi:
                raise SceneError(key, f"lower = {lo:g} must be smaller than upper = {hi:g} [{unit}]")
            out.append(Deviation(name, "uniform", lower=lo, upper=hi))
        elif keys == {"sd"}:
            sd = _number(f"{key}.sd", spec["sd"], unit)
            if not sd > 0.0:
                raise SceneError(f"{key}.sd", f"{sd!r} is out of range: allowed > 0 [{unit}]")
            out.append(Deviation(name, "normal", sd=sd))
        else:
            raise SceneError(key, f"keys {sorted(keys)}: give lower and upper (uniform) or sd alone (normal) [{unit}]")
    if not out:
        raise SceneError("tolerances", f"no quantity to vary; give at least one of {', '.join(QUANTITIES)}")
    if scene is not None and scene.cage is None:
        raise SceneError("tolerances", "the crush probability needs a [cage]")
    if scene is not None:  # a range that reaches impossible parts: refused before any stack is drawn
        from .tolerance_stacks import range_problem

        for deviation in out:
            problem = range_problem(scene, deviation, QUANTITIES[deviation.name][0])
            if problem is not None:
                raise problem
    return ToleranceSpec(samples=samples, seed=seed, deviations=tuple(out))
