"""Ball–pocket contact: a sphere in a cylindrical or spherical cage pocket (docs/model.md §7).

A cylindrical pocket is a cylinder of radius r_p whose axis is radial in the cage frame, through
the pocket centre on the cage's mean circle at azimuth psi_k. The ball (radius r_b) penetrates
the wall by

    delta = rho - (r_p - r_b),    rho = distance of the ball centre from the pocket axis,

along n, the unit vector from the axis to the ball centre in the plane normal to the axis.
The contact point is on the wall, p = foot of the ball centre on the axis + r_p n. A
spherical pocket (a ball-guided cage's: it holds the ball radially too) is the sphere of radius
r_p about the pocket centre: rho is the distance of the ball centre from that centre, and n
points from it to the ball centre.

Normal force: the pocket law (`pocket_laws`; by default Hertz with hysteresis damping,
`pocket_laws.hertz_hysteresis`) of the penetration, its rate and the impact speed v_0 the
bearing model remembers per pocket (`dynamics.bearing.model.track_impacts`: while a pocket is
open it stores the current approach speed, so when contact starts the speed it hit with is
already known). k_h, the Hertz constant of a sphere in a concave cylinder (curvatures 2/D, 2/D
against -2/d_p, 0) or sphere, is computed once per scene (`pocket_hertz_constant`, the exact
Hertz solution of `contact.hertz`).

Friction is Coulomb's, regularised: F_f = -mu F_n tanh(|v_s|/v_reg) v_s/|v_s| with v_s
the sliding velocity of the ball over the cage at p.

Kernels are pure (floats, contiguous float64 arrays, SI units, global frame); the parameters
are the bundle `PocketParams` (`pocket_parameters`), with the pocket law's bundle in it; results
come back in one array whose layout is given by the P_OUT_* indices.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numba
import numpy as np

from .._speed.compile_policy import KERNEL, NO_REFCOUNT
from .hertz import hertz_exact
from .pocket_laws import LAWS, operations

SHAPE_CYLINDRICAL, SHAPE_SPHERICAL = 0, 1
SHAPES = {"cylindrical": SHAPE_CYLINDRICAL, "spherical": SHAPE_SPHERICAL}


class PocketParams(NamedTuple):
    """The pockets of one cage (SI units; `pocket_parameters` packs it)."""

    ball_radius: float    # r_b [m]
    pocket_radius: float  # r_p [m]
    pitch_radius: float   # radius of the pocket-centre circle in the cage frame [m]
    pocket_z: float       # axial position of the pocket centres in the cage frame [m]
    eccentricity: float   # run-out: pocket-circle centre off the cage centre along the cage frame's +x [m]
    shape: int            # SHAPE_CYLINDRICAL | SHAPE_SPHERICAL
    mu: float             # friction coefficient [-]
    v_reg: float          # friction regularisation speed [m/s]
    law: tuple            # the pocket law's bundle (`pocket_laws`)


def no_pockets() -> PocketParams:
    """The bundle's type for a model without a cage (never read)."""
    return PocketParams(1.0, 1.0, 1.0, 0.0, 0.0, SHAPE_CYLINDRICAL, 0.0, 1.0,
                        LAWS.pack("hertz-hysteresis", 1.0, 1.0, "flores", 1.0))

# --- output vector layout ----------------------------------------------------------------
P_OUT_DELTA = 0  # penetration delta [m] (negative: gap)
P_OUT_APPROACH = 1  # approach velocity d delta/dt [m/s] (+: closing)
P_OUT_IN_CONTACT = 2  # 1.0 if delta > 0 else 0.0
P_OUT_FN = 3  # normal force magnitude F_n >= 0 [N]
P_OUT_NORMAL = 4  # 3: unit normal n, pocket axis -> ball centre
P_OUT_POINT = 7  # 3: contact point on the pocket wall [m]
P_OUT_FORCE_BALL = 10  # 3: total force on the ball [N]
P_OUT_MOMENT_BALL = 13  # 3: moment on the ball about its centre [N m]
P_OUT_FORCE_CAGE = 16  # 3: force on the cage (= -force on the ball) [N]
P_OUT_MOMENT_CAGE = 19  # 3: moment on the cage about the cage centre [N m]
P_OUT_FRICTION = 22  # 3: friction force on the ball [N]
P_OUT_DFN_DDELTA = 25  # dF_n/d delta [N/m]
P_OUT_DFN_DRATE = 26  # dF_n/d delta_dot [N s/m]
P_OUT_SLIDING_SPEED = 27  # |v_s| [m/s]
P_OUT_FRICTION_POWER = 28  # |F_f| |v_s| [W]
P_OUT_ORBITAL_POSITION = 29  # azimuth of the ball centre, atan2(y, x) [rad], in contact only (0 otherwise)
N_POCKET_OUT = 30



