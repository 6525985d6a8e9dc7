"""Numerical settings of the HHT-α integrator (docs/model.md §9), validated on construction."""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass, field, fields


class JacobianReuse(enum.Enum):
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
    """HHT-α, Newton and step-control settings. Tolerances, see `step_control.error_norm`:
    `atol` is in the units of the weighted coordinates (m when rotations are weighted by a
    length in m/rad); `newton_tol` is relative to the same scale as the error test."""

    alpha: float = field(default=0.1, metadata={"unit": "-", "ge": 0.0, "le": 1.0 / 3.0})
    first_step: float = field(default=1e-6, metadata={"unit": "s", "gt": 0.0})
    min_step: float = field(default=1e-8, metadata={"unit": "s", "gt": 0.0})
    max_step: float = field(default=2e-6, metadata={"unit": "s", "gt": 0.0})
    rtol: float = field(default=1e-4, metadata={"unit": "-", "ge": 0.0})
    atol: float = field(default=1e-9, metadata={"unit": "m", "gt": 0.0})
    adaptive: bool = field(default=True, metadata={"unit": "-"})
    newton_tol: float = field(default=1e-2, metadata={"unit": "-", "gt": 0.0})
    residual_tol: float = field(default=0.0, metadata={"unit": "N", "ge": 0.0})
    max_newton_iter: int = field(default=8, metadata={"unit": "-", "ge": 1})
    reuse_jacobian: JacobianReuse = field(default=JacobianReuse.ADAPTIVE,
                                          metadata={"unit": "-"})
    refactor_rate: float = field(default=0.3, metadata={"unit": "-", "gt": 0.0, "lt": 1.0})
    refactor_step_ratio: float = field(default=1.5, metadata={"unit": "-", "ge": 1.0})
    safety: float = field(default=0.9, metadata={"unit": "-", "gt": 0.0, "le": 1.0})
    min_factor: float = field(default=0.2, metadata={"unit": "-", "gt": 0.0, "lt": 1.0})
    max_factor: float = field(default=2.0, metadata={"unit": "-", "gt": 1.0})
    newton_failure_factor: float = field(default=0.25, metadata={"unit": "-", "gt": 0.0,
                                                                 "lt": 1.0})

    def __post_init__(self) -> None:
        if isinstance(self.reuse_jacobian, str):
            object.__setattr__(self, "reuse_jacobian", JacobianReuse(self.reuse_jacobian))
        for f in fields(self):
            meta, value = f.metadata, getattr(self, f.name)
            if "unit" not in meta or isinstance(value, (JacobianReuse, bool)):
                continue
            unit = meta["unit"]
            bad = (not math.isfinite(value)
                   or ("gt" in meta and not value > meta["gt"])
                   or ("ge" in meta and not value >= meta["ge"])
                   or ("lt" in meta and not value < meta["lt"])
                   or ("le" in meta and not value <= meta["le"]))
            if bad:
                allowed = ", ".join(f"{k} {meta[k]:.6g}" for k in ("gt", "ge", "lt", "le")
                                    if k in meta)
                raise ValueError(f"solver.{f.name} = {value!r} [{unit}] is out of range; "
                                 f"allowed: {allowed}")
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
