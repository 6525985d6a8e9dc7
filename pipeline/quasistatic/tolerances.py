"""Crush probability over manufacturing tolerances and operating conditions (docs/model.md §10.2).

The crush screen (docs/model.md §10.1) needs only the balls' excursion, which depends on the
loads, and the clearances, which depend on the dimensions and temperatures of the parts. So a
stack of tolerances costs a few array operations once the excursion is known:

- the excursion (s1, s_pp) comes from the quasi-static solution of the scene at its operating
  geometry; when the loads or the internal clearance vary, from solutions on a grid over their
  sampled ranges, interpolated linearly;
- each stack's clearances follow from its dimensions and temperatures by M.120–M.122;
- the margin and regime from M.116 and M.123 (`crush_screen.crush_margin`).

Ring and ball temperatures move the load distribution through the operating diametral
clearance (a 10 K difference between the rings changes it by ~17 µm of 118 µm, and the
excursion by several per cent), so the grid spans it; the other effects of the rings'
dimensions (pitch diameter, conformity) are left at the nominal operating stack, and the test
`test_tolerances.py::test_surrogate_against_full_screen` bounds the difference. What drives the margin is ranked by the squared standardised regression
coefficient of each input (its share of the margin's variance for a near-linear response),
with the Spearman rank correlation beside it and the R^2 of the linear fit, which says how far
the shares can be trusted (Sobol indices were weighed and not taken: docs/crush-probability.md).

Each quantity is sampled by a Latin hypercube of its own seeded stream (scipy.stats.qmc): every
one of n equally likely strata holds one stack, which spreads the stacks more evenly than
independent draws, keeps the binomial standard error an upper bound, works for any n, and
leaves the other quantities' samples as they were when one is added. Every stack goes through
the scene's own validation first (pipeline.scene.tolerance_stacks): one that is no bearing the
model covers is counted by the key it fails and left out of the probabilities, never screened.

`[tolerances]` in a scene: `samples`, `seed`, and one table per varied quantity, as deviations
from the scene's value: `{ lower = ..., upper = ... }` (uniform) or `{ sd = ... }` (normal,
mean 0), in the quantity's unit (QUANTITIES).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..scene.schema import SceneError
from ..scene.tolerance_section import QUANTITIES, ToleranceSpec, build_tolerance_spec  # noqa: F401 - part of this API

# --- the stacks ------------------------------------------------------------------------------
def sample_deviations(spec: ToleranceSpec, samples: int | None = None, seed: int | None = None) -> dict[str, np.ndarray]:
    """{quantity: deviations (n,)}, reproducible from the seed (each quantity its own stream)."""
    n = spec.samples if samples is None else samples
    root = np.random.SeedSequence(spec.seed if seed is None else seed)
    streams = root.spawn(len(QUANTITIES))
    index = {name: i for i, name in enumerate(QUANTITIES)}
    return {d.name: d.sample(np.random.default_rng(streams[index[d.name]]), n) for d in spec.deviations}


def _deviation(dev: dict[str, np.ndarray], n: int):
    """The sampled deviation of a quantity, zeros where it does not vary."""
    return lambda name: dev.get(name, np.zeros(n))


def _growth(scene, dev: dict[str, np.ndarray], n: int) -> dict[str, np.ndarray]:
    """M.120's 1 + alpha Delta T of each part at each stack's (deviated) temperature."""
    from ...dynamics.thermal import growth_factor

    t, a, d = scene.temperatures, scene.expansion, _deviation(dev, n)
    alpha = {"inner_ring": a.race, "outer_ring": a.race, "ball": a.ball, "cage": a.cage}
    return {part: growth_factor(alpha[part], t.rise(part) + d(f"{part}_temperature")) for part in alpha}


def stack_clearances(scene, dev: dict[str, np.ndarray], n: int):
    """CageClearances (arrays of n) of the stacks: the scene's drawing dimensions plus the
    deviations, each part grown to its (deviated) temperature (M.120)."""
    from ...dynamics.quasistatic.crush_screen import CageClearances

    b, c, d, f = scene.nominal.bearing, scene.nominal.cage, _deviation(dev, n), _growth(scene, dev, n)
    outside = (c.outside_diameter + d("cage_outside_diameter")) * f["cage"]
    bore = (c.bore_diameter + d("cage_bore_diameter")) * f["cage"]
    outer_land = (b.outer_shoulder_diameter + d("outer_land_diameter")) * f["outer_ring"]
    inner_land = (b.inner_shoulder_diameter + d("inner_land_diameter")) * f["inner_ring"]
    if c.guidance == "outer":
        guide, non_guiding = 0.5 * (outer_land - outside), 0.5 * (bore - inner_land)
    else:
        guide, non_guiding = 0.5 * (bore - inner_land), 0.5 * (outer_land - outside)
    pocket = (c.pocket_diameter + d("pocket_diameter")) * f["cage"] - (b.ball_diameter + d("ball_diameter")) * f["ball"]
    ecc = np.maximum(0.0, c.pocket_circle_eccentricity + d("pocket_circle_eccentricity")) * f["cage"]
    return CageClearances(pocket=pocket, guide=guide, pocket_circle_eccentricity=ecc,
                          pocket_index_range=c.pocket_index_range() * f["cage"], non_guiding=non_guiding)


def _excursion_at(scene, moment: float, axial: float, diametral_clearance: float | None):
    """(s1, s_pp, cos and sin of the push azimuth, the land shift of M.124 flattened (4)) of the scene at these
    loads, its inner ring grown or shrunk to give the operating diametral clearance P_d (None:
    the scene's)."""
    from ...dynamics import thermal as th
    from ...dynamics.quasistatic.crush_screen import excursion_of

    from ..scene.load import variant
    from .solution import land_shift, solve

    b = scene.operating.bearing
    if diametral_clearance is not None:
        factor = 1.0 + (b.diametral_clearance - diametral_clearance) / b.inner_groove_bottom_diameter
        b = th.scaled(b, factor, th.INNER_RING_LENGTHS)
    s = variant(scene, operating=dataclasses.replace(scene.operating, bearing=b),
                load=dataclasses.replace(scene.load, moment=moment, axial=axial))
    r = solve(s)
    x = excursion_of(r.azimuth, r.ball_orbital_speed, 0.5 * scene.operating.cage.mean_diameter)
    return np.concatenate([[x.first_harmonic, x.peak_to_peak, math.cos(x.push_azimuth), math.sin(x.push_azimuth)],
                           land_shift(scene, r).ravel()])


RING_QUANTITIES = ("inner_ring_temperature", "outer_ring_temperature", "ball_temperature", "ball_diameter",
                   "diametral_clearance")
NODES_BY_DIMENSION = {1: 17, 2: 7, 3: 5}


def stack_diametral_clearance(scene, dev: dict[str, np.ndarray], n: int) -> np.ndarray:
    """Operating diametral clearance P_d of each stack [m]: groove bottoms and balls grown to
    their (deviated) temperatures (M.120)."""
    b, d, f = scene.nominal.bearing, _deviation(dev, n), _growth(scene, dev, n)
    return ((b.outer_groove_bottom_diameter + d("diametral_clearance")) * f["outer_ring"]
            - b.inner_groove_bottom_diameter * f["inner_ring"] - 2.0 * (b.ball_diameter + d("ball_diameter")) * f["ball"])


def excursion_surrogate(scene, dev: dict[str, np.ndarray]):
    """(n, 8): s1, s_pp [m], cos and sin of the push azimuth and the land shift of M.124 [m] at each stack: one
    quasi-static solution, or linear interpolation on a grid over what moves the load distribution — the
    moment, the thrust and the operating diametral clearance (ring and ball temperatures, ball
    diameter) — NODES_BY_DIMENSION nodes per varied variable."""
    from scipy.interpolate import RegularGridInterpolator

    n = len(next(iter(dev.values())))
    at_stack = {"moment": scene.load.moment + dev.get("moment", np.zeros(n)),
                "axial": scene.load.axial + dev.get("axial", np.zeros(n))}
    if any(q in dev for q in RING_QUANTITIES):
        at_stack["diametral_clearance"] = stack_diametral_clearance(scene, dev, n)
    varied = [k for k, v in at_stack.items() if v.max() > v.min()]
    nominal = {"moment": scene.load.moment, "axial": scene.load.axial, "diametral_clearance": None}
    if not varied:
        return np.tile(_excursion_at(scene, nominal["moment"], nominal["axial"], None), (n, 1))
    nodes = NODES_BY_DIMENSION[len(varied)]
    axes = [np.linspace(at_stack[k].min(), at_stack[k].max(), nodes) for k in varied]
    grids = np.meshgrid(*axes, indexing="ij")
    values = np.empty(grids[0].shape + (8,))
    for idx in np.ndindex(grids[0].shape):
        point = nominal | {k: float(g[idx]) for k, g in zip(varied, grids)}
        values[idx] = _excursion_at(scene, point["moment"], point["axial"], point["diametral_clearance"])
    return RegularGridInterpolator(tuple(axes), values)(np.column_stack([at_stack[k] for k in varied]))


# --- the analysis ------------------------------------------------------------------------------
@dataclass(frozen=True)
class ToleranceResult:
    """Every sampled stack; the screen's arrays hold NaN (margin, clearances) and INVALID (regime)
    at the stacks that are no bearing the model covers (`valid` False; `invalid` counts them by
    the scene key whose check they fail)."""

    deviations: dict[str, np.ndarray]
    margin: np.ndarray  # (C - e_req)/C at the worst cage orientation [-]
    regime: np.ndarray  # 0 free, 1 pressed, 2 crushed, INVALID
    guide_clearance: np.ndarray  # [m]
    pocket_clearance: np.ndarray  # [m]
    non_guiding_gap: np.ndarray  # [m] (< 0: touching)
    spec: ToleranceSpec
    valid: np.ndarray | None = None  # bool (n,); None: all valid
    invalid: dict[str, int] = dataclasses.field(default_factory=dict)

    @property
    def valid_mask(self) -> np.ndarray:
        return np.ones(self.margin.size, bool) if self.valid is None else self.valid


INVALID = -1  # the regime code of a stack that is no bearing


def analyse(scene, spec: ToleranceSpec | None = None, samples: int | None = None,
            seed: int | None = None) -> ToleranceResult:
    """Sample the stacks of `spec` (default: the scene's [tolerances]), check each against the
    scene's own validation (pipeline.scene.tolerance_stacks) and screen the valid ones."""
    from ..scene.tolerance_stacks import invalid_stacks

    spec = spec or scene.tolerances
    if spec is None:
        raise SceneError("tolerances", "the scene has no [tolerances] table; see docs/scenes.md")
    if scene.cage is None:
        raise SceneError("tolerances", "the crush probability needs a [cage]")
    dev = sample_deviations(spec, samples, seed)
    n = len(next(iter(dev.values())))
    bad, reasons = invalid_stacks(scene, dev, n)
    valid = ~np.asarray(bad, dtype=bool)
    if not valid.any():
        raise SceneError("tolerances", f"none of the {n} sampled stacks is a bearing the model covers (they fail "
                                       f"{_reasons(reasons)}): narrow the tolerances")
    screened = _screen(scene, {k: v[valid] for k, v in dev.items()})

    def spread(values: np.ndarray, fill: float) -> np.ndarray:
        out = np.full(n, fill, dtype=np.asarray(values).dtype)
        out[valid] = values
        return out

    return ToleranceResult(deviations=dev, margin=spread(screened["margin"], np.nan),
                           regime=spread(screened["regime"], INVALID),
                           guide_clearance=spread(screened["guide"], np.nan),
                           pocket_clearance=spread(screened["pocket"], np.nan),
                           non_guiding_gap=spread(screened["gap"], np.nan), spec=spec,
                           valid=None if valid.all() else valid, invalid=reasons)


def _reasons(reasons: dict[str, int]) -> str:
    return ", ".join(f"{key} ({count})" for key, count in sorted(reasons.items(), key=lambda kv: -kv[1]))


def _screen(scene, dev: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    """The crush screen of every stack of `dev` (all valid): margin, regime code, guide and pocket
    clearances, gap to the non-guiding land."""
    from ...dynamics.quasistatic.crush_screen import margin_and_regime, non_guiding_gap, required_offset

    n = len(next(iter(dev.values())))
    x = excursion_surrogate(scene, dev)
    s1, s_pp, shift = x[:, 0], x[:, 1], x[:, 4:].reshape(n, 2, 2)
    push = np.arctan2(x[:, 3], x[:, 2])
    clear = stack_clearances(scene, dev, n)
    (_, worst), pressed = required_offset(s1, s_pp, clear)
    margin, code = margin_and_regime(worst, pressed, clear.guide)
    gap = non_guiding_gap(clear.non_guiding, np.minimum(worst, clear.guide), push, shift)
    return {"margin": np.asarray(margin, float), "regime": np.asarray(code, int), "guide": np.asarray(clear.guide, float),
            "pocket": np.asarray(clear.pocket, float), "gap": np.asarray(gap, float)}


def drivers(result: ToleranceResult) -> list[dict]:
    """Inputs ranked by their share of the margin's variance (squared standardised regression
    coefficient), with the Spearman rank correlation."""
    from scipy.stats import spearmanr

    names = list(result.deviations)
    ok = result.valid_mask
    X = np.column_stack([result.deviations[k][ok] for k in names])
    y = result.margin[ok]
    sx, sy = X.std(axis=0), y.std()
    rows = []
    if sy > 0.0:
        Z = (X - X.mean(axis=0)) / np.where(sx > 0, sx, 1.0)
        coef, *_ = np.linalg.lstsq(np.column_stack([Z, np.ones(len(y))]), (y - y.mean()) / sy, rcond=None)
        for i, name in enumerate(names):
            rho = float(spearmanr(X[:, i], y).statistic) if sx[i] > 0 else 0.0
            rows.append({"quantity": name, "unit": QUANTITIES[name][0], "src": float(coef[i]),
                         "variance_share": float(coef[i] ** 2), "spearman": rho})
    return sorted(rows, key=lambda r: -r["variance_share"])


def linear_share(result: ToleranceResult) -> float | None:
    """R^2 of the margin's linear regression on the deviations: how much of its variance the
    drivers' shares (squared standardised coefficients) account for; near 1 they are the whole
    story, well below 1 the margin responds non-linearly and the Spearman column ranks better."""
    ok = result.valid_mask
    X = np.column_stack([result.deviations[k][ok] for k in result.deviations] + [np.ones(int(ok.sum()))])
    y = result.margin[ok]
    if y.size < 3 or y.std() == 0.0:
        return None
    fit = X @ np.linalg.lstsq(X, y, rcond=None)[0]
    return float(1.0 - np.sum((y - fit) ** 2) / np.sum((y - y.mean()) ** 2))


def percentile_stack(result: ToleranceResult, q: float = 5.0) -> dict[str, float]:
    """The deviations of the stack whose margin sits at the q-th percentile."""
    margin = np.where(result.valid_mask, result.margin, np.inf)
    target = np.percentile(result.margin[result.valid_mask], q)
    i = int(np.argmin(np.abs(margin - target)))
    return {name: float(v[i]) for name, v in result.deviations.items()} | {"margin": float(result.margin[i])}


def stack_overrides(scene, stack: dict[str, float]) -> list[str]:
    """`--set` overrides that put one stack into the scene (dimensions as drawn, temperatures
    in °C), so a dynamic run can confirm its regime (pipeline.scene.tolerance_stacks.stack_values)."""
    from ..scene.tolerance_stacks import stack_values

    # 9 digits: 0.1 nm on a diameter, readable on the command line
    return [f"{key}={value:.9g}" for key, value in stack_values(scene, stack).items()]


def summary(result: ToleranceResult, scene) -> dict:
    """The JSON of the analysis: probabilities over the valid stacks with their standard errors,
    the stacks that are no bearing (counted by the key they fail), the margin's distribution, the
    drivers and the 5th-percentile stack."""
    ok = result.valid_mask
    n, drawn = int(ok.sum()), result.margin.size
    margin, regime = result.margin[ok], result.regime[ok]
    probs = {}
    for code, name in enumerate(("free", "pressed", "crushed")):
        p = float(np.mean(regime == code))
        # the binomial error of independent samples: an upper bound for a Latin hypercube's
        probs[name] = {"probability": p, "standard_error": math.sqrt(max(p * (1 - p), 1.0 / n) / n)}
    q = (1, 5, 25, 50, 75, 95, 99)
    stack5 = percentile_stack(result, 5.0)
    return {
        "samples": drawn, "valid_samples": n, "seed": result.spec.seed,
        "sampling": "Latin hypercube (scipy.stats.qmc), one stream per quantity",
        "tolerances": {d.name: d.describe() for d in result.spec.deviations},
        "invalid_stacks": {"count": drawn - n, "fraction": (drawn - n) / drawn, "by_key": dict(result.invalid)},
        "regime_probability": probs,
        "crush_probability": probs["crushed"]["probability"],
        "margin_percentiles": {f"p{k}": float(np.percentile(margin, k)) for k in q},
        "margin_mean": float(margin.mean()),
        "non_guiding_touch_probability": float(np.mean(result.non_guiding_gap[ok] < 0.0)),
        "guide_clearance_percentiles_m": {f"p{k}": float(np.percentile(result.guide_clearance[ok], k)) for k in (5, 50, 95)},
        "pocket_clearance_percentiles_m": {f"p{k}": float(np.percentile(result.pocket_clearance[ok], k)) for k in (5, 50, 95)},
        "drivers": drivers(result),
        "drivers_linear_r2": linear_share(result),
        "stack_at_p5": stack5,
        "stack_at_p5_overrides": stack_overrides(scene, stack5),
        "units": {"margin": "1", "probability": "1", "deviations": {k: QUANTITIES[k][0] for k in result.deviations}},
    }


def write_samples_csv(path, result: ToleranceResult) -> None:
    """Every stack drawn: its deviations, clearances, margin and regime ("invalid" with empty
    cells for a stack that is no bearing); units in the headers."""
    import io

    from ..staging.artefacts import atomic_write_bytes

    names = list(result.deviations)
    header = [f"{n}_deviation [{QUANTITIES[n][0]}]" for n in names] + [
        "guide_clearance [m]", "pocket_clearance [m]", "non_guiding_gap [m]", "crush_margin [1]", "regime"]
    cols = [result.deviations[n] for n in names] + [result.guide_clearance, result.pocket_clearance,
                                                     result.non_guiding_gap, result.margin]
    buf = io.StringIO()
    buf.write(",".join(header) + "\n")
    regimes = ("free", "pressed", "crushed")
    for i in range(result.margin.size):
        code = int(result.regime[i])
        cells = (f"{c[i]:.9g}" if math.isfinite(c[i]) else "" for c in cols)
        buf.write(",".join(cells) + f",{regimes[code] if code != INVALID else 'invalid'}\n")
    atomic_write_bytes(path, buf.getvalue().encode())