@numba.njit(**KERNEL)
def _cross(ax, ay, az, bx, by, bz):
    return ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx


@numba.njit(**NO_REFCOUNT)
def _column_mix(rot, u, v, w):
    """rot @ (u, v, w) as three floats."""
    return (rot[0, 0] * u + rot[0, 1] * v + rot[0, 2] * w,
            rot[1, 0] * u + rot[1, 1] * v + rot[1, 2] * w,
            rot[2, 0] * u + rot[2, 1] * v + rot[2, 2] * w)


@numba.njit(**KERNEL)
def pocket_contact(x_ball, v_ball, w_ball, x_cage, rot_cage, v_cage, w_cage, psi, impact_speed, params):
    """Ball–pocket contact of one ball in pocket psi (docs/model.md §7).

    x_ball, v_ball, w_ball (3,): ball centre [m], velocity [m/s], angular velocity [rad/s];
    x_cage (3,), rot_cage (3, 3) (cage-to-global rotation), v_cage (3,), w_cage (3,): the
    cage; psi [rad]: pocket azimuth in the cage frame; impact_speed [m/s]: v_0 of the
    pocket law (0 if not tracked); params: `PocketParams`. All vectors in the global frame.
    Returns out (N_POCKET_OUT,), layout P_OUT_*.
    """
    out = np.zeros(N_POCKET_OUT)
    _pocket_contact_into(out, x_ball, v_ball, w_ball, x_cage, rot_cage, v_cage, w_cage, math.cos(psi), math.sin(psi),
                         impact_speed, params)
    return out


@numba.njit(**NO_REFCOUNT)
def _pocket_contact_into(out, x_ball, v_ball, w_ball, x_cage, rot_cage, v_cage, w_cage, c, s, impact_speed, params):
    """`pocket_contact` writing into a zeroed row `out`; scalar arithmetic, no temporaries.
    c, s: cosine and sine of the pocket azimuth psi (fixed per pocket: the residual reads
    them from `CageArrays` instead of calling sin and cos for every pocket in every call)."""
    r_b, r_p = params.ball_radius, params.pocket_radius
    # pocket centre in the cage frame: on the pocket circle, whose centre the run-out moves off
    # the cage centre (the centre of the guiding surface, docs/model.md §7)
    lx, ly, lz = params.pitch_radius * c + params.eccentricity, params.pitch_radius * s, params.pocket_z
    ax, ay, az = _column_mix(rot_cage, c, s, 0.0)  # pocket axis, global
    ox, oy, oz = _column_mix(rot_cage, lx, ly, lz)  # pocket centre - cage centre, global
    dx, dy, dz = x_ball[0] - x_cage[0] - ox, x_ball[1] - x_cage[1] - oy, x_ball[2] - x_cage[2] - oz
    # a cylinder measures the distance from its axis, a sphere from its centre
    along = dx * ax + dy * ay + dz * az if params.shape == SHAPE_CYLINDRICAL else 0.0
    px, py, pz = dx - along * ax, dy - along * ay, dz - along * az
    rho = math.sqrt(px * px + py * py + pz * pz)
    if rho > 1e-12 * r_p:
        nx, ny, nz = px / rho, py / rho, pz / rho
    else:  # on the axis any direction normal to it will do; the cage axis is one
        nx, ny, nz = rot_cage[0, 2], rot_cage[1, 2], rot_cage[2, 2]
    delta = rho - (r_p - r_b)
    # contact point on the wall, relative to the ball centre and to the cage centre
    gap = r_p - rho
    bx, by, bz = gap * nx, gap * ny, gap * nz
    cx, cy, cz = x_ball[0] - x_cage[0] + bx, x_ball[1] - x_cage[1] + by, x_ball[2] - x_cage[2] + bz
    wbx, wby, wbz = _cross(w_ball[0], w_ball[1], w_ball[2], bx, by, bz)
    wcx, wcy, wcz = _cross(w_cage[0], w_cage[1], w_cage[2], cx, cy, cz)
    vx = v_ball[0] + wbx - v_cage[0] - wcx
    vy = v_ball[1] + wby - v_cage[1] - wcy
    vz = v_ball[2] + wbz - v_cage[2] - wcz
    delta_dot = vx * nx + vy * ny + vz * nz
    sx, sy, sz = vx - delta_dot * nx, vy - delta_dot * ny, vz - delta_dot * nz
    speed = math.sqrt(sx * sx + sy * sy + sz * sz)
    out[P_OUT_DELTA], out[P_OUT_APPROACH], out[P_OUT_SLIDING_SPEED] = delta, delta_dot, speed
    out[P_OUT_NORMAL], out[P_OUT_NORMAL + 1], out[P_OUT_NORMAL + 2] = nx, ny, nz
    out[P_OUT_POINT] = x_cage[0] + cx
    out[P_OUT_POINT + 1] = x_cage[1] + cy
    out[P_OUT_POINT + 2] = x_cage[2] + cz
    if delta <= 0.0:
        return
    out[P_OUT_IN_CONTACT] = 1.0
    # read only while the ball touches (the impact log): one libm call per touching pocket
    # rather than per pocket in every residual
    out[P_OUT_ORBITAL_POSITION] = math.atan2(x_ball[1], x_ball[0])
    f_n, dfn_dd, dfn_drate = operations.normal_force(params.law, delta, delta_dot, impact_speed)
    ratio = 0.0  # friction = -ratio * v_s
    if speed > 0.0:
        f_t = params.mu * f_n * math.tanh(speed / params.v_reg)
        ratio = f_t / speed
        out[P_OUT_FRICTION_POWER] = f_t * speed
    fx, fy, fz = -ratio * sx - f_n * nx, -ratio * sy - f_n * ny, -ratio * sz - f_n * nz
    mbx, mby, mbz = _cross(bx, by, bz, fx, fy, fz)
    mcx, mcy, mcz = _cross(cx, cy, cz, -fx, -fy, -fz)
    out[P_OUT_FN], out[P_OUT_DFN_DDELTA], out[P_OUT_DFN_DRATE] = f_n, dfn_dd, dfn_drate
    out[P_OUT_FORCE_BALL], out[P_OUT_FORCE_BALL + 1], out[P_OUT_FORCE_BALL + 2] = fx, fy, fz
    out[P_OUT_MOMENT_BALL], out[P_OUT_MOMENT_BALL + 1], out[P_OUT_MOMENT_BALL + 2] = mbx, mby, mbz
    out[P_OUT_FORCE_CAGE], out[P_OUT_FORCE_CAGE + 1], out[P_OUT_FORCE_CAGE + 2] = -fx, -fy, -fz
    out[P_OUT_MOMENT_CAGE], out[P_OUT_MOMENT_CAGE + 1], out[P_OUT_MOMENT_CAGE + 2] = mcx, mcy, mcz
    out[P_OUT_FRICTION], out[P_OUT_FRICTION + 1], out[P_OUT_FRICTION + 2] = -ratio * sx, -ratio * sy, -ratio * sz


