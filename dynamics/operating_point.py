"""The operating point of a bearing: the loads on its inner race and the speeds of its races
(docs/model.md §10 for the quasi-static solve, §4 for the dynamic model), in SI units."""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass


@dataclass(frozen=True)
class OperatingPoint:
    """Loads on the inner race and race speeds: axial [N] along +z, radial [N] along +x,
    moment [N·m] about +y; inner_speed, outer_speed [rad/s] about +z."""

    axial: float = 0.0
    radial: float = 0.0
    moment: float = 0.0
    inner_speed: float = 0.0
    outer_speed: float = 0.0

    def __post_init__(self) -> None:
        for name, value in asdict(self).items():
            if not math.isfinite(value):
                raise ValueError(f"{name} = {value}: must be a finite number (N, N·m or rad/s)")
