"""Cage contacts of the dynamic model: ball–pocket (§7) and cage–guiding-race hybrid short
journal (§8), with their tangent contributions. Kernels from dynamics.contact.pocket and
dynamics.journal.short_bearing; this file only places their results into g, the tangents and diag."""

from __future__ import annotations

import numba
import numpy as np

from .._speed.compile_policy import KERNEL, NO_REFCOUNT
from ..journal.short_bearing import (
    J_OUT_CONTACT_AZIMUTH, J_OUT_DF_DOMEGA_CAGE, J_OUT_DF_DOMEGA_RACE, J_OUT_DF_DPOS, J_OUT_DF_DVEL,
    J_OUT_DT_DOMEGA_CAGE, J_OUT_DT_DOMEGA_RACE, J_OUT_DT_DPOS, J_OUT_DT_DVEL, J_OUT_EPS, J_OUT_FILM_POWER,
    J_OUT_FORCE, J_OUT_FRICTION_POWER, J_OUT_METAL_FORCE, J_OUT_MIN_FILM, J_OUT_TORQUE, cage_race_journal_into,
)
from ..contact.pocket import (
    P_OUT_APPROACH, P_OUT_DFN_DDELTA, P_OUT_DFN_DRATE, P_OUT_FN, P_OUT_FORCE_BALL,
    P_OUT_FORCE_CAGE, P_OUT_FRICTION_POWER, P_OUT_IN_CONTACT, P_OUT_MOMENT_BALL,
    P_OUT_MOMENT_CAGE, P_OUT_NORMAL, P_OUT_ORBITAL_POSITION, P_OUT_POINT, P_OUT_SLIDING_SPEED,
    _pocket_contact_into,
)
from ..multibody.small import eye3, outer

from .channels import (
    DB_POCKET, DB_POCKET_APPROACH, DB_POCKET_FRICTION_POWER, DB_POCKET_IN_CONTACT, DB_POCKET_ORBITAL,
    DG_AZIMUTH, DG_EPS, DG_FILM_POWER, DG_FRICTION_POWER, DG_FX, DG_FY, DG_METAL, DG_MIN_FILM, DG_TORQUE,
)
from .layout import CAGE_BORDER, INNER_BORDER
from .tangents import add_pair, point_map


@numba.njit(**NO_REFCOUNT)
def pocket_forces(ball, cage, cos_psi, sin_psi, v0, pp, pres, g, b, F_cage, M_cage):
    """Ball in its pocket (docs/model.md §7): ball and cage are `bundles.Ball` and
    `bundles.Body`, (cos_psi, sin_psi) of the pocket azimuth psi, v0 [m/s] its remembered impact speed, pp
    the pocket parameters. The contact row goes into pres and, in contact
    (pres[P_OUT_IN_CONTACT] > 0; then `pocket_tangent` gives its Newton blocks), the ball's
    wrench is added to g[b:b+6] and the cage's (spatial, about its centre) to F_cage, M_cage."""
    pres[:] = 0.0
    _pocket_contact_into(pres, ball.x, ball.v, ball.w, cage.x, cage.R, cage.v, cage.w, cos_psi, sin_psi, v0, pp)
    if pres[P_OUT_IN_CONTACT] <= 0.0:
        return
    for i in range(3):
        g[b + i] += pres[P_OUT_FORCE_BALL + i]
        g[b + 3 + i] += pres[P_OUT_MOMENT_BALL + i]
        F_cage[i] += pres[P_OUT_FORCE_CAGE + i]
        M_cage[i] += pres[P_OUT_MOMENT_CAGE + i]


