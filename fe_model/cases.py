"""The perturbation load cases of stage 1 and what a solve of them hands to the fit
(docs/model.md §3): shared by the parametric models (fe_model.identify) and the mesh model
(fe_model.mesh_model)."""

from __future__ import annotations

import pathlib
from dataclasses import dataclass
from typing import Callable

import numpy as np

from .config import FEConfig

LOAD_AXES = (("fx", 0), ("fy", 1), ("fz", 2), ("mx", 3), ("my", 4))


@dataclass
class _Solved:
    loads: np.ndarray  # (n, 6)
    responses: np.ndarray  # (n, 6)
    groups: np.ndarray  # (n,) magnitude index
    names: list
    mesh_stats: dict
    timings: dict
    write_case: Callable[[pathlib.Path, int], None]  # .vtu of case k
    displacements: np.ndarray | None = None  # (3N, n), 3-D model only


def load_cases(config: FEConfig) -> tuple[np.ndarray, np.ndarray, list[str]]:
    """All perturbation cases: (n, 6) loads [N, N*m], magnitude-set label, case names."""
    loads, groups, names = [], [], []
    for axis_name, axis in LOAD_AXES:
        values = config.perturbation_forces if axis < 3 else config.perturbation_moments
        for k, value in enumerate(values):
            row = np.zeros(6)
            row[axis] = value
            loads.append(row)
            groups.append(k)
            names.append(f"{axis_name}_{value:+g}")
    return np.array(loads), np.array(groups), names


