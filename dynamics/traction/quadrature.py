"""Isothermal traction of an EHD point contact, by quadrature (docs/model.md §6.4): the reference
the fast engine is tested against, for every film law of `dynamics.traction.laws`.

Local shear stress (§6.4), uniform film h (the central film, §6.3), Hertzian pressure
p(x, y) = p_h sqrt(1 - (x/a)^2 - (y/b)^2), local low-shear viscosity eta(p) from
`dynamics.lubrication.rheology`; for the Eyring law (the default)::

    tau = tau0 asinh(eta(p) |s| / (tau0 h)) s/|s|,   s = (du0 - w_s y, dv0 + w_s x)

x is the entrainment direction (semi-axis a), y across it (semi-axis b), w_s the spin
(ball minus race, along the contact normal z). (du0, dv0) is the sliding velocity of the
ball relative to the race at the contact centre. The groove-curvature (Heathcote) term of
the sliding field is omitted: it is second order in y/R and the spec leaves it optional.

Sign convention: the kernels return the force and moment the film exerts ON THE BALL
(the body whose velocity exceeds the race's by s): F = -int tau dA, M_z = -int (x tau_y -
y tau_x) dA, both opposing the slip. The race receives the opposite.

Quadrature (§6.4): x = a rho cos(t), y = b rho sin(t), u = sqrt(1 - rho^2) so that
dA = a b u du dt and p = p_h u exactly; Gauss-Legendre in u on [0, 1] times the uniform
(periodic trapezoid) rule in t. The integrand is analytic in the slip vector
(asinh(k r)/r is even and analytic in r), so the rule converges quickly; near a spin pole
inside the ellipse the Eyring field varies on the scale tau0 h/(eta |w_s|), which sets how
fine the grid must be (tests check convergence).

The same grid kernel also returns the Jacobian d(F_x, F_y, M_z)/d(du0, dv0, w_s) for the
Newton matrix, analytically.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from .._speed.compile_policy import KERNEL
from ..lubrication import rheology
from . import inlet
from .laws import eyring, operations

@numba.njit(**KERNEL)
def traction_on_grid(a, b, h, tau0, du0, dv0, w_s, eta_u, grid, law, inlet_scale=math.inf):
    """Traction force, spin moment and Jacobian on a polar quadrature grid (docs/model.md §6.4).

    a, b [m] semi-axes (x = entrainment), h [m] film, tau0 [Pa] the law's stress scale (the
    Eyring stress, or tau_L: `laws.operations.stress_scale`), du0, dv0 [m/s] sliding velocity (ball -
    race) at the centre, w_s [rad/s] spin, law: a film law's bundle (`laws`). eta_u[i] =
    eta(p_h u_i) [Pa.s]; grid = (u_weight, cos_t, sin_t, rho_u), contiguous float64:
    u_weight[i] = w_i u_i (Gauss weight times the Jacobian u), cos_t/sin_t of the uniform
    angles, rho_u[i] = sqrt(1 - u_i^2); inlet_scale [s/m]: the film's inlet elasticity
    (`traction.inlet.inlet_scale`; inf: the viscous law alone). Returns (F_x, F_y, M_z, J) with
    F [N], M_z [N.m] on the ball and J[3, 3] = d(F_x, F_y, M_z)/d(du0, dv0, w_s).
    """
    u_weight, cos_t, sin_t, rho_u = grid
    n_t = cos_t.shape[0]
    area = a * b * 2.0 * math.pi / n_t
    Fx = 0.0
    Fy = 0.0
    Mz = 0.0
    J = np.zeros((3, 3))
    for i in range(eta_u.shape[0]):
        k = eta_u[i] / (tau0 * h)
        wi = area * u_weight[i] * tau0
        for j in range(n_t):
            x = a * rho_u[i] * cos_t[j]
            y = b * rho_u[i] * sin_t[j]
            sx = du0 - w_s * y
            sy = dv0 + w_s * x
            r = math.sqrt(sx * sx + sy * sy)
            g, c = operations.response(law, k, r)
            if inlet_scale < math.inf:
                exponent = inlet_scale * inlet.travel(rho_u[i] * cos_t[j], rho_u[i] * sin_t[j]) / max(g, inlet.G_FLOOR)
                fg, fc = inlet.factors(exponent, math.exp(-exponent))
                g, c = g * fg, c * fc
            tx = g * sx
            ty = g * sy
            Fx -= wi * tx
            Fy -= wi * ty
            Mz -= wi * (x * ty - y * tx)
            # A = g I + c s s^T;  ds/dq = [[1, 0, -y], [0, 1, x]]
            axx = g + c * sx * sx
            axy = c * sx * sy
            ayy = g + c * sy * sy
            dtx_dw = -axx * y + axy * x
            dty_dw = -axy * y + ayy * x
            J[0, 0] -= wi * axx
            J[0, 1] -= wi * axy
            J[0, 2] -= wi * dtx_dw
            J[1, 0] -= wi * axy
            J[1, 1] -= wi * ayy
            J[1, 2] -= wi * dty_dw
            J[2, 0] -= wi * (x * axy - y * axx)
            J[2, 1] -= wi * (x * ayy - y * axy)
            J[2, 2] -= wi * (x * dty_dw - y * dtx_dw)
    return Fx, Fy, Mz, J


def quadrature_grid(n_u: int, n_theta: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(u, u_weight, rho_u, cos_t, sin_t) of the polar rule: Gauss-Legendre on [0,1] x uniform t.

    Angles sit at t_j = 2 pi (j + 1/2)/n_theta so that no node lies on a symmetry axis.
    """
    if n_u < 1 or n_theta < 2:
        raise ValueError(f"quadrature grid n_u = {n_u}, n_theta = {n_theta}: need n_u >= 1, n_theta >= 2.")
    xg, wg = np.polynomial.legendre.leggauss(n_u)
    u = 0.5 * (xg + 1.0)
    u_weight = 0.5 * wg * u
    t = 2.0 * np.pi * (np.arange(n_theta) + 0.5) / n_theta
    return (u, np.ascontiguousarray(u_weight), np.sqrt(1.0 - u * u), np.cos(t), np.sin(t))


