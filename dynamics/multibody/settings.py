"""Numerical settings of the HHT-α integrator (docs/model.md §9), validated on construction.

The scene's `[solver]` table is built straight into these settings (plus the run's
`duration`, pipeline/scene/sections.py): the field metadata below (unit, range, choices,
doc) is the one definition of every solver key, and docs/scenes.md is generated from it.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass, field

from ..field_checks import check_fields


class JacobianReuse(enum.StrEnum):
    """When the Newton iteration matrix is rebuilt and factored.

    NEWTON: every iteration (full Newton; fewest iterations, most factorisations).
    STEP: once per step (modified Newton).
    ADAPTIVE: kept across iterations and steps while Newton converges fast enough
    (contraction below `HHTSettings.refactor_rate`) and the step changed by less than
    `HHTSettings.refactor_step_ratio`; rebuilt otherwise (the paper's practice).
    """

    NEWTON = "newton"
    STEP = "step"
    ADAPTIVE = "adaptive"


@dataclass(frozen=True)
class HHTSettings:
    """HHT-α, Newton and step-control settings. Tolerances, see `step_control`: each local
    error is held below atol + rtol L_i, L_i the coordinate's physical scale (the problem's
    `error_scales`; |q_i| for a problem without); `atol` is in the units of the weighted
    coordinates (m when rotations are weighted by a length in m/rad); `newton_tol` is relative
    to the same scale as the error test. The step controller sets the step; `max_step` only
    bounds it."""

    alpha: float = field(default=0.1, metadata={
        "unit": "-", "ge": 0.0, "le": 1.0 / 3.0,
        "doc": "HHT-alpha numerical damping (0: trapezoidal rule, with which case b's Newton fails once the cage "
               "rubs its land: the run stops with an error naming this key)"})
    first_step: float = field(default=1e-6, metadata={"unit": "s", "gt": 0.0, "doc": "first time step"})
    min_step: float = field(default=1e-8, metadata={
        "unit": "s", "gt": 0.0, "doc": "smallest step before the run gives up"})
    max_step: float = field(default=1e-4, metadata={
        "unit": "s", "gt": 0.0, "doc": "largest step: a safety bound, the tolerance sets the step"})
    rtol: float = field(default=1e-6, metadata={
        "unit": "-", "ge": 0.0, "lt": 1.0,
        "doc": "tolerance of the step controller, relative to each coordinate's physical scale (for a bearing: "
               "the displacement that changes the coordinate's elastic force by a mean ball load, capped by the "
               "clearances; docs/model.md M.99b)"})
    atol: float = field(default=1e-15, metadata={
        "unit": "m", "gt": 0.0, "doc": "absolute floor of the step controller's tolerance (positions)"})
    error_norm: str = field(default="max", metadata={
        "choices": ("max", "rms"),
        "doc": "how the coordinates' scaled errors are combined: 'max' (the worst coordinate decides, so an "
               "impact shortens the step) or 'rms'"})
    adaptive: bool = field(default=True, metadata={
        "doc": "adapt the step to the error estimate (M.99-M.101); false: fixed steps of first_step"})
    # 0.03: RADAU5's cap on its Newton tolerance (Hairer & Wanner; scipy's Radau and BDF the same);
    # measured on case b's work-precision window: 5 % fewer Newton iterations than 0.01 for the same
    # steps and errors within 1-11 %; 0.1 starts to raise the impact-peak error (docs/model.md M.102)
    newton_tol: float = field(default=3e-2, metadata={
        "unit": "-", "gt": 0.0, "doc": "Newton converges when its position correction, in the error norm, is below this (M.102)"})
    residual_tol: float = field(default=0.0, metadata={
        "unit": "N", "ge": 0.0, "doc": "Newton also converges when max |residual| is below this (0: off)"})
    newton_test: str = field(default="estimate", metadata={
        "choices": ("estimate", "correction"),
        "doc": "Newton's convergence test: 'estimate' stops when the remaining error, estimated from the "
               "contraction rate (Hairer & Wanner), is below newton_tol; 'correction' when the last correction is"})
    predictor: str = field(default="linear", metadata={
        "choices": ("linear", "constant"),
        "doc": "Newton's start for the new acceleration: 'linear' extrapolates the last step's change, "
               "'constant' starts from the old acceleration"})
    max_newton_iter: int = field(default=8, metadata={
        "unit": "-", "ge": 1, "doc": "Newton iterations before the step is rejected"})
    reuse_jacobian: str = field(default=JacobianReuse.ADAPTIVE, metadata={
        "choices": tuple(JacobianReuse),
        "doc": "when the Newton matrix is rebuilt: 'adaptive' keeps it while Newton contracts fast and the "
               "step barely changes, 'step' once per step, 'newton' every iteration"})
    refactor_rate: float = field(default=0.3, metadata={
        "unit": "-", "gt": 0.0, "lt": 1.0, "doc": "('adaptive') rebuild the matrix when Newton contracts by less than this"})
    refactor_step_ratio: float = field(default=3.0, metadata={
        "unit": "-", "ge": 1.0, "doc": "('adaptive') rebuild the matrix when the step changed by more than this factor"})
    safety: float = field(default=0.9, metadata={
        "unit": "-", "gt": 0.0, "le": 1.0, "doc": "safety factor of the step controller (M.101)"})
    min_factor: float = field(default=0.2, metadata={
        "unit": "-", "gt": 0.0, "lt": 1.0, "doc": "smallest change of the step from one step to the next (M.101)"})
    max_factor: float = field(default=2.0, metadata={
        "unit": "-", "gt": 1.0, "doc": "largest change of the step from one step to the next (M.101)"})
    newton_failure_factor: float = field(default=0.25, metadata={
        "unit": "-", "gt": 0.0, "lt": 1.0, "doc": "step reduction after a Newton failure"})

    def __post_init__(self) -> None:
        check_fields(self, "solver")
        object.__setattr__(self, "reuse_jacobian", JacobianReuse(self.reuse_jacobian))
        if not self.min_step <= self.first_step <= self.max_step:
            raise ValueError(
                f"solver steps must satisfy min_step <= first_step <= max_step; got "
                f"{self.min_step:g} <= {self.first_step:g} <= {self.max_step:g} s. "
                "Widen [min_step, max_step] or change first_step."
            )

    @property
    def gamma(self) -> float:
        """Newmark gamma = 1/2 + alpha (docs/model.md §9)."""
        return 0.5 + self.alpha

    @property
    def beta(self) -> float:
        """Newmark beta = (1 + alpha)^2 / 4 (docs/model.md §9)."""
        return 0.25 * (1.0 + self.alpha) ** 2
