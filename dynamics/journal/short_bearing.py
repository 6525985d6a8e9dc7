"""Cage–guiding-race interaction: the short journal bearing of docs/model.md §8.

The cage rim runs on the guiding race lands like a journal in a short bearing. The film force
is Ocvirk's short bearing with Gümbel's half film (paper eqs. 25–26); the metal contact is
Lundberg's dry line contact with full-slip friction; the land law (`land_laws`: hybrid,
hydrodynamic, dry, none, or one of the user's) weights the two by the eccentricity ratio
eps = e/C and sets the film clearance (`land_laws.operations.weights`). The hybrid law of the
paper (eqs. 28–31) takes the film alone up to eps = 1, metal alone from 1 + eps0, and uses the
clearance C + e0, e0 = eps0 C, so the film formulas stay finite through the blend.

Directions (docs/model.md §8): e_r along the cage centre's offset from the race axis,
e_t = e_z x e_r. Force on the cage F = A e_r + B e_t with A = -(f_F F_n^hyd + (1-f_F) Q)
and B = f_F F_t^hyd + (1-f_F) F_f^dry; torque about z on the cage
T = f_C T^hyd + (1-f_C) T^dry. The force and torque on the race are the opposites.

Choices the spec leaves open, made here and flagged for review:
* omega in the force formulas is the *sum* omega_cage + omega_race (entrainment, as the
  spec says); in the viscous torque it is the *difference* omega_cage - omega_race, since
  Couette shear vanishes when both surfaces turn together. For the reference scene (outer
  race fixed) the two are equal.
* the paper's torque weight f_C = (1 + eps0 - eps)/eps0 meets the film torque's
  (1 - eps_h^2)^(-1/2) growth at eps = 1 + eps0, where eps_h = e/(C + e0) reaches 1: T is
  continuous there but its slope would be infinite from the left. So in the blend the film
  torque is evaluated at min(eps_h, eps_clip) (eps_clip = 0.999, the clip the
  hydrodynamic-only law uses for all film terms): the slope stays finite, and T departs
  from eq. 31 only where f_C < 2.1 % (the last 2.1 % of the eps0 band), by less than
  f_C T^hyd there. The force needs no clip: f_F vanishes faster than any power.
* `lands`: the journal length L may be split into n separate lands (the race groove
  between them vents the film). n = 1 is the paper's single journal of length L; n = 2
  makes the film force 1/4 as large (each land is a short bearing of length L/2) and
  shares the dry load over two line contacts of length L/2.

Kernels are pure (floats and contiguous float64 arrays, SI units). The parameters are the
bundle `JournalParams`, packed once by `journal_parameters`, with the land law's bundle in it;
results come back as one float64 array whose layout is given by the J_OUT_* indices
(`unpack_journal` turns it into a dict).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numba
import numpy as np

from .._speed.compile_policy import KERNEL
from .dry import lundberg_load
from .land_laws import LAWS, operations
from .squeeze_film import N_SQUEEZE_OUT, squeeze_film_force

# static: Ocvirk for a centre at rest (paper eq. 25); dynamic: with the squeeze and whirl terms
# of the Reynolds equation (squeeze_film.py, docs/model.md M.94b-M.94e)
FILM_STATIC, FILM_DYNAMIC = 0, 1
FILMS = {"static": FILM_STATIC, "dynamic": FILM_DYNAMIC}
EPS_CLIP = 0.999  # film eccentricity clip of the film formulas (module docstring)


class JournalParams(NamedTuple):
    """The guide lands as a short journal bearing (SI units; `journal_parameters` packs it)."""

    radius: float     # R, land radius [m]
    length: float     # L, total land overlap (both sides) [m]
    clearance: float  # C, radial guide clearance [m]
    viscosity: float  # mu, lubricant dynamic viscosity at the land [Pa s]
    mu_dry: float     # metal-to-metal friction coefficient [-]
    v_reg: float      # friction regularisation speed [m/s]
    e_eff: float      # E', effective modulus cage/race [Pa]
    lands: float      # number of separate lands L is split into [-]
    guidance: float   # +1 outer-race guided (cage inside the land), -1 inner-race guided
    eps_clip: float   # film eccentricity clip: all film terms (hydrodynamic law), the torque (hybrid) [-]
    film: int         # FILM_STATIC | FILM_DYNAMIC: the film force's form
    law: tuple        # the land law's bundle (`land_laws`)


def no_journal() -> JournalParams:
    """The bundle of a cage that runs on no land (ball-guided, or no cage): the 'none' law."""
    return JournalParams(1.0, 1.0, 1.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0, EPS_CLIP, FILM_STATIC, LAWS.pack("none", 0.0))


# --- output vector layout ----------------------------------------------------------------
J_OUT_FORCE = 0  # 3: force on the cage (x, y, z) [N]; z is always 0 (no axial force)
J_OUT_TORQUE = 3  # torque about z on the cage [N m]
J_OUT_EPS = 4  # eps = e / C [-]
J_OUT_METAL_FORCE = 5  # metal-contact normal force (1 - f_F) Q [N]
J_OUT_FRICTION_POWER = 6  # (1 - f_F) |F_f^dry| |v_slide| [W], for the burn-zone map
J_OUT_CONTACT_AZIMUTH = 7  # azimuth of the race land point facing the cage's offset [rad]
J_OUT_DF_DPOS = 8  # 4: dFx/dx, dFx/dy, dFy/dx, dFy/dy [N/m]
J_OUT_DT_DPOS = 12  # 2: dT/dx, dT/dy [N]
J_OUT_DF_DVEL = 14  # 4: dFx/dvx, dFx/dvy, dFy/dvx, dFy/dvy [N s/m]
J_OUT_DT_DVEL = 18  # 2: dT/dvx, dT/dvy [N s]
J_OUT_DF_DOMEGA_CAGE = 20  # 2: dFx/d omega_cage, dFy/d omega_cage [N s]
J_OUT_DT_DOMEGA_CAGE = 22  # dT/d omega_cage [N m s]
J_OUT_DF_DOMEGA_RACE = 23  # 2
J_OUT_DT_DOMEGA_RACE = 25
J_OUT_FILM_POWER = 26  # viscous shear power of the land film, f_C |T_hyd omega_rel| [W]
J_OUT_MIN_FILM = 27  # thinnest land film, C_film - e (>= 0) [m]
N_JOURNAL_OUT = 28


@numba.njit(**KERNEL)
def ocvirk_force(eps, viscosity, omega_sum, R, L, C):
    """Short-bearing film force on the journal, Gümbel half film (docs/model.md §8, paper eq. 25).

    F_n = mu |omega| R L^3 / C^2 * eps^2 / (1 - eps^2)^2        (pushes the journal back)
    F_t = (pi/4) mu omega R L^3 / C^2 * eps / (1 - eps^2)^(3/2)  (90° ahead, sign of omega)
    eps [-] in [0, 1), viscosity mu [Pa s], omega_sum = omega_journal + omega_bearing
    [rad/s], R, L, C [m]. Returns (F_n, F_t, dF_n/deps, dF_t/deps) in N.
    """
    q = 1.0 - eps * eps
    p = viscosity * R * L**3 / (C * C)
    w = abs(omega_sum)
    f_n = p * w * eps * eps / (q * q)
    f_t = 0.25 * math.pi * p * omega_sum * eps / q**1.5
    df_n = p * w * 2.0 * eps * (1.0 + eps * eps) / q**3
    df_t = 0.25 * math.pi * p * omega_sum * (1.0 + 2.0 * eps * eps) / q**2.5
    return f_n, f_t, df_n, df_t


@numba.njit(**KERNEL)
def ocvirk_torque(eps, viscosity, omega_rel, R, L, C):
    """Viscous torque about z on the journal (docs/model.md §8, paper eq. 26).

    T = -pi mu omega_rel R^3 L / C * (2 + eps) / ((1 + eps) sqrt(1 - eps^2)):
    Couette shear over the full film of the converging half plus the striated film (fill
    fraction h_min/h) of the cavitated half; the Poiseuille share, O(eps^2 L^2 / R^2), is
    neglected. At eps = 0 it is Petroff's 2 pi mu omega R^3 L / C. omega_rel = omega_journal
    - omega_bearing [rad/s]; the torque opposes it. Returns (T [N m], dT/deps [N m]).
    """
    q = 1.0 - eps * eps
    g = (2.0 + eps) / ((1.0 + eps) * math.sqrt(q))
    t = -math.pi * viscosity * omega_rel * R**3 * L / C * g
    dlng = 1.0 / (2.0 + eps) - 1.0 / (1.0 + eps) + eps / q
    return t, t * dlng


@numba.njit(**KERNEL)
def _mode_weights(eps, params):
    """Weights (f_F, df_F/de, f_C, df_C/de) of the land law, the film clearance, whether metal
    can touch and whether the film terms are clipped (`land_laws.operations.weights`)."""
    c = params.clearance
    f_f, df_f, f_c, df_c, film_ratio, metal, clipped = operations.weights(params.law, eps)
    return f_f, df_f / c, f_c, df_c / c, c * film_ratio, metal, clipped


@numba.njit(**KERNEL)
def _film_terms(e, omega_sum, omega_rel, c_film, clip_all, params):
    """Film force/torque and derivatives for the n lands, with the over-e forms regular at e=0.

    Returns (F_n, F_t, T, dF_n/de, dF_t/de, dT/de, F_n/e, F_t/e, dF_n/dw_sum, dF_t/dw_sum,
    dT/dw_rel).
    """
    n = params.lands
    R, L, mu = params.radius, params.length, params.viscosity
    eps_h = e / c_film
    clipped = clip_all and eps_h > params.eps_clip
    if clipped:
        eps_h = params.eps_clip
    f_n, f_t, df_n, df_t = ocvirk_force(eps_h, mu, omega_sum, R, L / n, c_film)
    # hybrid blend: the torque is clipped too (finite slope at eps = 1 + eps0, module doc)
    eps_t = min(eps_h, params.eps_clip)
    t, dt = ocvirk_torque(eps_t, mu, omega_rel, R, L, c_film)
    if eps_t < eps_h:
        dt = 0.0
    q = 1.0 - eps_h * eps_h
    p1 = n * mu * R * (L / n) ** 3 / (c_film * c_film)  # per unit omega, all lands
    if clipped:  # beyond the clip the magnitude is frozen: no eps-slope
        df_n, df_t, dt = 0.0, 0.0, 0.0
        fn_e, ft_e = n * f_n / e, n * f_t / e
    else:
        fn_e = p1 * abs(omega_sum) * eps_h / (q * q * c_film)
        ft_e = 0.25 * math.pi * p1 * omega_sum / (q**1.5 * c_film)
    g_n = eps_h * eps_h / (q * q)
    g_t = eps_h / q**1.5
    dfn_dw = p1 * math.copysign(1.0, omega_sum) * g_n if omega_sum != 0.0 else 0.0
    dft_dw = 0.25 * math.pi * p1 * g_t
    dt_dw = t / omega_rel if omega_rel != 0.0 else ocvirk_torque(eps_t, mu, 1.0, R, L, c_film)[0]
    return (n * f_n, n * f_t, t, n * df_n / c_film, n * df_t / c_film, dt / c_film,
            fn_e, ft_e, dfn_dw, dft_dw, dt_dw)


@numba.njit(**KERNEL)
def journal_scalars(e, v_slide, omega_sum, omega_rel, params):
    """Polar components of the hybrid journal force and torque (docs/model.md §8) and slopes.

    e [m] eccentricity (>= 0); v_slide [m/s] tangential sliding speed of the cage surface
    over the race at the contact point; omega_sum, omega_rel [rad/s] cage +/- race speed.
    Returns, with F = A e_r + B e_t the force on the cage and T its torque about z:
    (A, B, T [N, N, N m], dA/de, dB/de, dT/de, A/e, B/e (regular at e = 0),
    dB/dv_slide, dT/dv_slide, dA/domega_sum, dB/domega_sum, dT/domega_rel,
    eps, metal normal force (1-f_F) Q [N], friction power [W], film shear power [W],
    thinnest film C_film - e [m]). With the dynamic film (params.film) the film force is
    left out here: `cage_race_journal` adds it, as it depends on the centre velocity.
    """
    eps = e / params.clearance
    f_f, df_f, f_c, df_c, c_film, dry_on, clip_all = _mode_weights(eps, params)
    fn = ft = th = dfn = dft = dth = fn_e = ft_e = dfn_dw = dft_dw = dth_dw = 0.0
    if f_f > 0.0 or f_c > 0.0:
        fn, ft, th, dfn, dft, dth, fn_e, ft_e, dfn_dw, dft_dw, dth_dw = _film_terms(
            e, omega_sum, omega_rel, c_film, clip_all, params
        )
        if params.film == FILM_DYNAMIC:  # the force comes from squeeze_film_force (caller)
            fn = ft = dfn = dft = fn_e = ft_e = dfn_dw = dft_dw = 0.0
    q_dry = dq_dry = q_e = 0.0
    if dry_on:
        n = params.lands
        q_land, k_land = lundberg_load(e - params.clearance, params.length / n, params.e_eff)
        q_dry, dq_dry, q_e = n * q_land, n * k_land, n * q_land / e
    mu_d, v_reg = params.mu_dry, params.v_reg
    lever = params.guidance * params.radius  # contact point = cage centre + lever e_r
    th_v = math.tanh(v_slide / v_reg)
    f_fr = -mu_d * q_dry * th_v  # full-slip friction, regularised
    dfr_dv = -mu_d * q_dry * (1.0 - th_v * th_v) / v_reg
    dfr_de = -mu_d * dq_dry * th_v
    a = -(f_f * fn + (1.0 - f_f) * q_dry)
    da = -(df_f * (fn - q_dry) + f_f * dfn + (1.0 - f_f) * dq_dry)
    b = f_f * ft + (1.0 - f_f) * f_fr
    db = df_f * (ft - f_fr) + f_f * dft + (1.0 - f_f) * dfr_de
    t = f_c * th + (1.0 - f_c) * lever * f_fr
    dt = df_c * (th - lever * f_fr) + f_c * dth + (1.0 - f_c) * lever * dfr_de
    a_e = -(f_f * fn_e + (1.0 - f_f) * q_e)
    b_e = f_f * ft_e - (1.0 - f_f) * mu_d * th_v * q_e
    metal = (1.0 - f_f) * q_dry
    power = (1.0 - f_f) * abs(f_fr) * abs(v_slide)
    film_power = abs(f_c * th * omega_rel)
    return (a, b, t, da, db, dt, a_e, b_e,
            (1.0 - f_f) * dfr_dv, (1.0 - f_c) * lever * dfr_dv,
            -f_f * dfn_dw, f_f * dft_dw, f_c * dth_dw, eps, metal, power,
            film_power, max(c_film - e, 0.0))


@numba.njit(**KERNEL)
def cage_race_journal(offset, velocity, omega_cage, omega_race, params):
    """Hybrid short-journal force and torque on the cage, with tangents (docs/model.md §8).

    offset (2,) [m]: cage centre minus guiding-race centre (x, y, global frame);
    velocity (2,) [m/s]: cage centre velocity relative to the race centre;
    omega_cage, omega_race [rad/s]: spin about +z; params: `JournalParams`.
    Returns out (N_JOURNAL_OUT,), layout J_OUT_*: force (3) and torque about z on the
    cage, eps, metal normal force, friction power, contact azimuth, and the exact
    derivatives of (F_x, F_y, T) with respect to (x, y), (v_x, v_y), omega_cage, omega_race.
    """
    out = np.empty(N_JOURNAL_OUT)
    cage_race_journal_into(offset[0], offset[1], velocity[0], velocity[1], omega_cage, omega_race, params, out,
                           np.empty(N_SQUEEZE_OUT))
    return out


@numba.njit(**KERNEL)
def cage_race_journal_into(ox, oy, vx, vy, omega_cage, omega_race, params, out, sq):
    """`cage_race_journal` of offset (ox, oy) [m] and velocity (vx, vy) [m/s] into out
    (N_JOURNAL_OUT), with sq (N_SQUEEZE_OUT) as the dynamic film's scratch: no allocation,
    for the residual of every Newton iteration."""
    out[:] = 0.0
    e = math.hypot(ox, oy)
    erx, ery = (ox / e, oy / e) if e > 0.0 else (1.0, 0.0)
    etx, ety = -ery, erx
    lever = params.guidance * params.radius
    v_r = vx * erx + vy * ery
    v_slide = vx * etx + vy * ety + lever * (omega_cage - omega_race)
    (a, b, t, da, db, dt, a_e, b_e, db_dv, dt_dv, da_dw, db_dw, dt_dwr,
     eps, metal, power, film_power, min_film) = journal_scalars(
        e, v_slide, omega_cage + omega_race, omega_cage - omega_race, params)
    out[0], out[1], out[3] = a * erx + b * etx, a * ery + b * ety, t
    out[J_OUT_EPS], out[J_OUT_METAL_FORCE], out[J_OUT_FRICTION_POWER] = eps, metal, power
    out[J_OUT_FILM_POWER], out[J_OUT_MIN_FILM] = film_power, min_film
    out[J_OUT_CONTACT_AZIMUTH] = math.atan2(lever * ery, lever * erx)
    # F = A e_r + B e_t; d e_r = e_t dphi, d e_t = -e_r dphi, dphi = e_t . dp / e, and
    # B depends on phi through v_slide = v . e_t + ..., d v_slide / dphi = -v . e_r.
    db_dphi_e = db_dv * (-v_r) / e if db_dv != 0.0 else 0.0  # dry only: e > C > 0
    dt_dphi_e = dt_dv * (-v_r) / e if dt_dv != 0.0 else 0.0
    er = (erx, ery)
    et = (etx, ety)
    for i in range(2):
        for j in range(2):
            out[J_OUT_DF_DPOS + 2 * i + j] = (
                da * er[i] * er[j] + db * et[i] * er[j]
                + (a_e + db_dphi_e) * et[i] * et[j] - b_e * er[i] * et[j]
            )
            out[J_OUT_DF_DVEL + 2 * i + j] = db_dv * et[i] * et[j]
        out[J_OUT_DT_DPOS + i] = dt * er[i] + dt_dphi_e * et[i]
        out[J_OUT_DT_DVEL + i] = dt_dv * et[i]
        out[J_OUT_DF_DOMEGA_CAGE + i] = da_dw * er[i] + (db_dw + db_dv * lever) * et[i]
        out[J_OUT_DF_DOMEGA_RACE + i] = da_dw * er[i] + (db_dw - db_dv * lever) * et[i]
    out[J_OUT_DT_DOMEGA_CAGE] = dt_dwr + dt_dv * lever
    out[J_OUT_DT_DOMEGA_RACE] = -dt_dwr - dt_dv * lever
    if params.film == FILM_DYNAMIC:
        _add_squeeze_film(ox, oy, vx, vy, omega_cage + omega_race, eps, erx, ery, params, out, sq)


@numba.njit(**KERNEL)
def _add_squeeze_film(ox, oy, vx, vy, omega_sum, eps, erx, ery, params, out, sq):
    """Add the weighted dynamic film force f_F F(e, V) (squeeze_film.py) and its exact
    tangents to out; V = v - (omega/2) e_z x e, so dV/de = -(omega/2) e_z x and
    dV/domega = -(1/2) e_z x e for either surface's speed."""
    f_f, df_f, _, _, c_film, _, _ = _mode_weights(eps, params)
    if f_f <= 0.0:
        return
    n = params.lands
    k_film = n * params.viscosity * params.radius * (params.length / n) ** 3 / c_film**3
    squeeze_film_force(ox, oy, vx, vy, omega_sum, c_film, k_film, params.eps_clip, sq)
    er = (erx, ery)
    dvw = (0.5 * oy, -0.5 * ox)  # dV/d omega = -(1/2) e_z x e
    for i in range(2):
        out[J_OUT_FORCE + i] += f_f * sq[i]
        dfw = 0.0
        for j in range(2):
            # dF/de = f_F (D_e + D_V dV/de) + F (df_F/de) e_r^T, dV/de = -(omega/2) [[0,-1],[1,0]]
            dv_de = -0.5 * omega_sum * sq[6 + 2 * i + 1] if j == 0 else 0.5 * omega_sum * sq[6 + 2 * i]
            out[J_OUT_DF_DPOS + 2 * i + j] += f_f * (sq[2 + 2 * i + j] + dv_de) + sq[i] * df_f * er[j]
            out[J_OUT_DF_DVEL + 2 * i + j] += f_f * sq[6 + 2 * i + j]
            dfw += f_f * sq[6 + 2 * i + j] * dvw[j]
        out[J_OUT_DF_DOMEGA_CAGE + i] += dfw
        out[J_OUT_DF_DOMEGA_RACE + i] += dfw


