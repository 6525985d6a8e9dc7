"""Ball–race contact geometry and kinematics: torus–sphere (docs/model.md §6.1, paper eqs. 21–23).

`ball_race_contact_kernel` is the numba kernel the dynamic model calls (2Z times per
residual). It writes its results into a caller-owned float64 array of length
`CONTACT_OUT_SIZE` (no allocation); the `OUT_*` constants index it.
`ball_race_contact_reference` is its slow twin, written independently in global-frame
vector algebra, and `ball_race_contact` a convenience wrapper returning a dict.

Conventions
-----------
- Race frame: origin at the race centre `x_r`, axes the columns of `R_r` (global ←
  local), local z = race axis, groove plane z = 0. Ball centre in the race frame
  (X̂, Ŷ, Ẑ), ρ = √(X̂² + Ŷ²), γ = atan2(Ŷ, X̂).
- Groove curvature centre C at radius d/2 in the plane through the axis and the ball.
  s = |C − x_b|; δ = s + D/2 − r (M.24's approach; δ ≤ 0 means no contact) — the same
  expression for inner and outer race (both grooves are concave).
- Unit normal n = (C − x_b)/s points from the contact towards the ball centre (the
  contact lies on the far side of the ball from C). Contact point p = x_b − (D/2 − δ/2) n
  (middle of the overlap).
- Contact angle α (signed, radians): angle of the load line to the radial plane,
  **positive when the outer contact lies on the +z side of the ball centre and the inner
  contact on the −z side** — i.e. the contact carries a +z thrust applied to the inner
  race. Inner race: α = atan2(−Ẑ, d_i/2 − ρ); outer race: α = atan2(Ẑ, ρ − d_o/2).
  (docs/model.md writes tan α = Ẑ/(d_i/2 − ρ) for the inner race; the sign is flipped here so
  that inner and outer angles of one loaded ball agree in sign.)
- Kinematics (§6.1): material velocity of each body at p, taken relative to the contact
  point itself (which moves with the ball centre and turns about the race axis at the
  ball's orbital rate Ω = (v_b − v_r)·e_t/ρ) — otherwise a ball rolling on a fixed outer
  race would show zero entrainment; tangent projections u_b, u_r; sliding = u_b − u_r
  (frame-independent); mean rolling (entrainment) velocity = (u_b + u_r)/2, u_s =
  |u_b + u_r| (sum of surface speeds); spin ω_s = (ω_b − ω_r)·n; slide-to-roll ratio =
  |sliding| / |mean rolling| (0 when both vanish, inf when only rolling vanishes).
  Local frame: e_x along the entrainment velocity (falls back to the race's
  circumferential direction when it vanishes), e_y = n × e_x (across, groove direction).
"""

from __future__ import annotations

import math

import numba
import numpy as np

from .._speed.compile_policy import NO_REFCOUNT

OUT_DELTA = 0  # δ [m]
OUT_ALPHA = 1  # α [rad]
OUT_N = 2  # n (3) [-]
OUT_P = 5  # contact point p (3) [m]
OUT_U_ROLL = 8  # mean rolling velocity vector (3) [m/s]
OUT_U_SUM = 11  # u_s, sum of surface speeds [m/s]
OUT_SLIDE = 12  # sliding velocity ball − race in the tangent plane (3) [m/s]
OUT_SPIN = 15  # ω_s [rad/s]
OUT_SRR = 16  # slide-to-roll ratio [-]
OUT_EX = 17  # e_x (3)
OUT_EY = 20  # e_y (3)
OUT_LEVER = 23  # s = |C − x_b| [m], the lever of the normal's rotation (M.34)
OUT_CENTER = 24  # groove curvature centre C (3) [m]
CONTACT_OUT_SIZE = 27


