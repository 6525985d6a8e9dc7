"""The one place the bearing model calls the Eyring traction fast path (MODEL.md §6.4).

Isolated so that the fast path's packing (tables, quadrature rule, scratch) can change
without touching the force kernel.
"""

from __future__ import annotations

import numba

from dynamics._kernel_options import NO_REFCOUNT
from dynamics.traction_fast import traction_fast


@numba.njit(**NO_REFCOUNT)
def eyring_traction(a_x, b_y, p_h, h, tau0, du0, dv0, w_s, eta_table, p_step, rule, work, iwork, tbuf, jacobian):
    """(F_x, F_y, M_z) on the ball into tbuf[0:3] and (jacobian) d(.)/d(du0, dv0, w_s) into
    tbuf[3:12], else zeros there; a_x along the entrainment direction. Returns the fast
    path's flag bits."""
    return traction_fast(a_x, b_y, p_h, h, tau0, du0, dv0, w_s, eta_table, p_step, rule, work, iwork, tbuf, jacobian)
