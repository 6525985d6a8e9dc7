"""Fast Eyring traction (docs/model.md §6.4): agreement with the quadrature reference, kernels vs twins.

Error metrics (the 2 % target of the fast path, docs/model.md §6.4):
- force: |F_fast - F_ref| / |F_ref| (vector norm, so each component is held relative to |F|);
  for pure spin (F_ref = 0 by symmetry) relative to |M_ref| / b instead;
- spin moment: |M_fast - M_ref| / max(|M_ref|, |F_ref| b): M_z is often a small difference
  of large opposite contributions (pole near the edge), then |F| b is its natural scale;
- Jacobian: max |J_fast - J_ref| / max |J_ref| <= 3 % (documented tolerance: Newton only
  needs a consistent approximate tangent; measured <= 1.4 %).
The reference is `traction_quadrature` on the (128, 1024) grid, itself within 0.3 % of
converged except right at a spin pole in the centre (0.4 %, tests/test_traction.py).
"""

import dataclasses
import math

import numpy as np
import pytest

from bearingsim.dynamics.lubrication.film_laws import nvm as film
from bearingsim.dynamics.traction import nodes as traction_nodes
from bearingsim.dynamics.traction import quadrature as traction
from bearingsim.dynamics.lubrication.lubricant import load_builtin_lubricant
from bearingsim.dynamics.traction.fast import (
    FLAG_NO_CONTACT, FLAG_OK, FLAG_PRESSURE_CLAMPED, FLAG_SLIP_CLAMPED, FLAG_UNVALIDATED, FastTraction,
    _Nodes, _NodeValues, _Slip,
    _accumulate_force_g, _accumulate_response, _eyring_argument, _eyring_response,
    _lerp_eyring_argument32, _slip_and_table_index, _slip_and_table_row32,
    _stress_factor32, _viscosity_lookup, traction_fast,
)
from bearingsim.dynamics._speed.simd_math import log_array, log_array32
from bearingsim.dynamics.traction.laws.eyring import SERIES_X
from bearingsim.dynamics._speed.table_lookup import pick_rows
from tests.simd_reference import lerp_fma_reference
from tests.lubrication_points import (
    curvature_radii, E_EFF, hertz_ellipse, random_operating_points, rolling_speed,
)

REF_GRID = (128, 1024)
TOL_F = TOL_M = 0.02  # docs/model.md §6.4: the fast path must agree with the quadrature within 2 %
TOL_J = 0.03


@pytest.fixture(scope="module")
def o156():
    return load_builtin_lubricant("nato-o156")


@pytest.fixture(scope="module")
def fast(o156):
    return FastTraction.build(o156)


def _ref(lub, point, grid=REF_GRID):
    a, b, p_h, h, du0, dv0, w_s = point
    return traction.traction_quadrature(a, b, p_h, h, lub.eyring_stress, lub.model_code,
                                        lub.rheology_params(), du0, dv0, w_s, grid)


def _errors(fast_result, ref, b):
    """(force, moment, Jacobian) errors with the metrics of the module docstring."""
    f, J = fast_result[0], fast_result[1]
    Fx, Fy, Mz, Jr = ref
    scale_F = math.hypot(Fx, Fy)
    if scale_F < 1e-9 * abs(Mz) / b:  # pure spin: no net force by symmetry
        scale_F = abs(Mz) / b
    eF = math.hypot(f[0] - Fx, f[1] - Fy) / scale_F
    eM = abs(f[2] - Mz) / max(abs(Mz), math.hypot(Fx, Fy) * b)
    eJ = np.abs(J - Jr).max() / np.abs(Jr).max()
    return eF, eM, eJ


def _contact(lub, race, angle, load, speed_factor):
    """(a, b, p_h, h, u) of a reference-bearing contact (tests/lubrication_points.py)."""
    Rx, Ry = curvature_radii(race, angle)
    a, b, p_h = hertz_ellipse(load, Rx, Ry)
    u = rolling_speed(angle, speed_factor)
    h = film.film_central_nvm(load, Rx, Ry, E_EFF, lub.eta0, lub.alpha_star, 2.0 * u)
    return a, b, p_h, h, u


