"""The one place the bearing model calls the Eyring traction fast path (MODEL.md §6.4).

Isolated so that the fast path's packing (tables, quadrature rule, scratch) can change
without touching the force kernel.
"""

from __future__ import annotations

import numba

FLAG_NOT_WIRED = 8


@numba.njit(cache=True)
def eyring_traction(a_x, b_y, p_h, h, tau0, du0, dv0, w_s, eta_table, p_step, tr_f, tr_i, tbuf):
    """(F_x, F_y, M_z) on the ball into tbuf[0:3] and d(.)/d(du0, dv0, w_s) into tbuf[3:12];
    returns the fast path's flag."""
    for i in range(12):
        tbuf[i] = 0.0
    return FLAG_NOT_WIRED
