"""The model choices of a quasi-static solve (docs/model.md §10), apart from its loads
(`dynamics.operating_point.OperatingPoint`) and its numerical settings."""

from __future__ import annotations

from dataclasses import dataclass

RACE_CONTROLS = ("outer", "inner")
KINEMATICS = ("exact", "linear")


@dataclass(frozen=True)
class QuasiStaticOptions:
    """centrifugal: ball centrifugal force m_b ω_c² r at the cage speed ω_c. gyroscopic: the
    gyroscopic moment J_b ω_c ω_r (Jones) is resisted by friction at the controlling race
    (race_control "outer" | "inner", λ = 2 there, 0 at the other). kinematics: "exact" (rigid
    rotation of the inner race; moment arms include the tilt-induced axial offset of the
    groove) or "linear" (small-rotation Jones / ISO/TS 16281 form; differs by O(θ cot α) in the
    moment balance). contact_constants: (k_i, k_o) [N/m^1.5] to replace the exact α-dependent
    Hertz constants (for comparisons with references that used fixed values)."""

    centrifugal: bool = True
    gyroscopic: bool = False
    race_control: str = "outer"
    kinematics: str = "exact"
    contact_constants: tuple[float, float] | None = None

    def __post_init__(self) -> None:
        if self.kinematics not in KINEMATICS:
            raise ValueError(f"kinematics = {self.kinematics!r}: allowed values are 'exact' and 'linear'")
        if self.race_control not in RACE_CONTROLS:
            raise ValueError(f"race_control = {self.race_control!r}: allowed values are 'outer' and 'inner'")