def _edge_cases(lub):
    """Ends of the operating range (brief F): tiny and maximum slip, pure spin, pure roll,
    very light load, spin pole just inside and just outside the ellipse edge."""
    cases = []
    for race, load in [("inner", 3000.0), ("outer", 100.0), ("inner", 20.0)]:
        a, b, p_h, h, u = _contact(lub, race, 30.0, load, 1.0)
        w = 0.03 * u / b
        cases += [(a, b, p_h, h, 1e-5 * u, 0.0, w), (a, b, p_h, h, 0.3 * u, 0.0, w),
                  (a, b, p_h, h, -0.3 * u, 0.05 * u, -w), (a, b, p_h, h, 0.0, 0.0, w),
                  (a, b, p_h, h, 1e-5 * u, 0.0, 0.0), (a, b, p_h, h, 0.0, 0.0, 0.0)]
        for rho in (0.97, 1.03):  # pole at rho ellipse radii, 40 deg off the y axis
            X, Y = rho * math.sin(0.7), rho * math.cos(0.7)
            cases.append((a, b, p_h, h, w * b * Y, -w * a * X, w))
    return cases


def _assert_agrees(lub, fast, points, tol_f=TOL_F, tol_m=TOL_M, tol_j=TOL_J):
    worst = np.zeros(3)
    rule32, force_only = fast.traction_rule(float32_residual=True), np.empty(12)  # the time loop's rule
    for point in points:
        ref = _ref(lub, point)
        got = fast.evaluate(*point)
        assert got[2] == FLAG_OK, point
        worst = np.maximum(worst, _errors(got, ref, point[1]) if any(ref[:3]) else
                           (0.0, 0.0, np.abs(got[1] - ref[3]).max() / np.abs(ref[3]).max()))
        # the time loop's common call: force and moment only, through the float32 passes
        assert traction_fast(*(float(v) for v in point), 0.0, rule32, force_only, False) == FLAG_OK
        if any(ref[:3]):
            worst = np.maximum(worst, _errors((force_only[:3], got[1]), ref, point[1]))
        else:
            assert not force_only[:3].any()
    print(f"fast vs quadrature over {len(points)} points: F {worst[0]:.2e}, M {worst[1]:.2e}, J {worst[2]:.2e}")
    assert worst[0] < tol_f and worst[1] < tol_m and worst[2] < tol_j


def test_fast_matches_quadrature_over_operating_range(o156, fast):
    points = random_operating_points(40, seed=5, lubricant=o156, film=film.film_central_nvm)
    _assert_agrees(o156, fast, points + _edge_cases(o156))


def _poles_just_outside(lub):
    """Spin pole a hair outside the ellipse edge, from the end of the major axis (across the
    rolling direction) round to the minor axis: where the cone rule's chords fan over almost
    half a turn while the contact lies in a narrow angle of them. Found in case b's inner-race
    contacts at t = 0.349 s (a/b 0.085, p_h 1.8 GPa): with 24 chords the force was 15 % and
    the spin moment 12 % off there (docs/model.md §6.4)."""
    cases = []
    for race, load in [("inner", 3000.0), ("outer", 1000.0)]:
        a, b, p_h, h, u = _contact(lub, race, 30.0, load, 1.0)
        w = 0.03 * u / b
        for rho in (1.0 + 1e-6, 1.003, 1.01):
            for off_axis in (0.0, 0.1, 0.3, 0.8, 1.5):  # rad from the -y axis
                X, Y = rho * math.sin(off_axis), -rho * math.cos(off_axis)
                cases.append((a, b, p_h, h, w * b * Y, -w * a * X, w))
    return cases


def test_fast_matches_quadrature_with_the_pole_just_outside_the_edge(o156, fast):
    _assert_agrees(o156, fast, _poles_just_outside(o156))


@pytest.mark.slow
@pytest.mark.parametrize("seed", [2024, 7])
def test_fast_matches_quadrature_on_240_random_points(o156, fast, seed):
    # measured (default rule): F <= 0.74 %, M <= 0.76 %, J <= 1.4 % on each of these samples
    points = random_operating_points(240, seed=seed, lubricant=o156, film=film.film_central_nvm)
    _assert_agrees(o156, fast, points)


