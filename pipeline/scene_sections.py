"""The sections of a scene file (SCENE.md), one frozen dataclass each, SI units.

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

    ball_diameter: float = field(metadata={"unit": "m", "gt": 0.0})
    ball_count: int = field(metadata={"unit": "-", "ge": 3})
    pitch_diameter: float = field(metadata={"unit": "m", "gt": 0.0})
    inner_conformity: float = field(metadata={"unit": "-", "gt": 0.5, "le": 1.0, "doc": "r_i / D"})
    outer_conformity: float = field(metadata={"unit": "-", "gt": 0.5, "le": 1.0, "doc": "r_o / D"})
    diametral_clearance: float = field(
        default=0.0, metadata={"unit": "m", "doc": "unmounted radial play x 2; negative = preload"}
    )
    inner_shoulder_diameter: float | None = field(default=None, metadata={"unit": "m", "gt": 0.0})
    outer_shoulder_diameter: float | None = field(default=None, metadata={"unit": "m", "gt": 0.0})
    inner_bore_diameter: float | None = field(default=None, metadata={"unit": "m", "gt": 0.0})
    outer_outside_diameter: float | None = field(default=None, metadata={"unit": "m", "gt": 0.0})
    width: float | None = field(default=None, metadata={"unit": "m", "gt": 0.0})


@dataclass(frozen=True)
class Materials:
    ball: Material
    race: Material
    cage: Material | None = None


@dataclass(frozen=True)
class Load:
    """Loads on the inner race: axial along +z, radial along +x, moment about +y."""

    axial: float = field(default=0.0, metadata={"unit": "N"})
    radial: float = field(default=0.0, metadata={"unit": "N", "ge": 0.0})
    moment: float = field(default=0.0, metadata={"unit": "N.m"})
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
    inner_rpm: float = field(default=0.0, metadata={"unit": "rev/min"})
    outer_rpm: float = field(default=0.0, metadata={"unit": "rev/min"})

    @property
    def inner(self) -> float:
        """Inner-race speed Omega_i [rad/s] about +z."""
        return self.inner_rpm * 2.0 * math.pi / 60.0

    @property
    def outer(self) -> float:
        return self.outer_rpm * 2.0 * math.pi / 60.0


@dataclass(frozen=True)
class Hinge:
    """Viscoelastic hinge of the inner race (MODEL.md §5); H given or identified by FE."""

    source: str = field(default="none", metadata={"choices": ("fe", "given", "none")})
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
    """Numerical settings of the dynamic stage (MODEL.md §9)."""

    alpha: float = field(default=0.1, metadata={"unit": "-", "ge": 0.0, "le": 1.0 / 3.0, "doc": "HHT"})
    duration: float = field(default=0.8, metadata={"unit": "s", "gt": 0.0})
    first_step: float = field(default=1e-6, metadata={"unit": "s", "gt": 0.0})
    min_step: float = field(default=1e-8, metadata={"unit": "s", "gt": 0.0})
    max_step: float = field(default=2e-6, metadata={"unit": "s", "gt": 0.0})
    rtol: float = field(default=1e-4, metadata={"unit": "-", "gt": 0.0, "lt": 1.0})
    atol: float = field(default=1e-9, metadata={"unit": "m", "gt": 0.0})

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

    ehd_film: bool = True
    traction: str = field(default="eyring", metadata={"choices": ("eyring", "coulomb", "none")})
    cage_race: str = field(default="hybrid", metadata={"choices": ("hybrid", "hydrodynamic", "dry", "none")})
    centrifugal: bool = True
    gyroscopic: bool = True
    film_formula: str = field(default="nvm", metadata={
        "choices": ("nvm", "hamrock-dowson"), "doc": "central film: Nijenbanning-Venner-Moes or Hamrock-Dowson"})
    min_film: float = field(default=5e-8, metadata={
        "unit": "m", "gt": 0.0, "doc": "floor of the film used by traction (mixed lubrication is not modelled)"})
    dry_friction: float = field(default=0.1, metadata={
        "unit": "-", "ge": 0.0, "le": 1.0, "doc": "ball-race Coulomb coefficient (traction = 'coulomb')"})
    contact_damping_ratio: float = field(default=0.05, metadata={
        "unit": "-", "ge": 0.0, "le": 1.0, "doc": "ball-race normal damping, fraction of critical for a ball on its Hertz stiffness"})
    pocket_friction: float = field(default=0.1, metadata={"unit": "-", "ge": 0.0, "le": 1.0})
    pocket_restitution: float = field(default=0.7, metadata={"unit": "-", "gt": 0.0, "le": 1.0})
    cage_race_friction: float = field(default=0.1, metadata={
        "unit": "-", "ge": 0.0, "le": 1.0, "doc": "metal-to-metal friction at the guide land"})
    cage_race_boundary: float = field(default=0.05, metadata={
        "unit": "-", "gt": 0.0, "lt": 1.0, "doc": "epsilon_0: boundary-layer width of the hybrid model / C"})


@dataclass(frozen=True)
class Output:
    sample_interval: float = field(default=1e-5, metadata={"unit": "s", "gt": 0.0})
