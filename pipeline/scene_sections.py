"""The sections of a scene file (docs/scenes.md), one frozen dataclass each, SI units.

Physical sections (`[bearing]`, `[cage]`, `[materials]`) reuse the dynamics' own types;
the ones below are the scene-only sections. Field metadata gives unit and range; the
generic builder in :mod:`pipeline.schema` enforces them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from bearingsim.dynamics.geometry import Material


@dataclass(frozen=True)
class CatalogueBearing:
    """`[bearing]` form 2: catalogue data (resolved to BearingGeometry)."""

    ball_diameter: float = field(metadata={"unit": "m", "gt": 0.0, "doc": "ball diameter D"})
    ball_count: int = field(metadata={"unit": "-", "ge": 3, "doc": "number of balls Z"})
    pitch_diameter: float = field(metadata={"unit": "m", "gt": 0.0, "doc": "pitch diameter d_m"})
    inner_conformity: float = field(metadata={"unit": "-", "gt": 0.5, "le": 1.0, "doc": "r_i / D"})
    outer_conformity: float = field(metadata={"unit": "-", "gt": 0.5, "le": 1.0, "doc": "r_o / D"})
    diametral_clearance: float = field(
        default=0.0, metadata={"unit": "m", "doc": "unmounted radial play x 2; negative = preload"}
    )
    inner_shoulder_diameter: float | None = field(default=None, metadata={"unit": "m", "gt": 0.0, "doc": "inner-ring land diameter"})
    outer_shoulder_diameter: float | None = field(default=None, metadata={"unit": "m", "gt": 0.0, "doc": "outer-ring land diameter"})
    inner_bore_diameter: float | None = field(default=None, metadata={"unit": "m", "gt": 0.0, "doc": "inner-ring bore"})
    outer_outside_diameter: float | None = field(default=None, metadata={"unit": "m", "gt": 0.0, "doc": "outer-ring outside diameter"})
    width: float | None = field(default=None, metadata={"unit": "m", "gt": 0.0, "doc": "ring width B"})


@dataclass(frozen=True)
class Materials:
    ball: Material
    race: Material
    cage: Material | None = None


@dataclass(frozen=True)
class Load:
    """Loads on the inner race: axial along +z, radial along +x, moment about +y."""

    axial: float = field(default=0.0, metadata={"unit": "N", "doc": "axial load on the inner race along +z"})
    radial: float = field(default=0.0, metadata={"unit": "N", "ge": 0.0, "doc": "radial load on the inner race along +x"})
    moment: float = field(default=0.0, metadata={"unit": "N.m", "doc": "moment on the inner race about +y"})
    step_time: float | None = field(default=None, metadata={
        "unit": "s", "ge": 0.0, "doc": "time of a sudden moment step (dynamic run only; with step_moment)"})
    step_moment: float | None = field(default=None, metadata={
        "unit": "N.m", "doc": "moment about +y from step_time on (the quasi-static start uses `moment`)"})

    def __post_init__(self) -> None:
        if (self.step_time is None) != (self.step_moment is None):
            raise ValueError("a load step needs both step_time [s] and step_moment [N.m]; "
                             f"got step_time = {self.step_time}, step_moment = {self.step_moment}")

    @property
    def load_step(self) -> tuple[float, float] | None:
        """(t_step [s], moment after it [N m]) or None (constant load)."""
        return None if self.step_time is None else (self.step_time, self.step_moment)


@dataclass(frozen=True)
class Speed:
    inner_rpm: float = field(default=0.0, metadata={"unit": "rev/min", "doc": "inner-race speed about +z"})
    outer_rpm: float = field(default=0.0, metadata={"unit": "rev/min", "doc": "outer-race speed about +z (the dynamic model keeps the outer race fixed)"})

    @property
    def inner(self) -> float:
        """Inner-race speed Omega_i [rad/s] about +z."""
        return self.inner_rpm * 2.0 * math.pi / 60.0

    @property
    def outer(self) -> float:
        return self.outer_rpm * 2.0 * math.pi / 60.0


@dataclass(frozen=True)
class Hinge:
    """Viscoelastic hinge of the inner race (docs/model.md §5); H given or identified by FE."""

    source: str = field(default="none", metadata={"choices": ("fe", "given", "none"), "doc": "'fe': identified by the FE stage; 'given': translational and bending below; 'none': inner race free"})
    translational: tuple[float, ...] | None = field(
        default=None, metadata={"unit": "N/m", "doc": "diagonal of H_u (3), or H_u as 3x3 / row-major (9)"}
    )
    bending: tuple[float, ...] | None = field(
        default=None, metadata={"unit": "N.m/rad", "gt": 0.0, "length": 2, "doc": "H_psi about x, y"}
    )
    damping_ratio_time: float = field(default=1e-6, metadata={"unit": "s", "ge": 0.0, "doc": "G = c_G H"})

    def __post_init__(self) -> None:
        if self.source == "given":
            if self.translational is None or self.bending is None:
                raise ValueError(
                    "source = 'given' needs both translational [N/m] and bending [N.m/rad]"
                )
            if len(self.translational) not in (3, 9):
                raise ValueError(
                    f"translational: expected 3 values (diagonal of H_u) or 9 (3x3 row-major) "
                    f"[N/m], got {len(self.translational)}"
                )
            import numpy as np

            H = np.array(self.stiffness_matrix())
            if not np.allclose(H, H.T, rtol=1e-9, atol=0.0) or np.linalg.eigvalsh(H).min() <= 0.0:
                raise ValueError(f"translational: H_u must be symmetric positive definite [N/m], "
                                 f"got {H.tolist()}")
        elif self.translational is not None or self.bending is not None:
            raise ValueError(
                f"translational/bending are only read when source = 'given' (source is "
                f"{self.source!r}); remove them or set source = 'given'"
            )

    def stiffness_matrix(self) -> list[list[float]]:
        """H_u as a 3x3 nested list [N/m]."""
        t = self.translational or ()
        if len(t) == 3:
            return [[t[0], 0.0, 0.0], [0.0, t[1], 0.0], [0.0, 0.0, t[2]]]
        return [list(t[0:3]), list(t[3:6]), list(t[6:9])]


@dataclass(frozen=True)
class SolverSettings:
    """Numerical settings of the dynamic stage (docs/model.md §9)."""

    alpha: float = field(default=0.1, metadata={"unit": "-", "ge": 0.0, "le": 1.0 / 3.0, "doc": "HHT-alpha numerical damping (0: trapezoidal rule)"})
    duration: float = field(default=0.8, metadata={"unit": "s", "gt": 0.0, "doc": "simulated time"})
    first_step: float = field(default=1e-6, metadata={"unit": "s", "gt": 0.0, "doc": "first time step"})
    min_step: float = field(default=1e-8, metadata={"unit": "s", "gt": 0.0, "doc": "smallest step before the run gives up"})
    max_step: float = field(default=2e-6, metadata={"unit": "s", "gt": 0.0, "doc": "largest step"})
    rtol: float = field(default=1e-4, metadata={"unit": "-", "gt": 0.0, "lt": 1.0, "doc": "relative tolerance of the step controller (of the position coordinates)"})
    atol: float = field(default=1e-9, metadata={"unit": "m", "gt": 0.0, "doc": "absolute tolerance of the step controller (positions)"})

    def __post_init__(self) -> None:
        if not self.min_step <= self.first_step <= self.max_step:
            raise ValueError(
                f"steps must satisfy min_step <= first_step <= max_step, got "
                f"{self.min_step:g} <= {self.first_step:g} <= {self.max_step:g} [s]"
            )
        if self.max_step > self.duration:
            raise ValueError(
                f"max_step = {self.max_step:g} s exceeds duration = {self.duration:g} s"
            )


@dataclass(frozen=True)
class Physics:
    """Switches and contact parameters: what a scene does not need is not computed."""

    ehd_film: bool = field(default=True, metadata={
        "doc": "compute the EHD central film of every ball-race contact (needs [lubricant])"})
    traction: str = field(default="eyring", metadata={"choices": ("eyring", "coulomb", "none"), "doc": "ball-race traction: Eyring lubricant (film needed), Coulomb (dry) or none"})
    cage_race: str = field(default="hybrid", metadata={"choices": ("hybrid", "hydrodynamic", "dry", "none"), "doc": "cage-land law: hybrid film/metal (paper eqs. 25-31), film only, metal only, or no contact"})
    centrifugal: bool = field(default=True, metadata={
        "doc": "ball centrifugal force in the quasi-static solve; the dynamic model's inertia always has it, so a dynamic run refuses false"})
    gyroscopic: bool = field(default=True, metadata={
        "doc": "gyroscopic moments: of the balls in the quasi-static solve (race control), of every body in the dynamics"})
    film_formula: str = field(default="nvm", metadata={
        "choices": ("nvm", "hamrock-dowson"), "doc": "central film: Nijenbanning-Venner-Moes or Hamrock-Dowson"})
    min_film: float = field(default=5e-8, metadata={
        "unit": "m", "gt": 0.0, "doc": "floor of the film used by traction (mixed lubrication is not modelled)"})
    dry_friction: float = field(default=0.1, metadata={
        "unit": "-", "ge": 0.0, "le": 1.0, "doc": "ball-race Coulomb coefficient (traction = 'coulomb')"})
    contact_damping_ratio: float = field(default=0.05, metadata={
        "unit": "-", "ge": 0.0, "le": 1.0, "doc": "ball-race normal damping, fraction of critical for a ball on its Hertz stiffness"})
    pocket_friction: float = field(default=0.1, metadata={"unit": "-", "ge": 0.0, "le": 1.0, "doc": "ball-pocket Coulomb coefficient (regularised)"})
    pocket_restitution: float = field(default=0.7, metadata={"unit": "-", "gt": 0.0, "le": 1.0, "doc": "coefficient of restitution of ball-pocket impacts (Hunt-Crossley damping)"})
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
        "unit": "m/s", "gt": 0.0, "doc": "slip speed over which Coulomb friction (traction = 'coulomb') reaches its full value"})


@dataclass(frozen=True)
class Output:
    sample_interval: float = field(default=1e-5, metadata={"unit": "s", "gt": 0.0, "doc": "interval of the saved time series"})
