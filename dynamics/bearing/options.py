"""Physics switches and contact parameters of the bearing model: the scene's `[physics]` table.

The scene loader builds this class straight from `[physics]` (pipeline/scene/sections.py),
so the field metadata below (unit, range, choices, doc) is the one definition of every
physics key; docs/scenes.md is generated from it. SI units.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from ..contact.pocket_laws import LAWS as POCKET_LAWS
from ..field_checks import check_fields
from ..journal.land_laws import LAWS as LAND_LAWS
from ..lubrication.film_laws import LAWS as FILM_LAWS
from ..traction.laws import LAWS


@dataclass(frozen=True)
class ModelOptions:
    """Which laws the contacts use and their parameters (docs/model.md §6–§8, §10)."""

    ehd_film: bool = field(default=True, metadata={
        "doc": "compute the EHD central film of every ball-race contact (needs [lubricant])"})
    traction: str = field(default="eyring", metadata={
        "choices": LAWS,
        "doc": "ball-race traction law (dynamics/traction/laws): " + "; ".join(
            f"'{name}' {law.doc}" + (" (needs [lubricant] and the film)" if law.film else "")
            for name, law in LAWS.items())})
    limiting_shear_coefficient: float = field(default=0.075, metadata={
        "unit": "-", "gt": 0.0, "le": 0.5,
        "doc": "Lambda of traction = 'limiting-shear': limiting shear stress over pressure (Bair & Winer 1979: "
               "0.05-0.1), taken at the mean Hertz pressure"})
    cage_race: str = field(default="hybrid", metadata={
        "choices": LAND_LAWS,
        "doc": "cage-land law (dynamics/journal/land_laws): " + "; ".join(
            f"'{name}' {law.doc}" + (" (needs [lubricant])" if law.film else "") for name, law in LAND_LAWS.items())})
    centrifugal: bool = field(default=True, metadata={
        "doc": "ball centrifugal force in the quasi-static solve; the dynamic model's inertia always has it, "
               "so a dynamic run refuses false"})
    gyroscopic: bool = field(default=True, metadata={
        "doc": "gyroscopic moments: of the balls in the quasi-static solve (race control), of every body in "
               "the dynamics"})
    film_formula: str = field(default="nvm", metadata={
        "choices": FILM_LAWS, "doc": "central EHD film law (dynamics/lubrication/film_laws): " + "; ".join(
            f"'{name}' {law.doc}" for name, law in FILM_LAWS.items())})
    min_film: float = field(default=5e-8, metadata={
        "unit": "m", "gt": 0.0, "doc": "floor of the film used by traction (mixed lubrication is not modelled)"})
    dry_friction: float = field(default=0.1, metadata={
        "unit": "-", "ge": 0.0, "le": 1.0, "doc": "ball-race Coulomb coefficient (traction = 'coulomb')"})
    contact_damping_ratio: float = field(default=0.05, metadata={
        "unit": "-", "ge": 0.0, "le": 1.0,
        "doc": "ball-race normal damping, fraction of critical for a ball on its Hertz stiffness"})
    pocket_friction: float = field(default=0.1, metadata={
        "unit": "-", "ge": 0.0, "le": 1.0, "doc": "ball-pocket Coulomb coefficient (regularised)"})
    pocket_law: str = field(default="hertz-hysteresis", metadata={
        "choices": POCKET_LAWS,
        "doc": "ball-pocket normal-force law (dynamics/contact/pocket_laws): " + "; ".join(
            f"'{name}' {law.doc}" for name, law in POCKET_LAWS.items())})
    pocket_restitution: float = field(default=0.7, metadata={
        "unit": "-", "gt": 0.0, "le": 1.0,
        "doc": "coefficient of restitution of ball-pocket impacts (Hunt-Crossley damping)"})
    cage_race_friction: float = field(default=0.1, metadata={
        "unit": "-", "ge": 0.0, "le": 1.0, "doc": "metal-to-metal friction at the guide land"})
    cage_race_boundary: float = field(default=0.05, metadata={
        "unit": "-", "gt": 0.0, "lt": 1.0, "doc": "epsilon_0: boundary-layer width of the hybrid model / C"})
    cage_race_film: str = field(default="dynamic", metadata={
        "choices": ("dynamic", "static"),
        "doc": "land film force: 'dynamic' = short bearing with the squeeze and whirl terms of the Reynolds "
               "equation (docs/model.md M.94b-M.94e); 'static' = the paper's eq. 25 (a centre at rest)"})
    cage_race_lands: int = field(default=2, metadata={
        "unit": "-", "ge": 1, "le": 2,
        "doc": "separate guide lands the cage overlap is split into: 2 = one on each side of the race groove, "
               "which vents the film (each a short bearing of half the length); 1 = the paper's single journal"})
    coulomb_regularisation: float = field(default=1e-3, metadata={
        "unit": "m/s", "gt": 0.0,
        "doc": "slip speed over which Coulomb friction (traction = 'coulomb') reaches its full value"})

    def __post_init__(self) -> None:
        check_fields(self, "physics")
