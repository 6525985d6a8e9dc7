"""Cage-motion class of one run from its summary metrics (SCENE.md `summary.json`).

The classes describe how the cage moves once the start-up transient has died out (all
metrics are taken over the last half of the run, see :mod:`pipeline.results.cage_metrics`):

=========== ===================================================================================
class        rule (checked in this order; thresholds are fields of :class:`CageClassThresholds`)
=========== ===================================================================================
crushed      ``cage_metal_contact_fraction >= crushed_contact`` (0.5) and
             ``cage_contact_angle_spread <= crushed_spread`` (0.5 rad): the cage is pressed
             metal-to-metal against one sector of its guide land most of the time — the
             load-fixed burn zone of MODEL.md §0.
whirling     ``|cage_whirl_ratio| >= whirl_ratio`` (0.5),
             ``cage_speed_variation <= regular_speed`` (0.2) and at least ``whirl_orbits``
             (1) full orbits of the cage centre in the analysis window, i.e.
             ``|cage_whirl_ratio| * cage_speed_mean * duration / 2 >= 2 pi whirl_orbits``:
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
(Mardia & Jupp's circular standard deviation, about ±29°) keeps the contact inside one
sector of the land, where a burn zone forms, whereas a cage rolling round the land
spreads it over the whole circle (spread > 1 rad). The whirl ratio of a centred cage is
noise, and a centre drifting across the axis in a short run turns its azimuth by up to
pi in a moment: hence the demand for a whirl at half the cage speed or faster *and* at
least one full orbit. The classes follow the published split of simulated and measured
cage motion into steady rotation, regular circular whirl and disordered (chaotic) motion
(e.g. "Investigation on the Cage Whirl State of Cylindrical Roller Bearings under High
Speed and Light Load", Machines 10(9):768, 2022; Schwarz, Grillenberger & Tremmel,
"Establishing a metric for identifying rolling bearing cage dynamics", 2020), plus the
crushed state this software exists to predict (MODEL.md §0).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

CAGE_CLASSES = ("centred", "whirling", "crushed", "chaotic")
NOT_CLASSIFIED = ("failed", "no cage")


@dataclass(frozen=True)
class CageClassThresholds:
    """`[sweep.thresholds]`: the limits of the cage-motion classes (module docstring)."""

    contact_free: float = field(default=0.05, metadata={
        "unit": "-", "gt": 0.0, "lt": 1.0, "doc": "metal-contact fraction below which the cage floats"})
    crushed_contact: float = field(default=0.5, metadata={
        "unit": "-", "gt": 0.0, "le": 1.0, "doc": "metal-contact fraction from which a cage can be crushed"})
    crushed_spread: float = field(default=0.5, metadata={
        "unit": "rad", "gt": 0.0, "doc": "largest circular spread of the contact direction of a crushed cage"})
    whirl_ratio: float = field(default=0.5, metadata={
        "unit": "-", "gt": 0.0, "doc": "|whirl speed / cage speed| from which the cage whirls"})
    steady_speed: float = field(default=0.05, metadata={
        "unit": "-", "gt": 0.0, "doc": "largest cage_speed_variation of a centred cage"})
    regular_speed: float = field(default=0.2, metadata={
        "unit": "-", "gt": 0.0, "doc": "largest cage_speed_variation of a whirling cage"})
    whirl_orbits: float = field(default=1.0, metadata={
        "unit": "-", "gt": 0.0, "doc": "full orbits of the cage centre in the analysis window to call it whirl"})

    def __post_init__(self) -> None:
        if not self.contact_free < self.crushed_contact:
            raise ValueError(f"contact_free = {self.contact_free:g} must be below crushed_contact = "
                             f"{self.crushed_contact:g} (metal-contact fractions)")
        if not self.steady_speed <= self.regular_speed:
            raise ValueError(f"steady_speed = {self.steady_speed:g} must not exceed regular_speed = "
                             f"{self.regular_speed:g} (cage speed variations)")


def _number(summary: dict, key: str) -> float | None:
    value = summary.get(key)
    if value is None or isinstance(value, bool):
        return None
    value = float(value)
    return value if math.isfinite(value) else None


def classify_cage(summary: dict | None, limits: CageClassThresholds = CageClassThresholds()) -> str:
    """The cage-motion class of one run's `summary.json` dict (None: the run failed)."""
    if summary is None:
        return "failed"
    if "cage_speed_mean" not in summary:  # the simulate stage writes cage keys only with a cage
        return "no cage"
    metal = _number(summary, "cage_metal_contact_fraction") or 0.0
    spread = _number(summary, "cage_contact_angle_spread")
    whirl = abs(_number(summary, "cage_whirl_ratio") or 0.0)
    variation = _number(summary, "cage_speed_variation")
    variation = math.inf if variation is None else variation
    # centre orbits over the analysis window, the last half of the run (cage_metrics)
    window = 0.5 * (_number(summary, "duration") or 0.0)
    orbits = whirl * abs(_number(summary, "cage_speed_mean") or 0.0) * window / (2.0 * math.pi)
    if metal >= limits.crushed_contact and spread is not None and spread <= limits.crushed_spread:
        return "crushed"
    if whirl >= limits.whirl_ratio and variation <= limits.regular_speed and orbits >= limits.whirl_orbits:
        return "whirling"
    if metal < limits.contact_free and variation <= limits.steady_speed:
        return "centred"
    return "chaotic"
