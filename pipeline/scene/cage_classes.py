"""Cage-motion class and risk level of one run from its summary metrics (docs/scenes.md
`summary.json`).

The classes describe how the cage moves once the start-up transient has died out (all
metrics are taken over the *settled window* of the run, see
`pipeline.results.settled_window`; summaries written before it existed used the last
half of the run):

=========== ===================================================================================
class        rule (checked in this order; thresholds are fields of `CageClassThresholds`)
=========== ===================================================================================
crushed      ``cage_metal_contact_fraction >= crushed_contact`` (0.5) and
             ``cage_contact_angle_spread <= crushed_spread`` (0.5 rad): the cage is pressed
             metal-to-metal against one sector of its guide land most of the time — the
             load-fixed burn zone of docs/model.md §0.
pressed      not crushed, ``cage_offset_spread <= crushed_spread`` (0.5 rad: the direction of
             the cage offset stays in one sector) and ``cage_eps_mean >= pressed_eps`` (0.6):
             the cage is pushed onto one sector of its land *through its film*. The film
             carries the load, but always on the same strip of land, which takes the whole
             shear heat; a film that thins as it heats, or a load rise, ends on that strip.
whirling     ``|cage_whirl_ratio| >= whirl_ratio`` (0.5),
             ``cage_speed_variation <= regular_speed`` (0.2) and at least ``whirl_orbits``
             (1) full orbits of the cage centre in the settled window, i.e.
             ``|cage_whirl_ratio| * cage_speed_mean * window / 2 pi >= whirl_orbits``:
             the centre orbits the bearing axis at a sizeable fraction of the cage speed
             with a regular spin (whirl in the film, or rolling round the land when in
             metal contact).
centred      ``cage_metal_contact_fraction < contact_free`` (0.05) and
             ``cage_speed_variation <= steady_speed`` (0.05), not whirling: the cage floats
             on its film at a steady speed — stable.
chaotic      anything else: intermittent metal contact, wandering contact direction,
             irregular speed.
=========== ===================================================================================

Two more labels are not motions: ``failed`` (the point did not finish) and ``no cage``
(the scene has no cage, so there are no cage metrics).

Why these numbers (this project's choice; a scene can change them in
``[sweep.thresholds]``): below 5 % of the time, metal contact is a few isolated events
rather than a regime; 50 % means contact most of the time. A circular spread of 0.5 rad
(Mardia & Jupp's circular standard deviation, about ±29°) keeps the contact — or the
offset of a pressed cage — inside one sector of the land, where a burn zone forms, whereas
a cage rolling or whirling round the land spreads it over the whole circle (spread > 1
rad). A mean eccentricity ratio of 0.6 means the film on the loaded side is down to
(1 + eps0 - 0.6) / (1 + eps0) ≈ 43 % of the concentric film (eps0 = 0.05), where the
short-bearing (Ocvirk) film force, eps_h sqrt(pi^2 (1 - eps_h^2) + 16 eps_h^2) /
(1 - eps_h^2)^2 in units of its scale, is already 2.4 times its small-offset linear value
pi eps_h: the film is held in its non-linear range by a load, the cage is not floating near
the centre. The whirl ratio of a centred cage is noise, and a centre drifting across the axis
in a short run turns its azimuth by up to pi in a moment: hence the demand for a whirl at
half the cage speed or faster *and* at least one full orbit. The classes follow the
published split of simulated and measured cage motion into steady rotation, regular
circular whirl and disordered (chaotic) motion (e.g. "Investigation on the Cage Whirl State
of Cylindrical Roller Bearings under High Speed and Light Load", Machines 10(9):768, 2022;
Schwarz, Grillenberger & Tremmel, "Establishing a metric for identifying rolling bearing
cage dynamics", 2020), plus the crushed and pressed states this software exists to
predict (docs/model.md §0).

Risk level (`risk_level`), from the class, the metal contact and the film-thickness
ratio Lambda_min = h_min / sigma of the land (`land_film_ratio_min`; sigma the composite
RMS roughness of cage rim and land):

=========== ===================================================================================
high         crushed; or ``cage_metal_contact_fraction >= risk_contact`` (0.05: contact is
             a regime, not isolated events); or ``Lambda_min < lambda_boundary`` (1:
             boundary lubrication, the asperities carry load somewhere on the land); or
             pressed with ``Lambda_min < lambda_full_film`` (3): a mixed film on the one
             sector that takes all the heat, which is how a burn zone starts.
elevated     pressed (a load-fixed sector through a full film: the land heats in one
             place); or any metal contact in the settled window (whirling or chaotic
             cages touching the land, a centred cage with isolated rubs); or
             ``Lambda_min < lambda_full_film`` (mixed lubrication somewhere on the land).
low          otherwise: a floating or whirling cage on a full film without contact.
=========== ===================================================================================

The Lambda limits are the classic lubrication regimes of T. E. Tallian (ASLE Trans. 10,
1967) and B. J. Hamrock (*Fundamentals of Fluid Film Lubrication*): Lambda < 1 boundary,
1-3 mixed, > 3 full film. Without a film (no `land_film_ratio_min`) the Lambda rules are
skipped and the class and contact decide.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

CAGE_CLASSES = ("centred", "whirling", "pressed", "crushed", "chaotic")
NOT_CLASSIFIED = ("failed", "no cage")
RISK_LEVELS = ("low", "elevated", "high")


@dataclass(frozen=True)
class CageClassThresholds:
    """`[sweep.thresholds]`: the limits of the cage-motion classes and risk levels (module
    docstring)."""

    contact_free: float = field(default=0.05, metadata={
        "unit": "-", "gt": 0.0, "lt": 1.0, "doc": "metal-contact fraction below which the cage floats"})
    crushed_contact: float = field(default=0.5, metadata={
        "unit": "-", "gt": 0.0, "le": 1.0, "doc": "metal-contact fraction from which a cage can be crushed"})
    crushed_spread: float = field(default=0.5, metadata={
        "unit": "rad", "gt": 0.0, "doc": "largest circular spread of the contact direction of a crushed cage "
                                         "(and of the offset direction of a pressed cage)"})
    pressed_eps: float = field(default=0.6, metadata={
        "unit": "-", "gt": 0.0, "doc": "smallest mean eccentricity ratio of a cage pressed onto its land"})
    whirl_ratio: float = field(default=0.5, metadata={
        "unit": "-", "gt": 0.0, "doc": "|whirl speed / cage speed| from which the cage whirls"})
    steady_speed: float = field(default=0.05, metadata={
        "unit": "-", "gt": 0.0, "doc": "largest cage_speed_variation of a centred cage"})
    regular_speed: float = field(default=0.2, metadata={
        "unit": "-", "gt": 0.0, "doc": "largest cage_speed_variation of a whirling cage"})
    whirl_orbits: float = field(default=1.0, metadata={
        "unit": "-", "gt": 0.0, "doc": "full orbits of the cage centre in the settled window to call it whirl"})
    risk_contact: float = field(default=0.05, metadata={
        "unit": "-", "gt": 0.0, "le": 1.0, "doc": "metal-contact fraction from which the risk is high"})
    lambda_boundary: float = field(default=1.0, metadata={
        "unit": "-", "gt": 0.0, "doc": "film-thickness ratio h_min/sigma below which the land runs in boundary lubrication (high risk)"})
    lambda_full_film: float = field(default=3.0, metadata={
        "unit": "-", "gt": 0.0, "doc": "film-thickness ratio h_min/sigma from which the land film is full (below: mixed)"})

    def __post_init__(self) -> None:
        if not self.contact_free < self.crushed_contact:
            raise ValueError(f"contact_free = {self.contact_free:g} must be below crushed_contact = "
                             f"{self.crushed_contact:g} (metal-contact fractions)")
        if not self.steady_speed <= self.regular_speed:
            raise ValueError(f"steady_speed = {self.steady_speed:g} must not exceed regular_speed = "
                             f"{self.regular_speed:g} (cage speed variations)")
        if not self.lambda_boundary < self.lambda_full_film:
            raise ValueError(f"lambda_boundary = {self.lambda_boundary:g} must be below lambda_full_film = "
                             f"{self.lambda_full_film:g} (film-thickness ratios)")


def _number(summary: dict, key: str) -> float | None:
    value = summary.get(key)
    if value is None or isinstance(value, bool):
        return None
    value = float(value)
    return value if math.isfinite(value) else None


def settled_duration(summary: dict) -> float:
    """Length of the window the metrics cover [s]: the settled window, or the last half of
    the run for summaries written before it."""
    window = summary.get("settled_window")
    if isinstance(window, (list, tuple)) and len(window) == 2 and None not in window:
        return max(0.0, float(window[1]) - float(window[0]))
    return 0.5 * (_number(summary, "duration") or 0.0)


def classify_cage(summary: dict | None, limits: CageClassThresholds = CageClassThresholds()) -> str:
    """The cage-motion class of one run's `summary.json` dict (None: the run failed)."""
    if summary is None:
        return "failed"
    if "cage_speed_mean" not in summary:  # the simulate stage writes cage keys only with a cage
        return "no cage"
    metal = _number(summary, "cage_metal_contact_fraction") or 0.0
    spread = _number(summary, "cage_contact_angle_spread")
    offset_spread = _number(summary, "cage_offset_spread")
    eps_mean = _number(summary, "cage_eps_mean")
    whirl = abs(_number(summary, "cage_whirl_ratio") or 0.0)
    variation = _number(summary, "cage_speed_variation")
    variation = math.inf if variation is None else variation
    orbits = whirl * abs(_number(summary, "cage_speed_mean") or 0.0) * settled_duration(summary) / (2.0 * math.pi)
    if metal >= limits.crushed_contact and spread is not None and spread <= limits.crushed_spread:
        return "crushed"
    if (offset_spread is not None and offset_spread <= limits.crushed_spread
            and eps_mean is not None and eps_mean >= limits.pressed_eps):
        return "pressed"
    if whirl >= limits.whirl_ratio and variation <= limits.regular_speed and orbits >= limits.whirl_orbits:
        return "whirling"
    if metal < limits.contact_free and variation <= limits.steady_speed:
        return "centred"
    return "chaotic"


