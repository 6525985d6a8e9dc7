"""A race's contact table: everything about a ball–race contact that depends only on the
contact angle, tabulated once per race on one grid so that the time loop interpolates
instead of recomputing (docs/model.md §6.2–§6.3).

Columns, each a (value, slope per rad) pair for cubic Hermite interpolation
(`contact.hertz.hermite` at `contact.hertz.table_position`):

    0 .. TABLE_COLUMNS - 1     Hertz: k_h, kappa, c_a, c_b (`contact.hertz.build_hertz_table`)
    TAB_FILM ..                film: R_x and the lambda-only NVM terms (`film_laws.nvm.geometry_terms`)
    TAB_SEMI_AXES ..           semi-axes per sqrt(delta): c_a k_h^(1/3), c_b k_h^(1/3) [m^(1/2)]
"""

from __future__ import annotations

import math

import numba
import numpy as np

from .._speed.compile_policy import NO_REFCOUNT
from ..contact.hertz import (
    TAB_CA, TAB_CB, TAB_DCA, TAB_DCB, TAB_DKH, TAB_KH, TABLE_COLUMNS, race_hertz_table,
)
from ..lubrication.film_laws.nvm import geometry_terms as nvm_geometry_terms

TAB_FILM = TABLE_COLUMNS  # first film column
N_FILM_TERMS = 6          # R_x and the five terms of film_laws.nvm.geometry_terms
TAB_SEMI_AXES = TAB_FILM + 2 * N_FILM_TERMS  # c_a k_h^(1/3), then c_b k_h^(1/3)


def curvature_radii(alpha, is_outer, D, d_m, r):
    """(R_x, R_y) [m] of a ball-race contact at contact angle alpha (docs/model.md M.58)."""
    c = math.cos(alpha)
    rho_ii1 = -2.0 * c / (d_m + D * c) if is_outer else 2.0 * c / (d_m - D * c)
    return 1.0 / (2.0 / D + rho_ii1), 1.0 / (2.0 / D - 1.0 / r)


curvature_radii_kernel = numba.njit(**NO_REFCOUNT)(curvature_radii)


def film_geometry_columns(D: float, d_m: float, r: float, is_outer: bool, n_nodes: int) -> np.ndarray:
    """R_x and the lambda-only NVM terms of `film_laws.nvm.geometry_terms` on the table's grid, so
    that the time loop's film needs no cosine and no lambda logarithms (a fifth of its cost per
    contact). Slopes by central differences (step 1e-6 rad; Hermite error then ~1e-9 relative)."""
    alpha = np.linspace(0.0, 0.5 * math.pi, n_nodes)
    step = 1e-6

    def row(a):
        Rx, Ry = curvature_radii(a, is_outer, D, d_m, r)
        return np.array([Rx, *nvm_geometry_terms(Rx, Ry)])

    out = np.empty((n_nodes, 2 * N_FILM_TERMS))
    for i, a in enumerate(alpha):
        out[i, 0::2] = row(a)
        out[i, 1::2] = (row(a + step) - row(a - step)) / (2.0 * step)
    return out


def semi_axis_columns(hertz: np.ndarray) -> np.ndarray:
    """a/sqrt(delta) = c_a k_h^(1/3) and b/sqrt(delta) = c_b k_h^(1/3) [m^(1/2)] with their
    slopes (Hertz, M.61: a = c_a F^(1/3) and F = k_h delta^(3/2)), so that the time loop
    needs no cube root per contact."""
    k13 = np.cbrt(hertz[:, TAB_KH])
    dk13 = hertz[:, TAB_DKH] * k13 / (3.0 * hertz[:, TAB_KH])
    out = np.empty((hertz.shape[0], 4))
    for c, (col, dcol) in enumerate(((TAB_CA, TAB_DCA), (TAB_CB, TAB_DCB))):
        out[:, 2 * c] = hertz[:, col] * k13
        out[:, 2 * c + 1] = hertz[:, dcol] * k13 + hertz[:, col] * dk13
    return out


def race_contact_table(bearing, e_eff: float, outer: bool) -> np.ndarray:
    """The contact table of the inner or outer race of `bearing` (dynamics.geometry.BearingGeometry),
    E' = e_eff [Pa]: Hertz, film and semi-axis columns (module docstring)."""
    hertz = race_hertz_table(bearing, e_eff, outer=outer)
    r = bearing.outer_groove_radius if outer else bearing.inner_groove_radius
    film = film_geometry_columns(bearing.ball_diameter, bearing.pitch_diameter, r, outer, hertz.shape[0])
    return np.ascontiguousarray(np.hstack([hertz, film, semi_axis_columns(hertz)]))
