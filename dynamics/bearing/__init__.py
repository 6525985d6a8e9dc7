"""The ball-bearing multibody model (docs/model.md §4–§8) on the general core of
`dynamics.multibody`: races, Z balls and cage, all contacts, the viscoelastic hinge.

`BearingModel` implements the integrator's residual protocol; `simulate_bearing` runs it and
returns a `BearingRun`, whose `channels()` names every saved series. `ModelOptions` is the
scene's `[physics]` table.

The names below load their module on first use, so that the scene loader, which builds
`ModelOptions` from `[physics]`, imports neither numba nor the kernels.
"""

from .._lazy import lazy_exports

_EXPORTS = {
    "BearingModel": ".model", "BearingModelParams": ".params", "BearingRun": ".run",
    "ModelOptions": ".options", "RunSeries": ".run", "build_model_params": ".params",
    "simulate_bearing": ".run",
}
__getattr__, __all__ = lazy_exports(__name__, _EXPORTS)
