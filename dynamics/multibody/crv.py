"""Conformal rotation vector (CRV) kinematics, docs/model.md §4 (M.4a–d).

The CRV is `c = 4 tan(phi/4) n` (M.4a). `|c| <= 4` covers every rotation with `|phi| <= pi`;
beyond it the rescaled vector `c* = -16 c / (c.c)` (phi -> phi - 2 pi) describes the same
rotation. References: Bauchau & Trainelli, "The vectorial parameterization of rotation",
Nonlinear Dynamics 32 (2003) 71–92; Bauchau, "Flexible Multibody Dynamics" (Springer 2011),
§13.6 (Wiener–Milenkovic parameters).

How the integrator uses it (the "allowed alternative" of §4): each body's orientation is
stored as a CRV and advanced multiplicatively, `R_{n+1} = R_n R(dc)`, where the increment
`dc` is the CRV of the material rotation increment of the Newmark update. Composition goes
through Euler parameters and picks the sign with `e0 >= 0`, which is exactly the rescaling
`c* = -16 c/(c.c)`: the stored CRV never leaves `|c| <= 4`. Angular velocities are the
material `Omega` of (M.4d), so no rate has to be remapped when the CRV is rescaled; for
models that integrate `c_dot` directly, `crv_rescale` maps the rate consistently.

All kernels are pure functions of contiguous float64 arrays (dimensionless CRV, rad, rad/s).
"""

from __future__ import annotations

import math

import numba
import numpy as np

from .._speed.compile_policy import KERNEL

# Below this |theta| [rad] the series of 4 tan(x/4)/x is used (its next term is x^4/1280).
_SMALL_ANGLE = 1e-4


@numba.njit(**KERNEL)
def skew(a):
    """Skew-symmetric matrix a~ with a~ b = a x b (3x3)."""
    s = np.zeros((3, 3))
    s[0, 1] = -a[2]
    s[0, 2] = a[1]
    s[1, 0] = a[2]
    s[1, 2] = -a[0]
    s[2, 0] = -a[1]
    s[2, 1] = a[0]
    return s


@numba.njit(**KERNEL)
def crv_c0(c):
    """Scalar part c0 = 2 - c.c/8 of the CRV (M.4a), dimensionless."""
    return 2.0 - (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) / 8.0


@numba.njit(**KERNEL)
def crv_to_matrix(c):
    """Rotation matrix R(c) = I + 2 (c0 c~ + c~ c~) / (4 - c0)^2 (M.4b)."""
    R = np.empty((3, 3))
    crv_to_matrix_into(c, R)
    return R


@numba.njit(**KERNEL)
def crv_to_matrix_into(c, R):
    """`crv_to_matrix` written into R (3x3): no allocation, for kernels without reference counting."""
    c0 = crv_c0(c)
    ct = ((0.0, -c[2], c[1]), (c[2], 0.0, -c[0]), (-c[1], c[0], 0.0))  # c~, as `skew`
    f = 2.0 / (4.0 - c0) ** 2
    for i in range(3):
        for j in range(3):  # (c~ c~)_ij = c_i c_j - |c|^2 delta_ij, no BLAS call for 3x3
            R[i, j] = f * (c0 * ct[i][j] + c[i] * c[j])
        R[i, i] += 1.0 - f * (c[0] * c[0] + c[1] * c[1] + c[2] * c[2])


@numba.njit(**KERNEL)
def crv_H(c):
    """Tangent operator H(c) with spatial omega = H c_dot (M.4c), 3x3."""
    c0 = crv_c0(c)
    f = 2.0 / (4.0 - c0) ** 2
    return f * (c0 * np.eye(3) + skew(c) + np.outer(c, c) / 4.0)


@numba.njit(**KERNEL)
def crv_H_inv(c):
    """Inverse tangent operator H^-1 = (c0 I - c~ + c c^T/4) / 2 (M.4d), 3x3."""
    c0 = crv_c0(c)
    return 0.5 * (c0 * np.eye(3) - skew(c) + np.outer(c, c) / 4.0)


@numba.njit(**KERNEL)
def crv_to_quaternion(c):
    """Euler parameters (e0, e1, e2, e3) of the CRV: e0 = c0/(4-c0), e = c/(4-c0).

    From M.4a with t = tan(phi/4): cos(phi/2) = (1-t^2)/(1+t^2) = c0/(4-c0) and
    sin(phi/2) n = 2t/(1+t^2) n = c/(4-c0).
    """
    c0 = crv_c0(c)
    d = 4.0 - c0
    e = np.empty(4)
    e[0] = c0 / d
    e[1] = c[0] / d
    e[2] = c[1] / d
    e[3] = c[2] / d
    return e


@numba.njit(**KERNEL)
def quaternion_to_crv(e):
    """CRV c = 4 e / (1 + e0) of unit Euler parameters, taking the sign with e0 >= 0.

    Choosing e0 >= 0 (|phi| <= pi) is the rescaling c* = -16 c/(c.c) of §4: |c| <= 4.
    """
    s = 1.0 if e[0] >= 0.0 else -1.0
    f = 4.0 / (1.0 + s * e[0])
    c = np.empty(3)
    c[0] = f * s * e[1]
    c[1] = f * s * e[2]
    c[2] = f * s * e[3]
    return c