@numba.njit(**NO_REFCOUNT)
def ball_race_contact_kernel(x_b, v_b, w_b, x_r, R_r, v_r, w_r, d_groove, r_groove, D, is_outer, out):
    """Torus–sphere contact of one ball with one race (docs/model.md §6.1, eqs. 21–23).

    x_b, v_b, w_b: ball centre [m], velocity [m/s], angular velocity [rad/s] (global).
    x_r, R_r, v_r, w_r: race centre [m], rotation (3×3, global ← race), velocity, angular
    velocity (global). d_groove: curvature-centre circle diameter d [m]; r_groove: groove
    radius r [m]; D: ball diameter [m]; is_outer: True for the outer race.
    out: float64[CONTACT_OUT_SIZE], filled per the OUT_* layout (see module doc).
    """
    # ball centre in the race frame: X = R_rᵀ (x_b − x_r)
    dx0, dx1, dx2 = x_b[0] - x_r[0], x_b[1] - x_r[1], x_b[2] - x_r[2]
    X = R_r[0, 0] * dx0 + R_r[1, 0] * dx1 + R_r[2, 0] * dx2
    Y = R_r[0, 1] * dx0 + R_r[1, 1] * dx1 + R_r[2, 1] * dx2
    Zh = R_r[0, 2] * dx0 + R_r[1, 2] * dx1 + R_r[2, 2] * dx2
    rho = math.sqrt(X * X + Y * Y)
    if rho > 0.0:
        cg, sg = X / rho, Y / rho
    else:  # ball on the axis: any plane will do
        cg, sg = 1.0, 0.0
    half_d = 0.5 * d_groove
    w_rad = half_d - rho  # (C − x_b) in (e_r, e_z) of the race frame
    w_ax = -Zh
    s = math.sqrt(w_rad * w_rad + w_ax * w_ax)
    delta = s + 0.5 * D - r_groove
    if is_outer:
        alpha = math.atan2(Zh, rho - half_d)
    else:
        alpha = math.atan2(-Zh, half_d - rho)
    n_rad, n_ax = w_rad / s, w_ax / s
    # local unit vectors → global: e_r, e_t (circumferential), e_z
    er0 = R_r[0, 0] * cg + R_r[0, 1] * sg
    er1 = R_r[1, 0] * cg + R_r[1, 1] * sg
    er2 = R_r[2, 0] * cg + R_r[2, 1] * sg
    et0 = -R_r[0, 0] * sg + R_r[0, 1] * cg
    et1 = -R_r[1, 0] * sg + R_r[1, 1] * cg
    et2 = -R_r[2, 0] * sg + R_r[2, 1] * cg
    n0 = n_rad * er0 + n_ax * R_r[0, 2]
    n1 = n_rad * er1 + n_ax * R_r[1, 2]
    n2 = n_rad * er2 + n_ax * R_r[2, 2]
    out[OUT_CENTER] = x_r[0] + half_d * er0
    out[OUT_CENTER + 1] = x_r[1] + half_d * er1
    out[OUT_CENTER + 2] = x_r[2] + half_d * er2
    depth = 0.5 * D - 0.5 * delta
    p0, p1, p2 = x_b[0] - depth * n0, x_b[1] - depth * n1, x_b[2] - depth * n2
    # material velocities at p: v + ω × (p − x)
    a0, a1, a2 = p0 - x_b[0], p1 - x_b[1], p2 - x_b[2]
    vb0 = v_b[0] + w_b[1] * a2 - w_b[2] * a1
    vb1 = v_b[1] + w_b[2] * a0 - w_b[0] * a2
    vb2 = v_b[2] + w_b[0] * a1 - w_b[1] * a0
    a0, a1, a2 = p0 - x_r[0], p1 - x_r[1], p2 - x_r[2]
    vr0 = v_r[0] + w_r[1] * a2 - w_r[2] * a1
    vr1 = v_r[1] + w_r[2] * a0 - w_r[0] * a2
    vr2 = v_r[2] + w_r[0] * a1 - w_r[1] * a0
    # surface velocities relative to the contact point, which moves with the ball centre and
    # turns about the race axis at the ball's orbital rate Ω = (v_b − v_r)·e_t / ρ
    orbit = ((v_b[0] - v_r[0]) * et0 + (v_b[1] - v_r[1]) * et1 + (v_b[2] - v_r[2]) * et2) / rho if rho > 0.0 else 0.0
    ax0, ax1, ax2 = orbit * R_r[0, 2], orbit * R_r[1, 2], orbit * R_r[2, 2]
    a0, a1, a2 = p0 - x_b[0], p1 - x_b[1], p2 - x_b[2]
    vc0 = v_b[0] + ax1 * a2 - ax2 * a1
    vc1 = v_b[1] + ax2 * a0 - ax0 * a2
    vc2 = v_b[2] + ax0 * a1 - ax1 * a0
    vb0, vb1, vb2 = vb0 - vc0, vb1 - vc1, vb2 - vc2
    vr0, vr1, vr2 = vr0 - vc0, vr1 - vc1, vr2 - vc2
    # tangent projections
    nb = vb0 * n0 + vb1 * n1 + vb2 * n2
    nr = vr0 * n0 + vr1 * n1 + vr2 * n2
    ub0, ub1, ub2 = vb0 - nb * n0, vb1 - nb * n1, vb2 - nb * n2
    ur0, ur1, ur2 = vr0 - nr * n0, vr1 - nr * n1, vr2 - nr * n2
    sl0, sl1, sl2 = ub0 - ur0, ub1 - ur1, ub2 - ur2
    m0, m1, m2 = 0.5 * (ub0 + ur0), 0.5 * (ub1 + ur1), 0.5 * (ub2 + ur2)
    mean_speed = math.sqrt(m0 * m0 + m1 * m1 + m2 * m2)
    slide_speed = math.sqrt(sl0 * sl0 + sl1 * sl1 + sl2 * sl2)
    if mean_speed > 0.0:
        ex0, ex1, ex2 = m0 / mean_speed, m1 / mean_speed, m2 / mean_speed
        srr = slide_speed / mean_speed
    else:
        # circumferential direction, projected on the tangent plane (it already is: e_t ⟂ n)
        ex0, ex1, ex2 = et0, et1, et2
        srr = 0.0 if slide_speed == 0.0 else math.inf
    out[OUT_DELTA] = delta
    out[OUT_ALPHA] = alpha
    out[OUT_N], out[OUT_N + 1], out[OUT_N + 2] = n0, n1, n2
    out[OUT_P], out[OUT_P + 1], out[OUT_P + 2] = p0, p1, p2
    out[OUT_U_ROLL], out[OUT_U_ROLL + 1], out[OUT_U_ROLL + 2] = m0, m1, m2
    out[OUT_U_SUM] = 2.0 * mean_speed
    out[OUT_SLIDE], out[OUT_SLIDE + 1], out[OUT_SLIDE + 2] = sl0, sl1, sl2
    out[OUT_SPIN] = (w_b[0] - w_r[0]) * n0 + (w_b[1] - w_r[1]) * n1 + (w_b[2] - w_r[2]) * n2
    out[OUT_SRR] = srr
    out[OUT_EX], out[OUT_EX + 1], out[OUT_EX + 2] = ex0, ex1, ex2
    out[OUT_EY] = n1 * ex2 - n2 * ex1
    out[OUT_EY + 1] = n2 * ex0 - n0 * ex2
    out[OUT_EY + 2] = n0 * ex1 - n1 * ex0
    out[OUT_LEVER] = s


