"""The ball-bearing multibody model (docs/model.md §4–§8) on the general core of
`dynamics.multibody`: races, Z balls and cage, all contacts, the viscoelastic hinge.

`BearingModel` implements the integrator's residual protocol; `simulate_bearing` runs it.
"""

from .model import BearingModel
from .params import BearingModelParams, ModelOptions, build_model_params
from .run import BearingRun, simulate_bearing

__all__ = ["BearingModel", "BearingModelParams", "BearingRun", "ModelOptions",
           "build_model_params", "simulate_bearing"]