# --- packing and unpacking (Python side, outside the hot loop) ----------------------------
class JournalGeometry(NamedTuple):
    """The lands the cage runs on: radius R [m] of the land, length L [m] of the total land
    overlap (both sides), radial clearance C [m], the number of separate lands L is split
    into, and the guiding race (outer | inner)."""

    radius: float
    length: float
    clearance: float
    lands: int = 1
    guidance: str = "outer"


def journal_parameters(
    geometry: JournalGeometry,
    *,
    viscosity: float,
    effective_modulus: float,
    friction_coefficient: float,
    eps0: float = 0.05,
    regularisation_speed: float = 1e-3,
    mode: str = "hybrid",
    eps_clip: float = EPS_CLIP,
    film: str = "static",
) -> JournalParams:
    """Pack and check the journal parameters (SI units) for `cage_race_journal`.

    geometry: the lands (`JournalGeometry`: R, L, C, lands, guidance); viscosity [Pa s] at the
    land; effective_modulus E' [Pa]; friction_coefficient mu_dry [-]; eps0 [-] boundary-layer
    thickness e0/C; regularisation_speed [m/s] of the dry friction; mode: the land law, a name
    of `land_laws.LAWS` (hybrid | hydrodynamic | dry | none | a registered one); eps_clip: largest film eccentricity e/C_film the film formulas
    are evaluated at (all of them in hydrodynamic mode, the torque in hybrid); film: static
    (paper eq. 25, a centre at rest) | dynamic (with the squeeze and whirl terms,
    squeeze_film.py).
    """
    radius, length, clearance, lands, guidance = geometry
    positive = {
        "radius [m]": radius, "length [m]": length, "clearance [m]": clearance,
        "effective_modulus [Pa]": effective_modulus, "eps0 [-]": eps0,
        "regularisation_speed [m/s]": regularisation_speed,
    }
    for name, value in positive.items():
        if not value > 0.0:
            raise ValueError(f"cage-race journal: {name} = {value!r} must be > 0")
    for name, value in {"viscosity [Pa s]": viscosity, "friction_coefficient [-]": friction_coefficient}.items():
        if not value >= 0.0:
            raise ValueError(f"cage-race journal: {name} = {value!r} must be >= 0")
    if mode not in LAWS:
        raise ValueError(f"cage-race journal: mode = {mode!r}; allowed: {', '.join(LAWS)}")
    if guidance not in ("outer", "inner"):
        raise ValueError(f"cage-race journal: guidance = {guidance!r}; allowed: 'outer', 'inner'")
    if int(lands) != lands or lands < 1:
        raise ValueError(f"cage-race journal: lands = {lands!r} must be a positive integer")
    if film not in FILMS:
        raise ValueError(f"cage-race journal: film = {film!r}; allowed: {', '.join(FILMS)}")
    if not 0.0 < eps_clip < 1.0:
        raise ValueError(f"cage-race journal: eps_clip = {eps_clip!r} must be in (0, 1), e.g. 0.999")
    return JournalParams(
        radius=float(radius), length=float(length), clearance=float(clearance), viscosity=float(viscosity),
        mu_dry=float(friction_coefficient), v_reg=float(regularisation_speed), e_eff=float(effective_modulus),
        lands=float(lands), guidance=1.0 if guidance == "outer" else -1.0, eps_clip=float(eps_clip),
        film=FILMS[film], law=LAWS.pack(mode, eps0))