def test_newtonian_limit_matches_closed_form(o156):
    # docs/model.md §6.4: Barus, no spin, tau0 -> inf: f = 3 eta0 du [e^s (s-1) + 1]/(h p_h s^2), s = alpha p_h
    lub = dataclasses.replace(o156.as_barus(), eyring_stress=1e15)
    a, b, p_h, h, du = 2e-4, 1.5e-3, 1.2e9, 2e-7, 0.01
    f, _, _ = FastTraction.build(lub).evaluate(a, b, p_h, h, du, 0.0, 0.0)
    s = lub.alpha_star * p_h
    f_closed = 3 * lub.eta0 * du * (math.exp(s) * (s - 1) + 1) / (h * p_h * s * s)
    W = 2.0 / 3.0 * math.pi * a * b * p_h
    # 1e-3: the eta table is linearly interpolated (relative error ~1e-4, module docstring)
    assert -f[0] / W == pytest.approx(f_closed, rel=1e-3)


def test_eyring_plateau_matches_closed_form(o156):
    # docs/model.md §6.4: f = (tau0/pbar) ln(2 eta0 du/(tau0 h)) + alpha tau0, pbar = 2 p_h/3, valid
    # when eta0 du/(tau0 h) >> 1 everywhere (here 100: asinh x - ln 2x < 1/(4 x^2) = 2.5e-5)
    lub = dataclasses.replace(o156.as_barus(), eyring_stress=1e6, ambient_viscosity=1.0,
                              pressure_viscosity_coefficient=1e-8)
    a, b, p_h, h, du = 2e-4, 1.5e-3, 1.0e9, 1e-7, 10.0
    f, _, _ = FastTraction.build(lub).evaluate(a, b, p_h, h, du, 0.0, 0.0)
    W = 2.0 / 3.0 * math.pi * a * b * p_h
    f_closed = lub.eyring_stress / (2 * p_h / 3) * math.log(2 * 1.0 * du / (1e6 * h)) + 1e-8 * 1e6
    assert -f[0] / W == pytest.approx(f_closed, rel=1e-4)


@pytest.mark.parametrize("pole", [(0.0, 0.0), (0.3, -0.5), (0.0, 0.96), (0.7, 0.75), (1.05, 0.1), (0.0, 2.5), (5.0, 3.0)])
def test_rules_integrate_area_and_second_moments(fast, pole):
    # every rule must integrate 1, X^2 and Y^2 over the ellipse: pi a b, pi a b/4, pi a b/4
    a, b, w_s = 2.5e-4, 2.4e-3, 100.0
    X_p, Y_p = pole
    du0, dv0 = w_s * b * Y_p, -w_s * a * X_p
    work, _ = fast.workspace()
    n = traction_nodes.place_nodes(a, b, du0, dv0, w_s, fast.rule, work[0], work[1], work[2], work[3:8])
    X, Y, W = work[0, :n], work[1, :n], work[2, :n]
    area = math.pi * a * b
    assert W.sum() == pytest.approx(area, rel=2e-3)
    assert (W * X * X).sum() == pytest.approx(area / 4, rel=5e-3)
    assert (W * Y * Y).sum() == pytest.approx(area / 4, rel=5e-3)
    assert np.all(X * X + Y * Y <= 1.0 + 1e-12)


def test_fast_jacobian_matches_finite_differences_of_reference(o156, fast):
    for point in ([2.5e-4, 2.4e-3, 1.6e9, 2.5e-7, 0.02, -0.01, 60.0],   # pole outside
                  [2.5e-4, 2.4e-3, 1.6e9, 2.5e-7, 2e-4, -1e-5, 600.0],  # pole inside
                  [1e-4, 1.2e-3, 6e8, 1e-7, 0.3, 0.02, 5.0]):           # light load, pole far
        _, J, _ = fast.evaluate(*point)
        for col in range(3):
            d = 1e-4 * max(abs(point[4 + col]), 1e-3 if col < 2 else 1.0)
            hi, lo = list(point), list(point)
            hi[4 + col] += d
            lo[4 + col] -= d
            fd = (np.array(_ref(o156, hi)[:3]) - np.array(_ref(o156, lo)[:3])) / (2 * d)
            assert np.allclose(J[:, col], fd, rtol=TOL_J, atol=TOL_J * np.abs(fd).max())


