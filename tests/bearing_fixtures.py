"""Small helpers shared by the bearing-model tests: the reference bearing (docs/model.md §2)
built directly from dynamics types, so these tests do not depend on the pipeline."""

from __future__ import annotations

import math

import numpy as np

from bearingsim.dynamics.bearing import ModelOptions, build_model_params
from bearingsim.dynamics.geometry import BearingGeometry, CageGeometry, Material
from bearingsim.dynamics.operating_point import OperatingPoint
from bearingsim.dynamics.quasistatic.options import QuasiStaticOptions
from bearingsim.dynamics.quasistatic.solver import solve_quasistatic
from bearingsim.dynamics.quasistatic.result import initial_state

STEEL = Material(208e9, 0.3, 7850.0)
BRONZE = Material(110e9, 0.34, 8800.0)
REFERENCE = BearingGeometry(0.01905, 22, 0.1584, 0.1573, 0.009753, 0.009906, 0.150, 0.166,
                            0.130, 0.196, 0.034)
REFERENCE_CAGE = CageGeometry(0.158, 0.02023, 0.00742, 0.0254, "outer")
INNER_SPEED = 3060.0 * 2.0 * math.pi / 60.0


def reference_model(moment=430.0, axial=34000.0, radial=0.0, options=ModelOptions(traction="coulomb", cage_race="dry"),
                    lubricant=None, hinge=True, cage=True, gyroscopic=True):
    """(params, start) of the reference bearing; dry by default (no lubricant needed)."""
    loads = OperatingPoint(axial=axial, radial=radial, moment=moment, inner_speed=INNER_SPEED)
    qs = solve_quasistatic(REFERENCE, STEEL, STEEL, loads, QuasiStaticOptions(gyroscopic=gyroscopic))
    start = initial_state(qs)
    H = (np.diag([1e9, 1e9, 1e9]), np.array([1e5, 1e5]), 1e-6) if hinge else None
    params = build_model_params(
        REFERENCE, REFERENCE_CAGE if cage else None, STEEL, STEEL, BRONZE, lubricant, loads,
        hinge=H, static_frame=(start["inner_race_displacement"], start["inner_race_rotation"]), options=options)
    return params, start