def journal_parameters_for_cage(bearing, cage, cage_material, race_material, *, viscosity: float,
                                friction_coefficient: float, lands: int = 1, **options) -> JournalParams:
    """`journal_parameters` from dynamics.geometry objects (R = land radius, L, C, E'), the
    land length split into `lands` separate lands.

    Extra keyword options (eps0, mode, ...) pass through unchanged.
    """
    from ..geometry import effective_modulus

    if cage.guide_ring is None:
        raise ValueError("a ball-guided cage (cage.guidance = 'ball') runs on no land: it has no journal")
    geometry = JournalGeometry(radius=0.5 * cage.guide_land_diameter(bearing),
                               length=cage.guide_land_length(bearing), clearance=cage.guide_clearance(bearing),
                               lands=lands, guidance=cage.guidance)
    return journal_parameters(geometry, viscosity=viscosity,
                              effective_modulus=effective_modulus(cage_material, race_material),
                              friction_coefficient=friction_coefficient, **options)


def unpack_journal(out: np.ndarray) -> dict:
    """Name the entries of a `cage_race_journal` result (units as in the J_OUT_* comments)."""
    return {
        "force": out[J_OUT_FORCE:J_OUT_FORCE + 3].copy(),
        "torque": float(out[J_OUT_TORQUE]),
        "eps": float(out[J_OUT_EPS]),
        "metal_force": float(out[J_OUT_METAL_FORCE]),
        "friction_power": float(out[J_OUT_FRICTION_POWER]),
        "contact_azimuth": float(out[J_OUT_CONTACT_AZIMUTH]),
        "dforce_dposition": out[J_OUT_DF_DPOS:J_OUT_DF_DPOS + 4].reshape(2, 2).copy(),
        "dtorque_dposition": out[J_OUT_DT_DPOS:J_OUT_DT_DPOS + 2].copy(),
        "dforce_dvelocity": out[J_OUT_DF_DVEL:J_OUT_DF_DVEL + 4].reshape(2, 2).copy(),
        "dtorque_dvelocity": out[J_OUT_DT_DVEL:J_OUT_DT_DVEL + 2].copy(),
        "dforce_domega_cage": out[J_OUT_DF_DOMEGA_CAGE:J_OUT_DF_DOMEGA_CAGE + 2].copy(),
        "dtorque_domega_cage": float(out[J_OUT_DT_DOMEGA_CAGE]),
        "dforce_domega_race": out[J_OUT_DF_DOMEGA_RACE:J_OUT_DF_DOMEGA_RACE + 2].copy(),
        "dtorque_domega_race": float(out[J_OUT_DT_DOMEGA_RACE]),
        "film_power": float(out[J_OUT_FILM_POWER]),
        "min_film": float(out[J_OUT_MIN_FILM]),
    }
