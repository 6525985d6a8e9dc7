"""The gap between the cage and the land that does not guide it, along a dynamic run.

An outer-guided cage faces the inner ring's land across its bore (an inner-guided one faces the
outer ring's land across its outside diameter). The model applies no force there (docs/model.md
§8.4), so the run is checked instead: at each sample, the gap left at the two ends of the cage's
width, where the inner ring's tilt brings its land closest,

    g(t) = C_n - max over z = ±w_c/2 of | c_xy(t) - (x_i,xy(t) + a_xy(t) / a_z(t) (z_c(t) + z - z_i(t))) |

with c the cage centre, x_i the inner-ring centre and a its axis (the outer ring is fixed and
centred). The cage's own tilt is not recorded and is left out. g < 0: the cage touches it.
"""

from __future__ import annotations

import numpy as np


def non_guiding_gap(cage_position: np.ndarray, inner_position: np.ndarray | None, inner_axis: np.ndarray | None,
                    clearance: float, half_width: float) -> np.ndarray:
    """g(t) [m] of the module docstring; positions (n, 3) [m], axis (n, 3) unit vectors; with no
    inner ring (an inner-guided cage's non-guiding land is the fixed outer ring) pass None."""
    c = np.asarray(cage_position, float)
    if inner_position is None:
        return clearance - np.hypot(c[:, 0], c[:, 1])
    xi, a = np.asarray(inner_position, float), np.asarray(inner_axis, float)
    worst = np.zeros(len(c))
    for z in (-half_width, half_width):
        lever = (c[:, 2] + z - xi[:, 2]) / a[:, 2]
        dx = c[:, 0] - (xi[:, 0] + a[:, 0] * lever)
        dy = c[:, 1] - (xi[:, 1] + a[:, 1] * lever)
        worst = np.maximum(worst, np.hypot(dx, dy))
    return clearance - worst


def non_guiding_summary(t: np.ndarray, gap: np.ndarray, clearance: float) -> dict:
    """Summary keys: the least gap, when, and the fraction of the run with contact."""
    i = int(np.argmin(gap))
    return {"non_guiding_clearance": float(clearance), "non_guiding_gap_min": float(gap[i]),
            "non_guiding_gap_min_time": float(t[i]), "non_guiding_contact_fraction": float(np.mean(gap < 0.0))}
