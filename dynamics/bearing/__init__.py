"""The ball-bearing multibody model (docs/model.md §4–§8) on the general core of
`dynamics.multibody`: races, Z balls and cage, all contacts, the viscoelastic hinge.

`BearingModel` implements the integrator's residual protocol; `simulate_bearing` runs it and
returns a `BearingRun`, whose `channels()` names every saved series. `ModelOptions` is the
scene's `[physics]` table.

The names below load their module on first use, so that the scene loader, which builds
`ModelOptions` from `[physics]`, imports neither numba nor the kernels.
"""

import importlib

_EXPORTS = {
    "BearingModel": ".model", "BearingModelParams": ".params", "BearingRun": ".run",
    "ModelOptions": ".options", "RunSeries": ".run", "build_model_params": ".params",
    "simulate_bearing": ".run",
}
__all__ = sorted(_EXPORTS)


def __getattr__(name):
    if name not in _EXPORTS:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(importlib.import_module(_EXPORTS[name], __name__), name)
    globals()[name] = value
    return value