@numba.njit(cache=True, inline="always")
def pocket_tangent(k, x_b, cage, pp, pres, K, C):
    """Tangent blocks of ball k's pocket contact (result row `pres` of `pocket_forces`) into
    K and C (`linear_solvers.Blocks`); x_b: the ball centre, cage: `bundles.Body`. Kept
    apart from the force so that a residual-only evaluation does not pass the tangent
    blocks."""
    n = pres[P_OUT_NORMAL:P_OUT_NORMAL + 3]
    p = pres[P_OUT_POINT:P_OUT_POINT + 3]
    nn = outer(n, n)
    GA = np.empty((3, 6))
    GB = np.empty((3, 6))
    I3 = eye3()
    point_map(p - x_b, I3, GA)
    point_map(p - cage.x, cage.R, GB)
    # normal stiffness along n (contact point on the wall moves with the ball centre)
    GA0 = np.zeros((3, 6))
    for i in range(3):
        GA0[i, i] = 1.0
    off = np.int64(CAGE_BORDER)  # typed int64, not Literal[int]: the overload _race_term uses (cold start)
    add_pair(k, off, pres[P_OUT_DFN_DDELTA] * nn, GA0, GB, K)
    # normal damping and regularised friction act on the relative velocity at p
    mu, v_reg = pp.mu, pp.v_reg
    c_f = mu * pres[P_OUT_FN] / max(pres[P_OUT_SLIDING_SPEED], v_reg)
    Jv = pres[P_OUT_DFN_DRATE] * nn + c_f * (I3 - nn)
    add_pair(k, off, Jv, GA, GB, C)


@numba.njit(**KERNEL)
def journal_forces(cage, race, jp, jres, squeeze, g, cage_off, race_force, race_moment):
    """Cage on its guiding land (docs/model.md §8): cage and race are `bundles.Body` (the
    race turns about z and, for an inner-guided cage, moves with the inner race); force and
    torque about z on the cage (spatial), into the cage rows g[cage_off:cage_off+6]; their
    reaction on the race, the force and the moment about the race's centre (spatial), added to
    race_force and race_moment (3 each); the `cage_race_journal` row, with the derivatives
    `journal_tangent` reads, into jres (squeeze: the dynamic film's scratch, N_SQUEEZE_OUT).
    Returns the power of the journal on the pair [W] (negative: dissipated). Allocates
    nothing: the residual of every Newton iteration calls it.

    The film and the line contact act between the cage and the land in the plane of the
    bearing (docs/model.md §8): the race's tilt does not enter them."""
    vel0, vel1 = cage.v[0] - race.v[0], cage.v[1] - race.v[1]
    w_race_z = race.w[2]
    out = jres
    dx, dy, dz = cage.x[0] - race.x[0], cage.x[1] - race.x[1], cage.x[2] - race.x[2]
    cage_race_journal_into(dx, dy, vel0, vel1, cage.w[2], w_race_z, jp, out, squeeze)
    F = out[J_OUT_FORCE:J_OUT_FORCE + 3]
    T = out[J_OUT_TORQUE]
    # torque about the global z axis, mapped to material moments of the cage
    for i in range(3):
        g[cage_off + i] += F[i]
        g[cage_off + 3 + i] += cage.R[2, i] * T
    # the reaction about the race's centre: -T e_z - d x F, d = cage centre - race centre (F_z = 0)
    mx, my, mz = dz * F[1], -dz * F[0], -T - (dx * F[1] - dy * F[0])
    race_force[0] -= F[0]
    race_force[1] -= F[1]
    race_moment[0] += mx
    race_moment[1] += my
    race_moment[2] += mz
    # the pair's power: the cage's relative motion, less the race's turning under d x F
    return (F[0] * vel0 + F[1] * vel1 + T * (cage.w[2] - w_race_z)
            + mx * race.w[0] + my * race.w[1] + (mz + T) * race.w[2])


@numba.njit(**KERNEL)
def journal_tangent(jres, Kb, Cb):
    """The cage–land journal's tangents into Kb, Cb, the cage's own 6x6 blocks, from the row
    `journal_forces` left in jres."""
    # offsets typed int64, not Literal[int]: numba compiles a callee once per literal argument
    _subtract_planar(Kb, jres, np.int64(J_OUT_DF_DPOS), np.int64(J_OUT_DT_DPOS))
    _subtract_planar(Cb, jres, np.int64(J_OUT_DF_DVEL), np.int64(J_OUT_DT_DVEL))
    Cb[0, 5] -= jres[J_OUT_DF_DOMEGA_CAGE]
    Cb[1, 5] -= jres[J_OUT_DF_DOMEGA_CAGE + 1]
    Cb[5, 5] -= jres[J_OUT_DT_DOMEGA_CAGE]