def risk_level(summary: dict | None, limits: CageClassThresholds = CageClassThresholds(),
               cage_class: str | None = None) -> tuple[str | None, list[str]]:
    """(risk level, reasons) of one run's summary (module docstring); (None, []) for a run
    without a cage or that failed. `cage_class` saves classifying twice."""
    cage_class = cage_class or classify_cage(summary, limits)
    if cage_class in NOT_CLASSIFIED:
        return None, []
    metal = _number(summary, "cage_metal_contact_fraction") or 0.0
    ratio = _number(summary, "land_film_ratio_min")
    high, elevated = [], []
    if cage_class == "crushed":
        high.append("crushed: metal contact on one sector of the land most of the time")
    if metal >= limits.risk_contact:
        high.append(f"metal contact {100 * metal:.3g} % of the settled run (>= {100 * limits.risk_contact:g} %)")
    if ratio is not None and ratio < limits.lambda_boundary:
        high.append(f"boundary lubrication on the land: Lambda_min {ratio:.2g} < {limits.lambda_boundary:g}")
    if cage_class == "pressed":
        if ratio is not None and ratio < limits.lambda_full_film:
            high.append(f"pressed on one sector through a mixed film: Lambda_min {ratio:.2g} < {limits.lambda_full_film:g}")
        else:
            elevated.append("pressed: one sector of the land carries the cage and takes its film heat")
    if 0.0 < metal < limits.risk_contact:
        elevated.append(f"metal contact {100 * metal:.2g} % of the settled run")
    if ratio is not None and limits.lambda_boundary <= ratio < limits.lambda_full_film and cage_class != "pressed":
        elevated.append(f"mixed lubrication on the land: Lambda_min {ratio:.2g} < {limits.lambda_full_film:g}")
    if high:
        return "high", high + elevated
    if elevated:
        return "elevated", elevated
    return "low", []