_NAMES = {
    "delta": (OUT_DELTA, 1), "alpha": (OUT_ALPHA, 1), "normal": (OUT_N, 3), "point": (OUT_P, 3),
    "rolling_velocity": (OUT_U_ROLL, 3), "u_sum": (OUT_U_SUM, 1), "sliding_velocity": (OUT_SLIDE, 3),
    "spin": (OUT_SPIN, 1), "slide_roll_ratio": (OUT_SRR, 1), "e_x": (OUT_EX, 3), "e_y": (OUT_EY, 3),
    "lever": (OUT_LEVER, 1), "curvature_center": (OUT_CENTER, 3),
}


def unpack_contact(out: np.ndarray) -> dict:
    """Name the entries of a kernel output array (floats and 3-vectors)."""
    return {k: (float(out[i]) if n == 1 else np.array(out[i:i + n])) for k, (i, n) in _NAMES.items()}


def ball_race_contact(x_b, v_b, w_b, x_r, R_r, v_r, w_r, d_groove, r_groove, D, is_outer) -> dict:
    """Convenience wrapper of `ball_race_contact_kernel` returning a dict of named outputs."""
    out = np.empty(CONTACT_OUT_SIZE)
    f64 = lambda a: np.ascontiguousarray(a, dtype=np.float64)  # noqa: E731
    ball_race_contact_kernel(f64(x_b), f64(v_b), f64(w_b), f64(x_r), f64(R_r), f64(v_r), f64(w_r),
                             float(d_groove), float(r_groove), float(D), bool(is_outer), out)
    return unpack_contact(out)


def ball_race_contact_reference(x_b, v_b, w_b, x_r, R_r, v_r, w_r, d_groove, r_groove, D, is_outer) -> dict:
    """Slow twin of the kernel in global-frame vector algebra (numpy), for tests."""
    x_b, v_b, w_b, x_r, v_r, w_r = (np.asarray(a, dtype=float) for a in (x_b, v_b, w_b, x_r, v_r, w_r))
    axis = np.asarray(R_r, dtype=float)[:, 2]
    rel = x_b - x_r
    z_hat = rel @ axis
    radial = rel - z_hat * axis
    rho = np.linalg.norm(radial)
    e_r = radial / rho if rho > 0 else np.asarray(R_r, dtype=float)[:, 0]
    center = x_r + 0.5 * d_groove * e_r
    w = center - x_b
    s = np.linalg.norm(w)
    n = w / s
    delta = s + 0.5 * D - r_groove
    if is_outer:
        alpha = math.atan2(z_hat, rho - 0.5 * d_groove)
    else:
        alpha = math.atan2(-z_hat, 0.5 * d_groove - rho)
    p = x_b - (0.5 * D - 0.5 * delta) * n
    tangent = np.eye(3) - np.outer(n, n)
    e_t = np.cross(axis, e_r)
    v_contact = v_b + np.cross(((v_b - v_r) @ e_t / rho) * axis, p - x_b)
    u_b = tangent @ (v_b + np.cross(w_b, p - x_b) - v_contact)
    u_r = tangent @ (v_r + np.cross(w_r, p - x_r) - v_contact)
    mean = 0.5 * (u_b + u_r)
    slide = u_b - u_r
    speed = np.linalg.norm(mean)
    e_x = mean / speed if speed > 0 else np.cross(axis, e_r)
    return {
        "delta": delta, "alpha": alpha, "normal": n, "point": p, "rolling_velocity": mean,
        "u_sum": 2.0 * speed, "sliding_velocity": slide, "spin": float((w_b - w_r) @ n),
        "slide_roll_ratio": (np.linalg.norm(slide) / speed) if speed > 0 else (0.0 if not slide.any() else math.inf),
        "e_x": e_x, "e_y": np.cross(n, e_x), "lever": s, "curvature_center": center,
    }