@numba.njit(**KERNEL)
def pocket_contacts(x_balls, v_balls, w_balls, x_cage, rot_cage, v_cage, w_cage, psi, impact_speeds, params):
    """`pocket_contact` for all Z balls: ball k in pocket psi[k] (docs/model.md §7).

    x_balls, v_balls, w_balls (Z, 3); psi, impact_speeds (Z,); the rest as in
    `pocket_contact`. Returns out (Z, N_POCKET_OUT); the cage's resultant is the column
    sum of P_OUT_FORCE_CAGE and P_OUT_MOMENT_CAGE.
    """
    z = x_balls.shape[0]
    out = np.zeros((z, N_POCKET_OUT))
    for k in range(z):
        _pocket_contact_into(out[k], x_balls[k], v_balls[k], w_balls[k], x_cage, rot_cage, v_cage,
                             w_cage, math.cos(psi[k]), math.sin(psi[k]), impact_speeds[k], params)
    return out


# --- scene-level set-up (Python side, once per scene) ------------------------------------
def check_pocket_clearance(ball_diameter: float, pocket_diameter: float) -> float:
    """Diametral pocket clearance d_p - D [m]; a pocket that cannot hold the ball is an error."""
    if not ball_diameter > 0.0:
        raise ValueError(f"bearing.ball_diameter = {ball_diameter!r} m must be > 0")
    if not pocket_diameter > ball_diameter:
        raise ValueError(
            f"cage.pocket_diameter = {pocket_diameter!r} m must exceed bearing.ball_diameter = "
            f"{ball_diameter!r} m: a cylindrical pocket needs a clearance (typically 1–6 % of D; "
            f"the reference cage has d_p = 0.02023 m for D = 0.01905 m)"
        )
    return pocket_diameter - ball_diameter


