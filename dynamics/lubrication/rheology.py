"""Low-shear viscosity of the lubricant versus pressure and temperature (docs/model.md §6.4).

Three models, each a pure numba kernel in SI units (Pa, K, Pa.s):

- Barus: ``eta = eta0 exp(alpha p)``;
- Roelands: ``ln eta = (ln eta0 + 9.67) [(1 + p/p_r)^z - 1]``, ``p_r = 1.96e8 Pa``
  (Roelands 1966; the isothermal form, eta0 at the operating temperature);
- modified WLF of Yasutomi, Bair & Winer (J. Tribol. 106, 1984), as written in docs/model.md §6.4::

      log10 eta = log10 eta_g - C1 (T - T_g) F / (C2 + (T - T_g) F),  eta_g = 1e12 Pa.s
      T_g(p) = T_g0 + A1 ln(1 + A2 p),   F(p) = 1 - B1 ln(1 + B2 p)

docs/model.md does not number the equations of §6.4; docstrings cite "§6.4" and the model name.

Every model holds the viscosity at the glass viscosity eta_g = 1e12 Pa.s once it reaches it
(docs/model.md §6.4, *Glass viscosity*): no liquid is more viscous (the glass transition is where
the viscosity passes about 1e12 Pa.s), no law fitted to liquid data says anything beyond it, and
the cap keeps every eta(p) finite and far inside float32 (3.4e38), the precision of the traction
engine's table. Barus' exponential would otherwise pass float32 near alpha p = 90 (4.5 GPa at
alpha = 2e-8 1/Pa) and float64 near alpha p = 700, and Roelands' near (ln eta0 + 9.67)((1 +
p/p_r)^z - 1) = 700. In the WLF law the glass is where T <= T_g(p), and where the empirical
F(p) turns negative at very high pressure (there (T - T_g) F would turn positive again and eta
would fall); it is held at eta_g in both cases. So eta(p) is continuous, non-decreasing and
finite for every p >= 0 in every model (the Eyring stress limits the traction of a glass
anyway), and no kernel returns NaN or overflows.

The kernels dispatch on an integer model code so the traction quadrature can take any model
through one signature: ``viscosity(p, model, params)`` with ``params`` packed by
``dynamics.lubrication.lubricant.Lubricant.rheology_params()``.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from .._speed.compile_policy import KERNEL

MODEL_BARUS = 0
MODEL_ROELANDS = 1
MODEL_WLF = 2
MODEL_CODES = {"barus": MODEL_BARUS, "roelands": MODEL_ROELANDS, "wlf": MODEL_WLF}

ROELANDS_PRESSURE = 1.96e8  # p_r [Pa], Roelands' universal reference pressure
ROELANDS_LN_ETA_INF = -9.67  # ln(eta_inf / 1 Pa.s), eta_inf = 6.31e-5 Pa.s (Roelands 1966)
WLF_LOG10_ETA_GLASS = 12.0  # log10(eta_g / 1 Pa.s): viscosity at the glass transition
GLASS_VISCOSITY = 10.0**WLF_LOG10_ETA_GLASS  # eta_g [Pa.s]: every model is held there (module docstring)
LN_GLASS_VISCOSITY = math.log(GLASS_VISCOSITY)

# params layout (index constants keep the packing and the kernels in step)
# barus:    [eta0, alpha]
# roelands: [eta0, z]
# wlf:      [T, T_g0, A1, A2, B1, B2, C1, C2]   (T, T_g0 in K; A1, C2 in K; A2, B2 in 1/Pa)


@numba.njit(**KERNEL)
def viscosity_barus(p, eta0, alpha):
    """Barus viscosity eta = min(eta0 exp(alpha p), eta_g) [Pa.s] (docs/model.md §6.4, (M.69)).

    p [Pa], eta0 [Pa.s], alpha [1/Pa]. The exponent is compared with ln(eta_g/eta0) before
    exp is taken, so no pressure overflows.
    """
    exponent = alpha * p
    if exponent >= LN_GLASS_VISCOSITY - math.log(eta0):
        return GLASS_VISCOSITY
    return eta0 * math.exp(exponent)


@numba.njit(**KERNEL)
def viscosity_roelands(p, eta0, z):
    """Roelands viscosity [Pa.s] (docs/model.md §6.4, (M.70)): ln(eta/eta0) = (ln eta0 + 9.67)((1+p/p_r)^z - 1),
    held at eta_g above it.

    p [Pa], eta0 [Pa.s] at ambient pressure and the operating temperature (above
    eta_inf = 6.31e-5 Pa.s, so that eta grows with p), z [-]. The exponent is compared with
    ln(eta_g/eta0) before exp is taken, so no pressure overflows.
    """
    ln_eta0 = math.log(eta0)
    exponent = (ln_eta0 - ROELANDS_LN_ETA_INF) * ((1.0 + p / ROELANDS_PRESSURE) ** z - 1.0)
    if exponent >= LN_GLASS_VISCOSITY - ln_eta0:
        return GLASS_VISCOSITY
    return eta0 * math.exp(exponent)


@numba.njit(**KERNEL)
def viscosity_wlf(p, T, Tg0, A1, A2, B1, B2, C1, C2):
    """Modified WLF (Yasutomi-Bair-Winer) viscosity eta(p, T) [Pa.s] (docs/model.md §6.4, modified WLF).

    p [Pa], T and Tg0 [K], A1 [K], A2 [1/Pa], B1 [-], B2 [1/Pa], C1 [-], C2 [K].
    Held at eta_g = 1e12 Pa.s where the liquid is below its glass transition.
    """
    Tg = Tg0 + A1 * math.log1p(A2 * p)
    F = 1.0 - B1 * math.log1p(B2 * p)
    if T <= Tg or F <= 0.0:
        # glass (T below T_g(p)), or past the pressure where the empirical F(p) changes sign
        # (there (T - T_g) F would turn positive again and eta would fall): hold eta_g
        return GLASS_VISCOSITY
    X = (T - Tg) * F
    return 10.0 ** (WLF_LOG10_ETA_GLASS - C1 * X / (C2 + X))


@numba.njit(**KERNEL)
def viscosity(p, model, params):
    """eta(p) [Pa.s] at the operating temperature for model code `model` (docs/model.md §6.4).

    `params` is the contiguous float64 array of `Lubricant.rheology_params()`.
    """
    if model == MODEL_BARUS:
        return viscosity_barus(p, params[0], params[1])
    if model == MODEL_ROELANDS:
        return viscosity_roelands(p, params[0], params[1])
    return viscosity_wlf(p, params[0], params[1], params[2], params[3], params[4], params[5], params[6], params[7])


@numba.njit(**KERNEL)
def pressure_viscosity_coefficient(model, params):
    """Approximate pressure-viscosity coefficient alpha* = d ln eta/dp at p = 0 [1/Pa] (docs/model.md §6.4).

    Analytic for each model:
    Barus alpha; Roelands z (ln eta0 + 9.67)/p_r;
    WLF ln10 C1 C2 (A1 A2 + B1 B2 (T - T_g0)) / (C2 + T - T_g0)^2.
    """
    if model == MODEL_BARUS:
        return params[1]
    if model == MODEL_ROELANDS:
        return params[1] * (math.log(params[0]) - ROELANDS_LN_ETA_INF) / ROELANDS_PRESSURE
    T, Tg0, A1, A2, B1, B2, C1, C2 = (
        params[0], params[1], params[2], params[3], params[4], params[5], params[6], params[7]
    )
    dT = T - Tg0
    if dT <= 0.0:
        return 0.0  # a glass at ambient pressure: no piezoviscous response left
    return math.log(10.0) * C1 * C2 * (A1 * A2 + B1 * B2 * dT) / (C2 + dT) ** 2


@numba.njit(**KERNEL)
def viscosity_on_grid(p, model, params, out):
    """Fill out[i] = eta(p[i]) [Pa.s]: the vector form used to precompute quadrature nodes."""
    for i in range(p.shape[0]):
        out[i] = viscosity(p[i], model, params)
    return out


def roelands_z_matching(eta0: float, alpha_star: float) -> float:
    """Roelands index z whose initial slope equals alpha* [1/Pa] at viscosity eta0 [Pa.s]."""
    return alpha_star * ROELANDS_PRESSURE / (math.log(eta0) - ROELANDS_LN_ETA_INF)


def viscosity_array(p: np.ndarray, model: int, params: np.ndarray) -> np.ndarray:
    """eta(p) for an array of pressures [Pa] -> [Pa.s] (convenience wrapper, not for hot loops)."""
    p = np.ascontiguousarray(p, dtype=np.float64).ravel()
    return viscosity_on_grid(p, model, np.ascontiguousarray(params, dtype=np.float64), np.empty_like(p))
