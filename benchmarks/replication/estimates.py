"""Closed-form estimates of how much the inner race of a ball bearing under thrust and moment
should move, set beside what the dynamic model does (docs/replication.md, "The inner race").

Two sources of ball-passage vibration, for rigid rings whose balls carry the quasi-static loads:

* **Varying compliance.** With the balls evenly spaced, every resultant on the inner race is a
  sum over the balls of a function of the ball's orbital position, f(psi_j + phi), phi the
  ball set's rotation. The sum depends on phi only through the Fourier harmonics of f whose order
  is a multiple of Z, so the force it varies by as the set turns by one ball pitch comes from
  harmonics of order Z - 1 and above. Under thrust and moment with every ball loaded, the Hertz
  load pattern Q(psi) = Q_0 (1 + k cos psi)^(3/2) (deflection linear in cos psi, k < 1) is
  analytic, and its n-th harmonic falls like n^(-5/2) rho^n with rho = (1 - sqrt(1 - k^2))/k
  (rho = exp(-acosh(1/k)): the branch point cos psi = -1/k, of order 3/2, bounds the strip in
  which Q is analytic). Only a load zone that ends
  (k > 1: balls unloaded over part of the orbit) gives the kink whose harmonics reach order Z.
* **Ball-spacing scatter.** Balls move in their pockets, so they are not evenly spaced. A ball
  displaced along its orbit by an angle delta turns its contact force F_j and moment M_j about
  the bearing axis: dF = delta e_z x F_j, dM = delta e_z x M_j. The inner race answers with
  x = C dF, C = (K_bearing + K_hinge)^-1, quasi-statically (its natural frequencies, kHz, are far
  above the ball-passage ones). For independent spacing errors of rms sigma the covariance of
  the load is sigma^2 sum_j g_j g_j^T, g_j = e_z x (F_j, M_j).

Only numpy: a test loads this file directly (tests/test_replication_estimates.py).
"""

from __future__ import annotations

import math

import numpy as np


def ball_loads_on_inner_race(load, contact_angle, azimuth, contact_radius):
    """The force and moment of each ball on the inner race, rows (F_x, F_y, F_z, M_x, M_y) [N, N m].

    `load` Q_j [N], `contact_angle` alpha_j [rad] (+: carries a +z thrust on the inner race, so the
    ball pushes the race towards -z), `azimuth` psi_j [rad], `contact_radius` r_j [m] (radius of
    the inner contact). The ball pushes the race inwards along -e_r and axially along -e_z; the
    moment is that of the axial part at r_j (the radial part's lever, the contact's small axial
    offset, is neglected)."""
    q, a, psi, r = (np.asarray(v, dtype=float) for v in (load, contact_angle, azimuth, contact_radius))
    er = np.stack([np.cos(psi), np.sin(psi)], axis=-1)
    et = np.stack([-np.sin(psi), np.cos(psi)], axis=-1)
    radial = -(q * np.cos(a))[:, None] * er
    axial = -(q * np.sin(a))
    moment = (q * np.sin(a) * r)[:, None] * et  # r e_r x (F_z e_z) = -F_z r e_t
    return np.column_stack([radial, axial, moment])


def spacing_sensitivity(loads5: np.ndarray) -> np.ndarray:
    """g_j = d(F_j, M_j)/d psi_j: the change of each ball's load on the race per radian it moves
    along its orbit, its force and moment turned about e_z (rows as `ball_loads_on_inner_race`)."""
    f = np.asarray(loads5, dtype=float)
    g = np.zeros_like(f)
    g[:, 0], g[:, 1] = -f[:, 1], f[:, 0]
    g[:, 3], g[:, 4] = -f[:, 4], f[:, 3]
    return g


def compliance(bearing_stiffness: np.ndarray, hinge_diagonal) -> np.ndarray:
    """C = (K_bearing + K_hinge)^-1, order (x, y, z, rot_x, rot_y) [m/N, rad/(N m)]."""
    return np.linalg.inv(np.asarray(bearing_stiffness, dtype=float) + np.diag(np.asarray(hinge_diagonal, dtype=float)))