@numba.njit(**KERNEL)
def crv_from_rotation_vector(theta):
    """CRV of the rotation vector theta = phi n [rad]: c = 4 tan(phi/4) n (M.4a)."""
    phi = math.sqrt(theta[0] ** 2 + theta[1] ** 2 + theta[2] ** 2)
    if phi < _SMALL_ANGLE:
        f = 1.0 + phi * phi / 48.0
    else:
        f = 4.0 * math.tan(phi / 4.0) / phi
    return f * theta


@numba.njit(**KERNEL)
def crv_to_rotation_vector(c):
    """Rotation vector phi n [rad] of the CRV: phi = 4 atan(|c|/4) (inverse of M.4a)."""
    nc = math.sqrt(c[0] ** 2 + c[1] ** 2 + c[2] ** 2)
    if nc < 4.0 * _SMALL_ANGLE:
        f = 1.0 - nc * nc / 48.0
    else:
        f = 4.0 * math.atan(nc / 4.0) / nc
    return f * c


@numba.njit(**KERNEL)
def crv_compose(p, q):
    """CRV r of R(r) = R(p) R(q) (apply q first, in the frame of p), rescaled to |r| <= 4."""
    a = crv_to_quaternion(p)
    b = crv_to_quaternion(q)
    e = np.empty(4)
    e[0] = a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3]
    e[1] = a[0] * b[1] + b[0] * a[1] + a[2] * b[3] - a[3] * b[2]
    e[2] = a[0] * b[2] + b[0] * a[2] + a[3] * b[1] - a[1] * b[3]
    e[3] = a[0] * b[3] + b[0] * a[3] + a[1] * b[2] - a[2] * b[1]
    # Renormalise: keeps |e| = 1 to round-off over millions of compositions.
    n = math.sqrt(e[0] ** 2 + e[1] ** 2 + e[2] ** 2 + e[3] ** 2)
    return quaternion_to_crv(e / n)


@numba.njit(**KERNEL)
def crv_rescale(c, c_dot):
    """Rescale a CRV past |c| = 4 and map its rate: c* = -16 c/(c.c), c*_dot = (dc*/dc) c_dot.

    dc*/dc = -(16/(c.c)) (I - 2 c c^T/(c.c)). The spatial angular velocity H(c) c_dot is
    unchanged by the map (tested). Returns (c*, c*_dot); unchanged when |c| <= 4.
    """
    cc = c[0] ** 2 + c[1] ** 2 + c[2] ** 2
    if cc <= 16.0:
        return c.copy(), c_dot.copy()
    f = -16.0 / cc
    cd = c[0] * c_dot[0] + c[1] * c_dot[1] + c[2] * c_dot[2]
    return f * c, f * (c_dot - 2.0 * cd / cc * c)


@numba.njit(cache=True, inline="always")
def _quaternion_of(c0, c1, c2):
    """`crv_to_quaternion` on scalars (same arithmetic), for the allocation-free update."""
    s0 = 2.0 - (c0 * c0 + c1 * c1 + c2 * c2) / 8.0
    d = 4.0 - s0
    return s0 / d, c0 / d, c1 / d, c2 / d


@numba.njit(**KERNEL)
def update_configuration(q_n, dq, rotation_slots, q_out):
    """Configuration update q_{n+1} = q_n (+) dq, in place into q_out.

    Additive for every coordinate except the CRV triples starting at `rotation_slots`, where
    dq holds the material rotation increment [rad] and R(c_{n+1}) = R(c_n) R(crv(dq)).
    The arithmetic of `crv_from_rotation_vector` and `crv_compose`, on scalars: this runs in
    every Newton iteration, inside the time loop that works without numba's reference counting
    (dynamics/_speed/compile_policy.py), where a small array per call cost more than the sums.
    """
    for i in range(q_n.shape[0]):
        q_out[i] = q_n[i] + dq[i]
    for k in range(rotation_slots.shape[0]):
        j = rotation_slots[k]
        t0, t1, t2 = dq[j], dq[j + 1], dq[j + 2]
        phi = math.sqrt(t0 ** 2 + t1 ** 2 + t2 ** 2)
        f = 1.0 + phi * phi / 48.0 if phi < _SMALL_ANGLE else 4.0 * math.tan(phi / 4.0) / phi
        a0, a1, a2, a3 = _quaternion_of(q_n[j], q_n[j + 1], q_n[j + 2])
        b0, b1, b2, b3 = _quaternion_of(f * t0, f * t1, f * t2)
        e0 = a0 * b0 - a1 * b1 - a2 * b2 - a3 * b3
        e1 = a0 * b1 + b0 * a1 + a2 * b3 - a3 * b2
        e2 = a0 * b2 + b0 * a2 + a3 * b1 - a1 * b3
        e3 = a0 * b3 + b0 * a3 + a1 * b2 - a2 * b1
        n = math.sqrt(e0 ** 2 + e1 ** 2 + e2 ** 2 + e3 ** 2)  # renormalised, as crv_compose
        e0, e1, e2, e3 = e0 / n, e1 / n, e2 / n, e3 / n
        sign = 1.0 if e0 >= 0.0 else -1.0
        g = 4.0 / (1.0 + sign * e0)
        q_out[j] = g * sign * e1
        q_out[j + 1] = g * sign * e2
        q_out[j + 2] = g * sign * e3
