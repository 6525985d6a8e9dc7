"""What the kernels call of a traction law: `stress_scale`, `response` (film laws) and
`dry_traction` (laws without film), each resolved by numba, from the class of the law's bundle,
to the function of that name in the law's module (`LAWS`, `dynamics.registry`). Called from
Python they do the same lookup."""

from __future__ import annotations

from numba.extending import overload

from . import LAWS


def stress_scale(law, p_h):
    """The law's stress scale tau_s [Pa] at maximum Hertz pressure p_h [Pa] (tau = tau_s g s)."""
    return LAWS.kernel(type(law), "stress_scale")(law, p_h)


def response(law, k, r):
    """(g, c) of a film law at k = eta/(tau_s h) [s/m], r = |s| [m/s]: tau = tau_s g s and
    d tau/d s = tau_s (g I + c s s^T)."""
    return LAWS.kernel(type(law), "response")(law, k, r)


def dry_traction(law, F_n, a, b, du0, dv0, w_s, out):
    """A law without film: out[0:3] = (F_x, F_y, M_z) on the ball, out[3:12] their Jacobian in
    (du0, dv0, w_s), row-major (units as `traction.fast.traction_fast`)."""
    return LAWS.kernel(type(law), "dry_traction")(law, F_n, a, b, du0, dv0, w_s, out)


@overload(stress_scale, inline="always")
def _stress_scale(law, p_h):
    function = LAWS.kernel(law, "stress_scale")
    return lambda law, p_h: function(law, p_h)


@overload(response, inline="always")
def _response(law, k, r):
    function = LAWS.kernel(law, "response")
    return lambda law, k, r: function(law, k, r)


@overload(dry_traction, inline="always")
def _dry_traction(law, F_n, a, b, du0, dv0, w_s, out):
    function = LAWS.kernel(law, "dry_traction")
    return lambda law, F_n, a, b, du0, dv0, w_s, out: function(law, F_n, a, b, du0, dv0, w_s, out)