def traction_quadrature(
    a: float, b: float, p_h: float, h: float, shear, model: int, params: np.ndarray,
    du0: float, dv0: float, w_s: float, grid: tuple[int, int] = (48, 256),
    elastic: tuple[float, float] = (math.inf, 0.0),
) -> tuple[float, float, float, np.ndarray]:
    """Reference traction (F_x [N], F_y [N], M_z [N.m], J[3,3]) on the ball (docs/model.md §6.4).

    a, b [m], p_h [Pa] maximum Hertz pressure, h [m] central film; shear: the Eyring stress
    tau0 [Pa] of the Eyring law, or the bundle of any film law of `laws`; rheology `model`/`params` from `Lubricant.model_code` /
    `rheology_params()`, du0, dv0 [m/s], w_s [rad/s]; grid = (n_u, n_theta); elastic = (G [Pa],
    u [m/s]): the film's shear modulus and mean surface speed for its inlet elasticity
    (`traction.inlet`; the default, the viscous law alone). The default grid (48 x 256) is converged
    to < 1e-4 relative over the operating range of the reference scene (tests/test_traction.py).
    """
    law = eyring.Eyring(float(shear)) if np.ndim(shear) == 0 else shear
    u, u_weight, rho_u, cos_t, sin_t = quadrature_grid(*grid)
    eta_u = rheology.viscosity_array(p_h * u, model, params)
    stress = operations.stress_scale(law, p_h)
    scale = inlet.inlet_scale(float(elastic[0]), a, float(elastic[1]), stress, h)
    return traction_on_grid(a, b, h, stress, du0, dv0, w_s, eta_u, (u_weight, cos_t, sin_t, rho_u), law, scale)
