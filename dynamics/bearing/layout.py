"""Coordinate layout of the bearing model, ordered for the block-arrow solver.

    ball k (k = 0..Z-1): 6k + (0..2) centre x [m]; 6k + (3..5) integral of the angular
        velocity (a ball's orientation never enters a force: error weight 0), v = omega
        (spatial = material for a sphere)
    border, from NB0 = 6 Z:
        inner race: NB0 + (0..2) centre x [m]; NB0 + (3..5) CRV, v = material Omega;
            row NB0 + 5 (spin about its own axis) is replaced by the prescribed speed
        cage (when modelled): NB0 + (6..8) centre x [m]; NB0 + (9..11) CRV, v = Omega

The outer race is fixed and eliminated (no coordinates).
"""

from __future__ import annotations

import numpy as np

BALL_DOF = 6
RACE_DOF = 6
CAGE_DOF = 6
# offsets inside the border block (the block-arrow matrix's B, E, F)
INNER_BORDER = 0
CAGE_BORDER = RACE_DOF


def ball_offset(k: int) -> int:
    """Global index of ball k's first coordinate."""
    return BALL_DOF * k


def border_size(has_cage: bool) -> int:
    return RACE_DOF + (CAGE_DOF if has_cage else 0)


def n_dof(ball_count: int, has_cage: bool) -> int:
    return BALL_DOF * ball_count + border_size(has_cage)


def inner_offset(ball_count: int) -> int:
    return BALL_DOF * ball_count


def cage_offset(ball_count: int, has_cage: bool) -> int:
    """Global index of the cage's first coordinate, -1 without a cage."""
    return BALL_DOF * ball_count + RACE_DOF if has_cage else -1


def rotation_slots(ball_count: int, has_cage: bool) -> np.ndarray:
    slots = [inner_offset(ball_count) + 3]
    if has_cage:
        slots.append(cage_offset(ball_count, True) + 3)
    return np.array(slots, dtype=np.int64)


def spin_row(ball_count: int) -> int:
    """Row of the inner race's material spin, replaced by the prescribed speed."""
    return inner_offset(ball_count) + 5


def ball_states(x: np.ndarray, ball_count: int) -> np.ndarray:
    """The ball coordinates of q or v (..., n_dof) as (..., Z, BALL_DOF): [..., k, 0:3] centre
    (or its velocity), [..., k, 3:6] rotation integral (or omega). For x contiguous along its
    last axis this is a view: writing to it writes x."""
    return x[..., :BALL_DOF * ball_count].reshape(x.shape[:-1] + (ball_count, BALL_DOF))