def scatter_radial_rms(g: np.ndarray, c: np.ndarray, sigma: float) -> float:
    """rms radial displacement [m] of the inner race for independent spacing errors of rms
    `sigma` [rad] on every ball: sqrt(trace of the x-y block of C S C^T), S = sigma^2 sum g g^T."""
    s = sigma ** 2 * (g.T @ g)
    cov = c @ s @ c.T
    return math.sqrt(cov[0, 0] + cov[1, 1])


def spacing_deviation(azimuth: np.ndarray, bins: int = 72) -> tuple[np.ndarray, np.ndarray]:
    """The balls' departure from even spacing, (t, Z) [rad], without the part fixed in space.

    `azimuth` (t, Z): each ball's orbital position (ball k starts at 2 pi k/Z; balls keep their
    order). The deviation of ball k is its position minus 2 pi k/Z minus the circular mean of
    that difference over the set (a common rotation moves no load). What a ball's deviation
    owes to where it is on the orbit (the steady excursion pattern of the moment, fixed in space)
    is a smooth function of position: its sum over the balls, like any smooth pattern's, is
    steady, so it offsets the race but does not shake it. It is removed as the mean deviation
    per bin of orbital position. Returns (full deviation, fluctuating part)."""
    psi = np.asarray(azimuth, dtype=float)
    z = psi.shape[1]
    d = psi - 2.0 * math.pi * np.arange(z) / z
    common = np.angle(np.exp(1j * d).mean(axis=1))
    dev = np.angle(np.exp(1j * (d - common[:, None])))
    where = np.floor(np.mod(psi, 2.0 * math.pi) / (2.0 * math.pi) * bins).astype(int) % bins
    mean = np.bincount(where.ravel(), dev.ravel(), bins) / np.maximum(np.bincount(where.ravel(), None, bins), 1)
    return dev, dev - mean[where]


def spacing_response(g_of_psi, azimuth: np.ndarray, deviation: np.ndarray, c: np.ndarray) -> np.ndarray:
    """Quasi-static displacement (t, 5) of the inner race answering the load change sum_j
    g(psi_j) delta_j at every sample; `g_of_psi(psi)` gives g for an array of positions."""
    psi = np.asarray(azimuth, dtype=float)
    t, z = psi.shape
    g = g_of_psi(psi.ravel()).reshape(t, z, 5)
    df = np.einsum("tzk,tz->tk", g, deviation)
    return df @ c.T


def hertz_pattern_ratio(q_min: float, q_max: float) -> float:
    """k of Q(psi) = Q_0 (1 + k cos psi)^(3/2) with the given extremes (deflection linear in cos psi)."""
    r = (q_max / q_min) ** (2.0 / 3.0)
    return (r - 1.0) / (r + 1.0)


def harmonic_decay(k: float) -> float:
    """rho of |c_n| ~ n^(-5/2) rho^n for the harmonics of (1 + k cos psi)^(3/2), 0 < k < 1."""
    return (1.0 - math.sqrt(1.0 - k * k)) / k


def varying_compliance_force(k: float, balls: int, mean_load: float, contact_angle: float,
                             samples: int = 401) -> float:
    """Peak-to-peak [N] of the radial resultant of the evenly spaced balls' loads
    Q_0 max(1 + k cos psi, 0)^(3/2) as the set turns through one ball pitch (the loads of the
    rigid-ring pattern held; the race's response to it is this over its stiffness). Q_0 is set so
    that the mean load is `mean_load`."""
    grid = np.linspace(0.0, 2.0 * math.pi, 4096, endpoint=False)
    q0 = mean_load / np.mean(np.maximum(1.0 + k * np.cos(grid), 0.0) ** 1.5)
    phi = np.linspace(0.0, 2.0 * math.pi / balls, samples)
    psi = phi[:, None] + 2.0 * math.pi * np.arange(balls) / balls
    q = q0 * np.maximum(1.0 + k * np.cos(psi), 0.0) ** 1.5 * math.cos(contact_angle)
    fx, fy = (q * np.cos(psi)).sum(axis=1), (q * np.sin(psi)).sum(axis=1)
    return float(max(np.ptp(fx), np.ptp(fy)))