def test_taylor_sin_cos_on_the_cone_range():
    phi = np.linspace(-math.pi / 2, math.pi / 2, 101)
    for p in phi:
        c, s = traction_nodes._cos_sin_small.py_func(p)
        assert abs(c - math.cos(p)) < 3e-12 and abs(s - math.sin(p)) < 3e-12


def test_cone_edges_equal_the_angle_construction():
    """`nodes._cone_edges` turns -P by +-asin(1/|P|) with rotations; the angles themselves
    (atan2 of each edge mapped to the working plane, the mid-angle and half the opening)
    must give the same cone, from a pole on the ellipse edge to the far rule's 4 radii."""
    rng = np.random.default_rng(23)
    for _ in range(400):
        A = math.sqrt(rng.uniform(0.05, 0.25))
        P_scaled, phi = 1.0 + rng.choice([0.0, 1e-9, 1e-3, rng.uniform(0, 3)]), rng.uniform(-math.pi, math.pi)
        PX, PV = P_scaled * math.cos(phi), P_scaled * math.sin(phi)
        beta, centre = math.asin(1.0 / P_scaled), math.atan2(-PV, -PX)
        e1 = math.atan2(math.sin(centre - beta), A * math.cos(centre - beta))
        e2 = math.atan2(math.sin(centre + beta), A * math.cos(centre + beta))
        half = 0.5 * ((e2 - e1) % (2 * math.pi))
        c, s, h = traction_nodes._cone_edges(A, PX * A, PV, P_scaled)
        assert abs(h - half) < 1e-12 and abs(c - math.cos(e1 + half)) < 1e-12 and abs(s - math.sin(e1 + half)) < 1e-12


def test_float32_residual_stays_within_a_millionth_of_tau0_times_the_area(o156, fast):
    """docs/model.md §6.4: the time loop's residual-only call (every node value in float32) moves
    the force by < 1e-6 of tau0 pi a b and the spin moment by < 1e-6 of tau0 pi a b^2 from the
    float64 evaluation of the same rule, over the reference scene's operating range."""
    points = random_operating_points(300, seed=21, lubricant=o156, film=film.film_central_nvm)
    rule64, rule32 = fast.traction_rule(), fast.traction_rule(float32_residual=True)
    f64, f32 = np.empty(12), np.empty(12)
    worst = np.zeros(2)
    for a, b, p_h, h, du0, dv0, w_s in points:
        traction_fast(a, b, p_h, h, du0, dv0, w_s, 0.0, rule64, f64, False)
        traction_fast(a, b, p_h, h, du0, dv0, w_s, 0.0, rule32, f32, False)
        unit = fast.law.tau0 * math.pi * a * b
        dF, dM = math.hypot(f32[0] - f64[0], f32[1] - f64[1]), abs(f32[2] - f64[2])
        worst = np.maximum(worst, (dF / unit, dM / (unit * b)))
    print(f"float32 against float64 over {len(points)} points: F {worst[0]:.2e}, M {worst[1]:.2e} of tau0 pi a b (b)")
    assert 0.0 < worst[0] < 1e-6 and worst[1] < 1e-6


