"""Stage 1 (docs/model.md §3): FE identification of the inner-race hinge stiffness.

Public API: FEConfig, RingSeat, identify_hinge, HingeIdentification, read_hinge,
convergence_study, fit_hinge, HingeFit, richardson. Never imports dynamics or pipeline.
Attributes load lazily: reading `FEConfig` (scene validation) must not pay for scipy,
scikit-fem or gmsh.
"""

from __future__ import annotations

import importlib

_ATTRS = {
    "FEConfig": "bearingsim.fe_model.config",
    "HingeFit": "bearingsim.fe_model.hinge_fit",
    "fit_hinge": "bearingsim.fe_model.hinge_fit",
    "HingeIdentification": "bearingsim.fe_model.identify",
    "identify_hinge": "bearingsim.fe_model.identify",
    "read_hinge": "bearingsim.fe_model.artefacts",
    "convergence_study": "bearingsim.fe_model.convergence",
    "richardson": "bearingsim.fe_model.convergence",
    "RingSeat": "bearingsim.meshes.housing",
}

__all__ = sorted(_ATTRS)


def __getattr__(name: str):
    if name in _ATTRS:
        return getattr(importlib.import_module(_ATTRS[name]), name)
    raise AttributeError(f"module 'fe_model' has no attribute {name!r}")
