"""The sections of a scene file (docs/scenes.md), one frozen dataclass each, SI units.

Physical sections (`[bearing]`, `[cage]`, `[materials]`) and the settings the dynamics take
(`[physics]`, the integrator's part of `[solver]`) reuse the dynamics' own types; the ones
below are the scene-only sections. Field metadata gives unit and range; the generic builder
in `pipeline.scene.schema` enforces them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from ...dynamics.bearing.options import ModelOptions
from ...dynamics.geometry import Material
from ...dynamics.multibody.settings import HHTSettings


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
    inner_shoulder_diameter: float | tuple[float, float] | None = field(default=None, metadata={
        "unit": "m", "gt": 0.0, "length": 2,
        "doc": "inner-ring land diameter: one value, or [side toward +z, side toward -z]"})
    outer_shoulder_diameter: float | tuple[float, float] | None = field(default=None, metadata={
        "unit": "m", "gt": 0.0, "length": 2,
        "doc": "outer-ring land diameter: one value, or [side toward +z, side toward -z]"})
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


# `[physics]` is built straight into the model's options: each key is defined once, with its
# unit, range and doc, in dynamics/bearing/options.py (the quasi-static stage reads
# `centrifugal` and `gyroscopic` from it too).
Physics = ModelOptions


@dataclass(frozen=True)
class SolverSettings(HHTSettings):
    """`[solver]`: the integrator's settings (dynamics/multibody/settings.py, docs/model.md §9),
    passed to it as they are, plus the length of the run."""

    duration: float = field(default=0.8, metadata={"unit": "s", "gt": 0.0, "doc": "simulated time"})

    def __post_init__(self) -> None:
        super().__post_init__()
        if self.max_step > self.duration:
            raise ValueError(
                f"max_step = {self.max_step:g} s exceeds duration = {self.duration:g} s"
            )


@dataclass(frozen=True)
class Thermal:
    """`[thermal]`: part temperatures for the operating geometry (docs/model.md §2.1). Scene
    dimensions hold at `reference_degC`; each part grows with its own temperature. A part whose
    temperature is not given takes `parts_degC`, whose default is the lubricant's operating
    temperature (parts and oil in equilibrium; without a lubricant, the reference temperature)."""

    reference_degC: float = field(default=20.0, metadata={
        "unit": "degC", "ge": -100.0, "le": 350.0,
        "doc": "temperature at which the scene's dimensions hold (ISO 1: 20 °C)"})
    parts_degC: float | None = field(default=None, metadata={
        "unit": "degC", "ge": -100.0, "le": 350.0,
        "doc": "temperature of every part not given below; default lubricant.temperature_degC, "
               "which must then lie in this range (reference_degC without a [lubricant])"})
    inner_ring_degC: float | None = field(default=None, metadata={
        "unit": "degC", "ge": -100.0, "le": 350.0, "doc": "inner-ring temperature; default parts_degC"})
    outer_ring_degC: float | None = field(default=None, metadata={
        "unit": "degC", "ge": -100.0, "le": 350.0, "doc": "outer-ring temperature; default parts_degC"})
    ball_degC: float | None = field(default=None, metadata={
        "unit": "degC", "ge": -100.0, "le": 350.0, "doc": "ball temperature; default parts_degC"})
    cage_degC: float | None = field(default=None, metadata={
        "unit": "degC", "ge": -100.0, "le": 350.0, "doc": "cage temperature; default parts_degC"})


@dataclass(frozen=True)
class Output:
    sample_interval: float = field(default=1e-5, metadata={"unit": "s", "gt": 0.0, "doc": "interval of the saved time series"})
    figures: bool = field(default=True, metadata={"doc": "draw the PNG figures of the quasistatic and simulate stages; false skips them (results are the same; sweeps: [sweep] figures = false)"})
    paraview_frames: int = field(default=200, metadata={"unit": "-", "ge": 0, "le": 10000, "doc": "frames of the ParaView motion series the report stage writes (report/paraview/, docs/outputs.md): the run's samples thinned to at most this many; 0 writes none"})