@numba.njit(**KERNEL)
def journal_race_tangent(jres, Kb, Cb):
    """The tangents that tie an inner-guided cage to the inner race into the border blocks Kb,
    Cb (`linear_solvers.Blocks.B`), from the row `journal_forces` left in jres: the journal
    acts on the offset and velocity of the cage relative to the race, and its reaction on the
    race is the opposite force and torque about z (the small lever d x F is left out of the
    tangents). The cage's own block is `journal_tangent`'s."""
    c, r = np.int64(CAGE_BORDER), np.int64(INNER_BORDER)
    for M, i_force, i_torque in ((Kb, np.int64(J_OUT_DF_DPOS), np.int64(J_OUT_DT_DPOS)),
                                 (Cb, np.int64(J_OUT_DF_DVEL), np.int64(J_OUT_DT_DVEL))):
        for i in range(2):
            for j in range(2):
                d = jres[i_force + 2 * i + j]
                M[c + i, r + j] += d  # the cage's force against the race's position
                M[r + i, c + j] += d  # the race's force (-F) against the cage's position
                M[r + i, r + j] -= d
            dt = jres[i_torque + i]
            M[c + 5, r + i] += dt
            M[r + 5, c + i] += dt
            M[r + 5, r + i] -= dt
    # the race's spin (its material z rate) enters the film through omega_race
    for i in range(2):
        Cb[c + i, r + 5] -= jres[J_OUT_DF_DOMEGA_RACE + i]
        Cb[r + i, r + 5] += jres[J_OUT_DF_DOMEGA_RACE + i]
        Cb[r + i, c + 5] += jres[J_OUT_DF_DOMEGA_CAGE + i]
    Cb[c + 5, r + 5] -= jres[J_OUT_DT_DOMEGA_RACE]
    Cb[r + 5, r + 5] += jres[J_OUT_DT_DOMEGA_RACE]
    Cb[r + 5, c + 5] += jres[J_OUT_DT_DOMEGA_CAGE]


@numba.njit(**KERNEL)
def _subtract_planar(M, out, i_force, i_torque):
    """M -= the cage block of d(F_x, F_y, T)/d(x, y) (or of the velocities): rows 0, 1
    (force, row-major 2x2 at out[i_force]) and 5 (torque, out[i_torque:i_torque+2])."""
    for i in range(2):
        for j in range(2):
            M[i, j] -= out[i_force + 2 * i + j]
        M[5, i] -= out[i_torque + i]


@numba.njit(**NO_REFCOUNT)
def pocket_diag(pres, diag, d):
    """Ball k's pocket channels (channels.PER_BALL, from diag[d]) from its contact row."""
    diag[d + DB_POCKET] = pres[P_OUT_FN]
    diag[d + DB_POCKET_IN_CONTACT] = pres[P_OUT_IN_CONTACT]
    diag[d + DB_POCKET_APPROACH] = pres[P_OUT_APPROACH]
    diag[d + DB_POCKET_ORBITAL] = pres[P_OUT_ORBITAL_POSITION]
    diag[d + DB_POCKET_FRICTION_POWER] = pres[P_OUT_FRICTION_POWER]


@numba.njit(**KERNEL)
def journal_diag(jres, diag):
    """The cage-land channels (channels.GLOBAL) from the `cage_race_journal` row."""
    diag[DG_EPS] = jres[J_OUT_EPS]
    diag[DG_FX] = jres[J_OUT_FORCE]
    diag[DG_FY] = jres[J_OUT_FORCE + 1]
    diag[DG_TORQUE] = jres[J_OUT_TORQUE]
    diag[DG_METAL] = jres[J_OUT_METAL_FORCE]
    diag[DG_FRICTION_POWER] = jres[J_OUT_FRICTION_POWER]
    diag[DG_AZIMUTH] = jres[J_OUT_CONTACT_AZIMUTH]
    diag[DG_FILM_POWER] = jres[J_OUT_FILM_POWER]
    diag[DG_MIN_FILM] = jres[J_OUT_MIN_FILM]