def pocket_hertz_constant(ball_diameter: float, pocket_diameter: float, effective_modulus: float,
                          shape: str = "cylindrical"):
    """(kappa, k_h) of a ball of diameter D in a pocket of diameter d_p (§7): the exact Hertz
    solution (`hertz.hertz_exact`, docs/model.md §6.2).

    Curvatures: ball 2/D, 2/D; a cylindrical pocket -2/d_p round the cylinder, 0 along its
    axis (an elliptical contact); a spherical pocket -2/d_p, -2/d_p (a circular one).
    """
    check_pocket_clearance(ball_diameter, pocket_diameter)
    if not effective_modulus > 0.0:
        raise ValueError(f"pocket contact: effective modulus E' = {effective_modulus!r} Pa must be > 0")
    if shape == "spherical":
        curvature_sum, difference = 4.0 / ball_diameter - 4.0 / pocket_diameter, 0.0
    else:
        curvature_sum = 4.0 / ball_diameter - 2.0 / pocket_diameter
        difference = (2.0 / pocket_diameter) / curvature_sum
    kappa, _, k_h, _, _ = hertz_exact(curvature_sum, difference, effective_modulus)
    return float(kappa), float(k_h)


def pocket_parameters(*, ball_diameter: float, pocket_diameter: float, pitch_radius: float,
                      effective_modulus: float, friction_coefficient: float, regularisation_speed: float = 1e-3,
                      pocket_axial_offset: float = 0.0, pocket_circle_eccentricity: float = 0.0,
                      shape: str = "cylindrical", law: str = "hertz-hysteresis", **law_options) -> PocketParams:
    """Pack and check the pocket parameters (SI) for `pocket_contact` / `pocket_contacts`.

    pitch_radius [m]: radius of the pocket-centre circle (cage mean radius);
    pocket_circle_eccentricity [m]: run-out, the pocket circle's centre off the cage centre
    towards pocket 0 (the cage frame's +x); regularisation_speed [m/s] of the friction;
    shape: "cylindrical" (radial axis) | "spherical"; law: the normal-force law, a name of
    `pocket_laws.LAWS`, whose `pack` takes the pocket's Hertz constant and `law_options`
    (restitution [-], damping_model, reference_impact_speed [m/s]: the floor and default of v_0).
    """
    if shape not in SHAPES:
        raise ValueError(f"pocket contact: shape = {shape!r}; allowed: {', '.join(SHAPES)}")
    _, k_h = pocket_hertz_constant(ball_diameter, pocket_diameter, effective_modulus, shape)
    for name, value in {"pitch_radius [m]": pitch_radius, "regularisation_speed [m/s]": regularisation_speed}.items():
        if not value > 0.0:
            raise ValueError(f"pocket contact: {name} = {value!r} must be > 0")
    if not friction_coefficient >= 0.0:
        raise ValueError(f"pocket contact: friction_coefficient = {friction_coefficient!r} must be >= 0")
    if law not in LAWS:
        raise ValueError(f"pocket contact: law = {law!r}; allowed: {', '.join(LAWS)}")
    return PocketParams(
        ball_radius=0.5 * ball_diameter, pocket_radius=0.5 * pocket_diameter, pitch_radius=float(pitch_radius),
        pocket_z=float(pocket_axial_offset), eccentricity=float(pocket_circle_eccentricity), shape=SHAPES[shape],
        mu=float(friction_coefficient), v_reg=float(regularisation_speed), law=LAWS.pack(law, k_h, **law_options))


def pocket_parameters_for_cage(bearing, cage, ball_material, cage_material, *, restitution: float,
                               friction_coefficient: float, **options) -> PocketParams:
    """`pocket_parameters` from dynamics.geometry objects (D, d_p, d_c/2, run-out, shape, E' ball–cage:
    the cage's own material)."""
    from ..geometry import effective_modulus

    return pocket_parameters(
        ball_diameter=bearing.ball_diameter, pocket_diameter=cage.pocket_diameter,
        pitch_radius=0.5 * cage.mean_diameter, pocket_circle_eccentricity=cage.pocket_circle_eccentricity,
        shape=cage.pocket_form,
        effective_modulus=effective_modulus(ball_material, cage_material),
        restitution=restitution, friction_coefficient=friction_coefficient, **options,
    )


def pocket_azimuths(ball_count: int, index_errors=None, pitch_radius: float = 1.0) -> np.ndarray:
    """psi_k = 2 pi k / Z [rad], the pocket azimuths in the cage frame (docs/model.md §1),
    each moved by its pitch error along the pitch circle (index_errors [m], one a pocket, on
    a pitch circle of radius pitch_radius [m])."""
    psi = 2.0 * np.pi * np.arange(ball_count) / ball_count
    if index_errors is not None:
        psi = psi + np.asarray(index_errors, float) / pitch_radius
    return psi