def test_passes_equal_their_py_funcs(o156, fast):
    """Every njit pass of traction_fast against its plain-Python twin on random contacts."""
    rng = np.random.default_rng(13)
    for _ in range(6):
        a, b, p_h, h = rng.uniform(1e-4, 4e-4), rng.uniform(1e-3, 3e-3), rng.uniform(3e8, 2.5e9), rng.uniform(5e-8, 5e-7)
        du0, dv0, w_s = rng.uniform(-1, 1) * 10 ** rng.uniform(-5, 0), rng.uniform(-0.1, 0.1), rng.uniform(-500, 500)
        results = []
        for twin in (False, True):
            pick = (lambda f: f.py_func) if twin else (lambda f: f)
            work, iwork = fast.workspace()
            X, Y, W, fi, r, k, x, z, ash = work[:9]
            n = pick(traction_nodes.place_nodes)(a, b, du0, dv0, w_s, fast.rule, X, Y, W, work[3:8])
            pick(_slip_and_table_index)(X, Y, n, a, b, p_h, du0, dv0, w_s, 1.0 / fast.p_step, fi, r)
            pick(_viscosity_lookup)(fi, n, fast.eta_table, 1.0 / (fast.law.tau0 * h), k)
            pick(_eyring_argument)(k, r, n, x, z)
            pick(log_array)(z, n, fi, iwork, ash)
            out, force_only = np.empty(12), np.full(12, np.nan)
            nodes, values = _Nodes(X, Y, W), _NodeValues(k, r, x, z, ash)
            g, c = np.empty(n), np.empty(n)
            pick(_eyring_response)(values, n, True, g, c)
            pick(_accumulate_response)(nodes, g, c, n, a, b, du0, dv0, w_s, out)
            pick(_accumulate_force_g)(nodes, g, n, a, b, du0, dv0, w_s, force_only)
            assert np.allclose(force_only[:3], out[:3], rtol=1e-12, atol=1e-15 * np.abs(out[:3]).max())
            assert not force_only[3:].any()
            # the float32 residual passes (py_funcs: math.sqrt of a float32 is a float64 there)
            work32, iwork32 = fast.workspace32()
            fi32, r32, k32, x32, z32, ash32 = work32
            eta_flat32 = fast.eta_table.astype(np.float32).ravel()
            last = np.float32(eta_flat32.size // 2 - 1.000001)
            row, picked = np.empty(n, dtype=np.uint32), np.empty(n, dtype=np.int64)
            pick(_slip_and_table_row32)(_Nodes(X, Y, W), n, a, b, p_h, _Slip(du0, dv0, w_s), 1.0 / fast.p_step, last,
                                        row, fi32, r32)
            fi64 = np.empty_like(fi)  # (fi itself now holds log_array's exponents)
            pick(_slip_and_table_index)(X, Y, n, a, b, p_h, du0, dv0, w_s, 1.0 / fast.p_step, fi64, np.empty_like(r))
            # float32 rounds the terms of s, not s: near the pole |s| is good to ~1e-7 of the terms
            terms = abs(du0) + abs(dv0) + abs(w_s) * b
            assert np.allclose(r32[:n], r[:n], rtol=2e-7, atol=2e-7 * terms)
            assert np.allclose(row + fi32[:n], np.minimum(fi64[:n], float(last)), rtol=2e-7, atol=1e-6)
            pick(pick_rows)(row, n, eta_flat32.view(np.int64), picked)
            pick(_lerp_eyring_argument32)(picked, fi32, r32, n, 1.0 / (fast.law.tau0 * h), k32, x32, z32)
            # a float32 index near the table's end (4096) resolves 2^-12 of an interval, over which eta
            # changes by ~2.5 % (alpha p_step): ~6e-6 relative, far inside the table's own 1e-4
            assert np.allclose(k32[:n], k[:n], rtol=1e-5)
            pick(log_array32)(z32, n, fi32, iwork32, ash32)
            # d asinh(k r) = k dr/sqrt(1 + x^2) <= dr/r: the rounding of |s| near the pole passes through
            dash = np.abs(r32[:n] - r[:n]) / r[:n]
            assert np.all(np.abs(ash32[:n] - ash[:n]) <= 1e-6 * np.maximum(ash[:n], 1.0) + dash)
            force32 = np.empty(12)
            g32 = np.empty(n, dtype=np.float32)
            pick(_stress_factor32)(k32, r32, x32, ash32, n, g32)
            pick(_accumulate_force_g)(nodes, g32, n, a, b, du0, dv0, w_s, force32)
            # force scale: the whole area at the largest stress (tau0 = 1 here); moment: times b
            gross = np.pi * a * b * ash[:n].max() * np.array([1.0, 1.0, b])
            assert np.all(np.abs(force32[:3] - out[:3]) <= 1e-6 * gross)
            results.append(out * fast.law.tau0)
        # fastmath reassociates the sums in the compiled kernels: agreement to rounding only
        assert np.allclose(results[0], results[1], rtol=1e-9, atol=1e-12 * np.abs(results[1]).max())
        full, residual_only, residual32 = np.empty(12), np.full(12, np.nan), np.full(12, np.nan)
        traction_fast(a, b, p_h, h, du0, dv0, w_s, 0.0, fast.traction_rule(), full)
        assert np.allclose(full, results[1], rtol=1e-9, atol=1e-12 * np.abs(results[1]).max())
        traction_fast(a, b, p_h, h, du0, dv0, w_s, 0.0, fast.traction_rule(), residual_only, False)
        assert np.allclose(residual_only[:3], full[:3], rtol=1e-12) and not residual_only[3:].any()
        traction_fast(a, b, p_h, h, du0, dv0, w_s, 0.0, fast.traction_rule(float32_residual=True), residual32, False)
        gross = fast.law.tau0 * np.pi * a * b * ash[:n].max() * np.array([1.0, 1.0, b])
        assert np.all(np.abs(residual32[:3] - full[:3]) <= 1e-6 * gross) and not residual32[3:].any()
        assert np.any(residual32[:3] != full[:3])  # the float32 passes did run


def test_float32_passes_give_the_exact_table_lookup_and_stress_factor(o156, fast):
    """docs/model.md §6.4: the float32 residual splits the table position into row and fraction
    in the slip pass, picks the rows in a pass of loads and interpolates in the Eyring pass; g =
    asinh(x)/|s| has a pass of its own before the float64 sums. On a contact with its pole inside
    the ellipse: the interpolation is the fused multiply-add of exact arithmetic rounded once
    (tests/simd_reference.py), and the g pass with its float64 sums gives the bits of the sums
    that form g themselves."""
    points = random_operating_points(200, seed=31, lubricant=o156, film=film.film_central_nvm)
    a, b, p_h, h, du0, dv0, w_s = points[0]
    work, iwork = fast.workspace()
    X, Y, W = work[0], work[1], work[2]
    n = traction_nodes.place_nodes(a, b, du0, dv0, w_s, fast.rule, X, Y, W, work[3:8])
    (fi, r, k, x, z, ash), iw = fast.workspace32()
    eta_flat32 = fast.eta_table.astype(np.float32).ravel()
    last = np.float32(eta_flat32.size // 2 - 1.000001)
    row = np.empty(n, dtype=np.uint32)
    _slip_and_table_row32(_Nodes(X, Y, W), n, a, b, p_h, _Slip(du0, dv0, w_s), 1.0 / fast.p_step, last, row, fi, r)
    rows = np.empty(n, dtype=np.int64)
    pick_rows(row, n, eta_flat32.view(np.int64), rows)
    _lerp_eyring_argument32(rows, fi, r, n, 1.0 / (fast.law.tau0 * h), k, x, z)
    position = row.astype(np.float32) + fi[:n]  # exact: i and f - i come from one float32 f
    assert np.array_equal(k[:n], lerp_fma_reference(position, eta_flat32, 1.0 / (fast.law.tau0 * h)))
    log_array32(z, n, fi, iw, ash)
    force, force_g, g = np.empty(12), np.empty(12), np.empty(n, dtype=np.float32)
    g64 = np.empty(n)  # the float64 path's g pass, fed the float32 values: g in float32, stored wide
    _eyring_response(_NodeValues(k, r, x, z, ash), n, False, g64, g64)
    _accumulate_force_g(_Nodes(X, Y, W), g64, n, a, b, du0, dv0, w_s, force)
    _stress_factor32(k, r, x, ash, n, g)
    _accumulate_force_g(_Nodes(X, Y, W), g, n, a, b, du0, dv0, w_s, force_g)
    assert np.array_equal(force_g, force) and force[:3].any()
    # the g pass against its definition: g |s| = asinh(k |s|) to the float32 log's ~1e-7 absolute
    # (simd_math.log_array32), g = k (1 - x^2/6 + 3x^4/40) below SERIES_X
    big = x[:n] >= SERIES_X
    exact = np.arcsinh(x[:n].astype(float))
    assert np.all(np.abs(g[big] * r[:n][big] - exact[big]) <= 1e-6 * np.maximum(exact[big], 1.0))
    small = x[:n][~big].astype(float)
    ratio = np.where(small > 0, np.arcsinh(small) / np.where(small > 0, small, 1.0), 1.0)  # asinh(x)/x
    assert np.allclose(g[~big], k[:n][~big] * ratio, rtol=1e-6)


def test_scratch_on_a_cache_line_and_the_same_bits_at_any_offset(o156, fast):
    """dynamics/_speed/aligned.py: the workspaces start every row on a cache line, and where a row
    starts changes no bit of the traction (the vectorised passes do not peel for alignment),
    float32 residual and float64 with the Jacobian alike."""
    from bearingsim.dynamics._speed.aligned import CACHE_LINE

    rule = fast.traction_rule(float32_residual=True)
    for scratch in (rule.work, rule.iwork, rule.work32, rule.iwork32):
        rows = scratch.reshape(-1, scratch.shape[-1])
        assert all(row.ctypes.data % CACHE_LINE == 0 for row in rows) and scratch.shape[-1] >= fast.max_nodes

    def shifted(a, offset):
        raw = np.empty(a.nbytes + 2 * CACHE_LINE, dtype=np.uint8)
        start = (-raw.ctypes.data) % CACHE_LINE + offset
        return raw[start:start + a.nbytes].view(a.dtype).reshape(a.shape)

    points = random_operating_points(60, seed=41, lubricant=o156, film=film.film_central_nvm)
    reference = [np.empty((len(points), 12)) for _ in range(2)]
    for offset in (0, 8, 16, 32, 48):
        moved = rule._replace(**{name: shifted(getattr(rule, name), offset)
                                 for name in ("work", "iwork", "work32", "iwork32")})
        assert moved.work.ctypes.data % CACHE_LINE == offset
        for i, point in enumerate(points):
            for path, (tr, jacobian) in enumerate(((moved, False), (moved.with_float32_residual(False), True))):
                out = np.empty(12)
                traction_fast(*point, 0.0, tr, out, jacobian)
                if offset == 0:
                    reference[path][i] = out
                else:
                    assert np.array_equal(out, reference[path][i]), (offset, i, path)


def test_batch_equals_single_calls(o156, fast):
    points = np.array(random_operating_points(12, seed=9, lubricant=o156, film=film.film_central_nvm))
    F, J, flags = fast.evaluate_batch(*points.T)
    for i, p in enumerate(points):
        f, j, flag = fast.evaluate(*p)
        # the batch loop inlines traction_fast and compiles it anew; with fastmath ('reassoc',
        # 'contract') LLVM may fuse or reorder differently per CPU, so bitwise equality holds on
        # some machines and not others (a CI host differed in the last bit of J): rounding only
        assert flags[i] == flag
        assert np.allclose(F[i], f, rtol=1e-12, atol=1e-13 * np.abs(f).max())
        assert np.allclose(J[i], j, rtol=1e-12, atol=1e-13 * np.abs(j).max())


def test_flags_and_never_nan(fast):
    base = (2e-4, 2e-3, 1.5e9, 2e-7)
    f, J, flag = fast.evaluate(0.0, 2e-3, 1.5e9, 2e-7, 0.1, 0.0, 0.0)
    assert flag == FLAG_NO_CONTACT and not f.any() and not J.any()
    _, _, flag = fast.evaluate(2e-4, 2e-3, 6e9, 2e-7, 0.1, 0.0, 0.0)
    assert flag & FLAG_PRESSURE_CLAMPED
    _, _, flag = fast.evaluate(2e-3, 2e-3, 1.5e9, 2e-7, 0.1, 0.0, 0.0)  # circular contact: not validated
    assert flag == FLAG_UNVALIDATED
    extremes = [(0.0, 0.0, 0.0), (0.0, 0.0, 1e-300), (1e-300, 0.0, 1e-300), (1e300, -1e300, 1e-300),
                (1e3, 0.0, 1e6), (0.0, 0.0, 1e9), (1e-12, 1e-12, 0.0)]
    for du0, dv0, w_s in extremes:
        for h in (2e-7, 1e-15):
            f, J, flag = fast.evaluate(*base[:3], h, du0, dv0, w_s)
            expected = FLAG_SLIP_CLAMPED if max(abs(du0), abs(dv0), abs(w_s) * base[1]) > 1e4 else FLAG_OK
            assert flag == expected and np.all(np.isfinite(f)) and np.all(np.isfinite(J)), (h, du0, dv0, w_s)
