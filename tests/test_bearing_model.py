"""The bearing model's residual and tangents (docs/model.md §4–§9): consistency with the
quasi-static solver, action = reaction, and tangents against finite differences."""

from __future__ import annotations

import numpy as np
import pytest

from bearingsim.dynamics.bearing import BearingModel, ModelOptions
from bearingsim.dynamics.bearing import layout
from bearingsim.dynamics.bearing.run import initial_coordinates
from bearingsim.dynamics.multibody.crv import update_configuration

from .bearing_fixtures import REFERENCE, STEEL, reference_model


@pytest.fixture(scope="module")
def dry():
    params, start = reference_model()
    model = BearingModel(params)
    q, v = initial_coordinates(params, start)
    return params, start, model, q, v


@pytest.fixture(scope="module")
def lubricated():
    from bearingsim.dynamics.lubrication.lubricant import load_builtin_lubricant

    params, start = reference_model(options=ModelOptions(), lubricant=load_builtin_lubricant("nato-o156"))
    model = BearingModel(params)
    q, v = initial_coordinates(params, start)
    return params, start, model, q, v


def forces(model, q, v):
    n = model.n_dof
    ma, g = np.zeros(n), np.zeros(n)
    model.evaluate(0.0, q, v, np.zeros(n), ma, g)
    return g


def _centripetal_ratio(moment: float) -> tuple[np.ndarray, np.ndarray, object, object]:
    """Radial contact force on each ball at the quasi-static start over -m omega_c^2 rho.

    Traction, damping and the gyroscopic moment are off on both sides (without traction
    there is no gyroscopic friction; normal damping would see the approach that an orbiting
    ball has on a tilted race)."""
    params, start = reference_model(moment=moment, gyroscopic=False,
                                    options=ModelOptions(traction="none", cage_race="none",
                                                         contact_damping_ratio=0.0))
    model = BearingModel(params)
    q, v = initial_coordinates(params, start)
    g = forces(model, q, v)
    w_c, m_b = start["cage_angular_speed"], params.ball_mass
    ratio, axial = np.empty(params.ball_count), np.empty(params.ball_count)
    balls_q, balls_g = layout.ball_states(q, params.ball_count), layout.ball_states(g, params.ball_count)
    for k in range(params.ball_count):
        x, f = balls_q[k, :3], balls_g[k, :3]
        rho = np.hypot(x[0], x[1])
        ratio[k] = (f[:2] @ x[:2] / rho) / (-m_b * w_c**2 * rho)
        axial[k] = f[2] / (m_b * w_c**2 * rho)
    return ratio, axial, params, g


def test_quasistatic_start_is_an_orbit_of_the_dynamic_model():
    """Under pure thrust, the quasi-static equilibrium (docs/model.md §10) must leave each ball with
    exactly the centripetal force of its orbit, -m omega_c^2 rho, and the inner race in
    equilibrium with its load: the two solvers share geometry, Hertz law and load signs."""
    ratio, axial, params, g = _centripetal_ratio(moment=0.0)
    np.testing.assert_allclose(ratio, 1.0, atol=1e-3)
    np.testing.assert_allclose(axial, 0.0, atol=1e-3)
    o = layout.inner_offset(params.ball_count)
    assert np.abs(g[o:o + 3]).max() < 1e-6 * 34000.0  # N: loads balanced by the contacts
    assert np.abs(g[o + 3:o + 5]).max() < 1e-6 * 430.0  # N m


def test_quasistatic_start_under_moment_is_close():
    """Under the 430 N m moment the race tilts by ~1 mrad. The quasi-static kernel places each
    inner groove centre in the ball's global azimuth plane (Jones' approximation), the dynamic
    kernel on the exact tilted torus: the contact loads differ by ~1e-3 relative, seen here as
    up to ~6 % of the (small, ~46 N) centripetal force. A bound, not a match: it documents the
    size of the start-up transient this approximation causes."""
    ratio, _, _, _ = _centripetal_ratio(moment=430.0)
    assert np.abs(ratio - 1.0).max() < 0.06
    assert np.abs(ratio - 1.0).max() > 1e-3  # the approximation is visible: this is no match


def test_contact_forces_are_equal_and_opposite(dry):
    """Sum of all generalised contact forces on balls + inner race + cage, plus the outer
    race's share, is the applied load: checked through linear momentum with the outer race
    removed from the sum — so here via one ball–race contact's wrench pair."""
    from bearingsim.dynamics.bearing.bundles import Ball, Body
    from bearingsim.dynamics.bearing.race_forces import RACE_ROW, contact_scratch, race_contact
    from bearingsim.dynamics.multibody.crv import crv_to_matrix

    params, _, model, q, v = dry
    o = layout.inner_offset(params.ball_count)
    R = crv_to_matrix(q[o + 3:o + 6])
    res = np.zeros(RACE_ROW.size)
    x_b, x_r = q[0:3].copy(), q[o:o + 3].copy()
    ball = Ball(x_b, v[0:3].copy(), v[3:6].copy())
    race = Body(x_r, R, v[o:o + 3].copy(), R @ v[o + 3:o + 6])
    hit = race_contact(ball, race, False, params.fp, params.ip, params.races.inner, params.traction, params.film,
                       contact_scratch(1), res, True)
    assert hit
    f_b, f_r = RACE_ROW["force_ball"].view(res), RACE_ROW["force_race"].view(res)
    m_b, m_r = RACE_ROW["moment_ball"].view(res), RACE_ROW["moment_race"].view(res)
    np.testing.assert_allclose(f_b, -f_r, rtol=0, atol=1e-9)
    # moments about the race centre balance: m_r + m_b + (x_b - x_r) x f_b = 0
    total = m_r + m_b + np.cross(x_b - x_r, f_b)
    assert np.abs(total).max() < 1e-9 * np.abs(f_b).max()


def _fd_tangents(model, q, v, cols):
    n = model.n_dof
    K, C = np.zeros((n, len(cols))), np.zeros((n, len(cols)))
    for c, j in enumerate(cols):
        rotation = j >= layout.inner_offset(model.params.ball_count) or j % layout.BALL_DOF >= 3
        ev, eq = (1e-6 if rotation else 1e-8), 1e-10
        vp, vm = v.copy(), v.copy()
        vp[j] += ev
        vm[j] -= ev
        C[:, c] = -(forces(model, q, vp) - forces(model, q, vm)) / (2 * ev)
        dq = np.zeros(n)
        dq[j] = eq
        qp, qm = np.empty(n), np.empty(n)
        update_configuration(q, dq, model.rotation_slots, qp)
        update_configuration(q, -dq, model.rotation_slots, qm)
        K[:, c] = -(forces(model, qp, v) - forces(model, qm, v)) / (2 * eq)
    return K, C


@pytest.mark.parametrize("case", ["lubricated", "frictionless"])
def test_tangents_agree_with_finite_differences(case, lubricated, dry):
    """Approximate tangents are allowed (docs/model.md §9), but the stiff parts must be right:
    ball translation/rotation and the inner race, against central differences of g, for the
    reference scene's Eyring traction and without traction. (Saturated dry Coulomb friction
    is not held to this: its tilt-slip coupling is only partly in the tangent.)"""
    if case == "lubricated":
        params, _, model, q, v = lubricated
    else:
        p, start = reference_model(options=ModelOptions(traction="none", cage_race="dry"))
        params, model = p, BearingModel(p)
        q, v = initial_coordinates(p, start)
    o = layout.inner_offset(params.ball_count)
    cols = [0, 1, 2, 3, 4, 5, o, o + 1, o + 2, o + 3, o + 4]
    Kfd, Cfd = _fd_tangents(model, q, v, cols)
    n = model.n_dof
    K = model.jacobian(0.0, q, v, np.zeros(n), 0.0, 0.0, 1.0).to_dense()[:, cols]
    C = model.jacobian(0.0, q, v, np.zeros(n), 0.0, 1.0, 0.0).to_dense()[:, cols]
    spin = layout.spin_row(params.ball_count)
    rows = [r for r in range(n) if r != spin]  # that row is replaced by the speed constraint
    # Newton needs each column right where it is stiff: 5 % of the column's own scale, plus
    # 1e-3 of the matrix's stiffest entry for terms too weak to matter next to it (e.g. the
    # turning of the contact frame under dry friction, ~1e-4 of the Hertz stiffness).
    for name, model_t, fd in (("K", K, Kfd), ("C", C, Cfd)):
        floor = 1e-3 * np.abs(fd[rows]).max()
        for c in range(len(cols)):
            scale = np.abs(fd[rows, c]).max()
            err = np.abs(model_t[rows, c] - fd[rows, c]).max()
            assert err <= 0.05 * scale + floor, (
                f"{name} column {cols[c]}: error {err:.3e} of scale {scale:.3e} (floor {floor:.3e})")


def test_float32_traction_residual_is_the_float64_one_to_its_rounding(lubricated):
    """The time loop's residual (float32 traction passes, dynamics/traction/fast.py) against the
    default float64 one at a slipping state: equal to well under a millinewton on out-of-balance
    forces of ~100 N (the start balances the Hertz loads; what is left is the traction of the
    imposed slip), not identical (the passes ran), and the tangent untouched (always float64)."""
    params, _, model64, q, v = lubricated
    v = v.copy()
    v[: 6 * params.ball_count: 6] += 0.05  # sliding in every contact: the Eyring passes all run
    model32 = BearingModel(params.with_float32_residual())
    g64, g32 = forces(model64, q, v), forces(model32, q, v)
    assert np.abs(g64).max() > 50.0
    assert np.abs(g32 - g64).max() < 1e-4
    assert np.any(g32 != g64)
    n = model64.n_dof
    for c in ((0.0, 0.0, 1.0), (0.0, 1.0, 0.0)):
        J64 = model64.jacobian(0.0, q, v, np.zeros(n), *c).to_dense()
        J32 = model32.jacobian(0.0, q, v, np.zeros(n), *c).to_dense()
        assert np.array_equal(J64, J32)


def test_physics_switches_remove_the_film():
    """[physics] ehd_film = false: the film kernel is not called (film diagnostics stay 0);
    with it on, every loaded contact reports a film of order 0.1–1 µm."""
    from bearingsim.dynamics.lubrication.lubricant import load_builtin_lubricant

    films = {}
    for on in (True, False):
        params, start = reference_model(lubricant=load_builtin_lubricant("nato-o156"),
                                        options=ModelOptions(traction="coulomb", ehd_film=on))
        model = BearingModel(params)
        q, v = initial_coordinates(params, start)
        forces(model, q, v)
        films[on] = np.stack([model.channel("contacts/inner_film"), model.channel("contacts/outer_film")])
    assert np.all(films[False] == 0.0)
    assert np.all((films[True] > 5e-8) & (films[True] < 5e-6))


def test_kernels_without_reference_counting_neither_leak_nor_drop_references(lubricated):
    """The force and tangent kernels compiled without numba's reference counting
    (dynamics/_speed/compile_policy.py) only borrow the caller's arrays: after many residual and
    tangent evaluations every array passed in has exactly the Python reference count it had
    before (a kernel returning a borrowed view, or keeping one, would change it by one per
    call; a dropped reference would free an array still in use)."""
    import sys

    params, _, model, q, v = lubricated
    n = model.n_dof
    a, ma, g = np.zeros(n), np.zeros(n), np.zeros(n)
    P = params
    watched = [q, v, a, ma, g, P.fp, P.ip, *P.races, P.traction.eta_table, P.traction.rule, P.traction.work,
               P.traction.iwork, P.pocket, P.journal, P.pocket_psi, *P.hinge, model.mass, model.impact_speeds,
               model.diag, model.K.D, model.K.B, model.C.E, model.arrays.cage.cos_psi, model.arrays.work.rows,
               model.arrays.work.pocket_rows, model.arrays.work.R_inner, model.arrays.work.outer.w]
    before = [sys.getrefcount(x) for x in watched]
    for _ in range(50):
        model.evaluate(0.0, q, v, a, ma, g)
        model.jacobian(0.0, q, v, a, 1.0, 1.0, 1.0)
    assert [sys.getrefcount(x) for x in watched] == before
    assert np.all(np.isfinite(g)) and np.abs(g).max() > 0.0


def _film_inputs(lubricated, outer):
    """(D, d_m, r, E', eta0, alpha*, min_film) of the reference bearing and oil, from their own
    objects (not the model's parameter vector)."""
    from bearingsim.dynamics.geometry import effective_modulus
    from bearingsim.dynamics.lubrication.lubricant import load_builtin_lubricant

    lub = load_builtin_lubricant("nato-o156")
    r = REFERENCE.outer_groove_radius if outer else REFERENCE.inner_groove_radius
    return (REFERENCE.ball_diameter, REFERENCE.pitch_diameter, r, effective_modulus(STEEL, STEEL),
            lub.eta0, lub.alpha_star, ModelOptions().min_film)


@pytest.mark.parametrize("outer", [False, True])
def test_tabulated_film_equals_the_nvm_formula(lubricated, outer):
    """The time loop's film reads R_x and the lambda-only NVM terms from the race table
    (race_table.film_geometry_columns) and takes the formula for all contacts at once
    (film.film_central_nvm_batch); both it and the one-contact path (race_forces.film_of_carry)
    must equal film.film_central_nvm with R_x, R_y computed from the contact angle
    (docs/model.md §6.2–§6.3) -- over the table's whole range of contact angles, between and on
    its nodes, for loads and speeds of the reference bearing."""
    from bearingsim.dynamics.bearing.params import FILM_NVM, FP_ALPHA_P, FP_E_EFF, FP_ETA0, IP_FILM
    from bearingsim.dynamics.bearing.race_forces import (
        CA_FEL, CA_RX, CA_U, N_CARRY, film_of_carry, nvm_terms_into,
    )
    from bearingsim.dynamics.bearing.race_table import curvature_radii
    from bearingsim.dynamics.contact.hertz import table_position
    from bearingsim.dynamics.lubrication.film import FILM_BATCH_ROWS, film_central_nvm_batch
    from bearingsim.dynamics.lubrication.film_laws.nvm import film_central_nvm

    params = lubricated[0]
    table = params.races.outer if outer else params.races.inner
    D, d_m, r, e_eff, eta0, alpha_p, min_film = _film_inputs(lubricated, outer)
    rng = np.random.default_rng(5)
    alphas = np.concatenate([rng.uniform(0.0, 1.5, 60), np.linspace(0.0, np.pi / 2, 181)[1:170:7], [-0.45]])
    carries, direct = np.zeros((alphas.size, N_CARRY)), np.empty(alphas.size)
    for i, alpha in enumerate(alphas):
        F, u_s = 10 ** rng.uniform(2.0, 3.8), 10 ** rng.uniform(0.5, 1.5)  # 100 N..6 kN, 3..30 m/s
        Rx, Ry = curvature_radii(abs(alpha), outer, D, d_m, r)
        direct[i] = max(film_central_nvm(F, Rx, Ry, e_eff, eta0, alpha_p, u_s), min_film)
        carries[i, CA_FEL], carries[i, CA_U] = F, u_s
        nvm_terms_into(table, *table_position(table, alpha), carries[i])
        ip = params.ip.copy()
        ip[IP_FILM] = FILM_NVM
        assert film_of_carry(carries[i], alpha, outer, params.fp, ip, params.film) == pytest.approx(direct[i],
                                                                                                   rel=1e-8), alpha
    n = alphas.size
    film_in = np.ascontiguousarray(carries[:, [CA_FEL, CA_RX, CA_U, *range(CA_RX + 1, CA_RX + 6)]].T)
    h = np.empty(n)
    film_central_nvm_batch(film_in, n, params.fp[FP_E_EFF], params.fp[FP_ETA0], params.fp[FP_ALPHA_P], h,
                           np.empty((FILM_BATCH_ROWS, 5 * n)), np.empty(5 * n, dtype=np.int64))
    np.testing.assert_allclose(np.maximum(h, min_film), direct, rtol=1e-8)


@pytest.mark.parametrize("outer", [False, True])
def test_tabulated_semi_axes_equal_hertz(lubricated, outer):
    """The time loop takes the contact semi-axes as (c k_h^(1/3)) sqrt(delta) from the race
    table (race_table.semi_axis_columns); Hertz's a = c_a F^(1/3) with F = k_h delta^(3/2)
    and the exact table (hertz.hertz_table_eval) must give the same, between the nodes too."""
    from bearingsim.dynamics.bearing.race_table import TAB_SEMI_AXES
    from bearingsim.dynamics.contact.hertz import hermite, hertz_table_eval, table_position

    table = lubricated[0].races.outer if outer else lubricated[0].races.inner
    rng = np.random.default_rng(11)
    for alpha, delta in zip(rng.uniform(0.0, 1.5, 80), 10 ** rng.uniform(-7, -4.5, 80)):
        k_h, _, _, c_a, c_b = hertz_table_eval(table, alpha)
        F13 = (k_h * delta ** 1.5) ** (1.0 / 3.0)
        j, t, step = table_position(table, alpha)
        assert hermite(table, j, TAB_SEMI_AXES, t, step)[0] * delta ** 0.5 == pytest.approx(c_a * F13, rel=1e-8)
        assert hermite(table, j, TAB_SEMI_AXES + 2, t, step)[0] * delta ** 0.5 == pytest.approx(c_b * F13, rel=1e-8)


def test_hamrock_dowson_film_option_uses_the_contact_curvatures(lubricated):
    """With the Hamrock–Dowson option the model's film is film_hamrock_dowson's central film
    at R_x, R_y of the contact angle (docs/model.md §6.3), not the tabulated NVM terms."""
    from bearingsim.dynamics.bearing.params import FILM_CONTACT, IP_FILM
    from bearingsim.dynamics.bearing.race_forces import CA_FEL, CA_U, N_CARRY, film_of_carry
    from bearingsim.dynamics.bearing.race_table import curvature_radii
    from bearingsim.dynamics.lubrication.film_laws.hamrock_dowson import HamrockDowson, film_hamrock_dowson

    params = lubricated[0]
    D, d_m, r, e_eff, eta0, alpha_p, min_film = _film_inputs(lubricated, False)
    for alpha, F, u_s in [(0.3, 800.0, 12.0), (0.55, 4000.0, 25.0), (0.45, 150.0, 4.0)]:
        Rx, Ry = curvature_radii(alpha, False, D, d_m, r)
        expected = max(film_hamrock_dowson(F, Rx, Ry, e_eff, eta0, alpha_p, u_s)[0], min_film)
        carry = np.full(N_CARRY, np.nan)  # the NVM terms stay unread
        carry[CA_FEL], carry[CA_U] = F, u_s
        ip = params.ip.copy()
        ip[IP_FILM] = FILM_CONTACT
        assert film_of_carry(carry, alpha, False, params.fp, ip, HamrockDowson()) == pytest.approx(expected,
                                                                                                  rel=1e-12)


def test_the_direct_kernel_call_is_taken_only_for_arrays_it_can_read(dry):
    """BearingModel calls the compiled kernel directly once it is typed (model.py `_Kernel`);
    that call does not check the arrays it unboxes, so a strided array would be read as if it
    were contiguous. Only contiguous float64 vectors of the model's length may take it;
    anything else goes through numba's own dispatch."""
    params, _, model, q, v = dry
    n = model.n_dof
    model.evaluate(0.0, q, v, np.zeros(n), np.zeros(n), np.zeros(n))  # types the direct call
    call = model._kernel_call
    assert call.entry is not None and call._fits(np.zeros(n))
    for bad in (np.zeros(2 * n)[::2], np.zeros(n, dtype=np.float32), np.zeros(n, dtype=np.int64),
                np.zeros(n + 1), np.zeros((1, n)), list(np.zeros(n))):
        assert not call._fits(bad), bad


def test_error_scales_follow_contact_stiffness_and_clearances(dry):
    """M.99b: L_i = Q_mean / K_ii, or the clearance a coordinate moves freely in. The inner race's
    K_xx with the balls held is its inner contacts' Hertz stiffness dQ/d(delta) = 1.5 Q / delta
    (Q = K delta^1.5) projected on x, plus the hinge's 1e9 N/m — computed here from the
    quasi-static solver's loads, approaches and angles, not from the dynamic model."""
    from bearingsim.dynamics.operating_point import OperatingPoint
    from bearingsim.dynamics.quasistatic.options import QuasiStaticOptions
    from bearingsim.dynamics.quasistatic.solver import solve_quasistatic

    from .bearing_fixtures import INNER_SPEED

    params, start, model, q, v = dry
    scales = model.error_scales(0.0, q, v)
    Z = params.ball_count
    qs = solve_quasistatic(REFERENCE, STEEL, STEEL,
                           OperatingPoint(axial=34000.0, radial=0.0, moment=430.0, inner_speed=INNER_SPEED),
                           QuasiStaticOptions(gyroscopic=True))
    q_mean = np.mean(np.concatenate([qs.inner_load, qs.outer_load]))
    loaded = qs.inner_deflection > 0
    k_contact = 1.5 * qs.inner_load[loaded] / qs.inner_deflection[loaded]
    k_xx = np.sum(k_contact * np.cos(qs.inner_contact_angle[loaded]) ** 2 * np.cos(qs.azimuth[loaded]) ** 2) + 1e9
    o = layout.inner_offset(Z)
    assert scales[o] == pytest.approx(q_mean / k_xx, rel=0.1)
    c = layout.cage_offset(Z, True)
    pocket_clearance = params.pocket.pocket_radius - params.pocket.ball_radius
    np.testing.assert_allclose(scales[c:c + 3], params.guide_clearance)  # a free cage: its guide clearance
    np.testing.assert_allclose(scales[c + 3:c + 6], pocket_clearance)    # its rotation: the pockets'
    ball0 = scales[:3]  # ball 0 sits on +x: x radial (contacts), y along the orbit (free in its pocket)
    assert ball0[1] == pytest.approx(pocket_clearance)
    assert ball0[0] < 1e-4 * params.pitch_diameter and ball0[0] < ball0[2] < ball0[1]


def test_border_gyroscopic_moment_is_the_rigid_body_ones_bit_for_bit():
    # assembly._add_gyroscopic writes rigid_body.gyroscopic_moment's arithmetic on scalars so
    # that the residual kernel allocates nothing; the two must give the same bits.
    from bearingsim.dynamics.bearing.assembly import _add_gyroscopic
    from bearingsim.dynamics.multibody.rigid_body import gyroscopic_moment

    rng = np.random.default_rng(11)
    for _ in range(200):
        Jx, Jz = rng.uniform(1e-4, 1e-1, 2)
        Om = rng.normal(size=3) * rng.choice([1e-3, 1.0, 1e3])
        g = rng.normal(size=8)
        expected = g.copy()
        expected[2:5] += gyroscopic_moment(np.diag(np.array([Jx, Jx, Jz])), Om)[0]
        _add_gyroscopic(Jx, Jx, Jz, Om, g, 2)
        assert np.array_equal(g, expected)


def test_a_tangent_call_leaves_the_residual_and_the_films_as_they_are(lubricated):
    """The Newton matrix's evaluation (want_tangent) returns the same residual and diagnostics
    as a residual-only one. A loop variable of the damping block that shadowed the race table
    position once made tangent calls read the film at the wrong contact angle."""
    params, _, model, q, v = lubricated
    n = model.n_dof
    results = []
    for want_tangent in (False, True):
        ma, g = np.zeros(n), np.zeros(n)
        model._kernel(0.0, q, v, np.zeros(n), ma, g, want_tangent)
        films = np.stack([model.channel("contacts/inner_film"), model.channel("contacts/outer_film")])
        results.append((g, films))
    assert np.all(results[0][1] > 0.0)
    np.testing.assert_allclose(results[1][1], results[0][1], rtol=1e-12)
    # the tangent call takes the traction in float64, the residual-only one through float32 passes
    np.testing.assert_allclose(results[1][0], results[0][0], rtol=0, atol=1e-5 * np.abs(results[0][0]).max())


@pytest.mark.parametrize("case", ["lubricated", "dry"])
def test_a_tangent_call_gives_the_residual_of_a_residual_only_call(case, lubricated, dry):
    """The compiled loop calls `evaluate_bearing` without tangents in Newton's iterations and
    with them at a refactorisation: both must give the same M a, and g and the drive moment to
    rounding (float64 traction) or to the float32 residual passes' rounding, here with every
    contact slipping and the cage off centre (its land film and the dynamic squeeze term
    acting). Then the kernel, compiled without reference counting, must leave every array's count
    as it was, with and without tangents."""
    import sys

    from bearingsim.dynamics.bearing.assembly import evaluate_bearing

    params, _, _, q, v = {"lubricated": lubricated, "dry": dry}[case]
    Z = params.ball_count
    q, v = q.copy(), v.copy()
    v[: 6 * Z: 6] += 0.05
    cage = 6 * Z + 6
    q[cage:cage + 2] += (1.2e-4, -0.7e-4)  # of a 0.29 mm guide clearance
    v[cage:cage + 2] += (0.02, 0.01)
    rng = np.random.default_rng(7)
    a = rng.normal(scale=10.0, size=q.size)
    for float32, p in ((False, params), (True, params.with_float32_residual())):
        model = BearingModel(p)
        K, C = model.K.blocks(), model.C.blocks()
        out = []
        for want_tangent in (True, False):
            ma, g, diag = np.zeros(q.size), np.zeros(q.size), np.zeros(model.diag.size)
            drive = evaluate_bearing(0.0, q, v, a, model.kernel_data(), want_tangent, ma, g, diag, K, C)
            out.append((drive, ma, g, diag))
        assert np.abs(out[0][2]).max() > 1.0
        assert np.array_equal(out[0][1], out[1][1])  # M a
        # float64: the tangent route's traction, computed with its Jacobian, rounds differently;
        # float32: the residual passes' rounding as well
        tol = 1e-5 if float32 else 1e-12
        np.testing.assert_allclose(out[1][2], out[0][2], rtol=0, atol=tol * np.abs(out[0][2]).max())
        assert abs(out[1][0] - out[0][0]) <= tol * abs(out[0][0])
        if case == "lubricated":
            from bearingsim.dynamics.bearing import channels
            assert channels.read(out[1][3], Z, "cage_race/eccentricity_ratio") > 0.3  # the land film acts
    watched = [q, v, a, ma, g, diag, params.fp, params.journal, model.arrays.work.journal_row,
               model.arrays.work.journal_squeeze, model.K.D, model.C.B]
    before = [sys.getrefcount(x) for x in watched]
    for i in range(50):
        evaluate_bearing(0.0, q, v, a, model.kernel_data(), i % 5 == 0, ma, g, diag, K, C)
    assert [sys.getrefcount(x) for x in watched] == before


def test_a_residual_call_clears_every_slot_it_reads_and_no_tangent_value_leaks_into_it(lubricated):
    """A residual-only call clears only `RC_RESIDUAL_SPANS` of each contact row: those must be
    exactly the slots outside the tangent-only fields, and a residual after a tangent call at
    another state must be the residual from freshly zeroed rows, to the bit."""
    from bearingsim.dynamics.bearing.assembly import evaluate_bearing
    from bearingsim.dynamics.bearing.race_forces import RACE_ROW, RC_RESIDUAL_SPANS

    tangent_only = {s for c in RACE_ROW if c.description.endswith("tangent only")
                    for s in range(c.slot, c.slot + c.width)}
    cleared = {s for lo, hi in RC_RESIDUAL_SPANS for s in range(lo, hi)}
    assert cleared == set(range(RACE_ROW.size)) - tangent_only and len(tangent_only) == 49

    params, _, _, q, v = lubricated
    p = params.with_float32_residual()
    q_b, v_b = q.copy(), v.copy()
    v_b[: 6 * p.ball_count: 6] += 0.05  # every contact slips: the tangent slots fill
    a = np.random.default_rng(3).normal(scale=10.0, size=q.size)
    out = []
    for tangent_first in (False, True):
        model = BearingModel(p)
        K, C = model.K.blocks(), model.C.blocks()
        ma, g, diag = np.zeros(q.size), np.zeros(q.size), np.zeros(model.diag.size)
        if tangent_first:
            evaluate_bearing(0.0, q_b, v_b, a, model.kernel_data(), True, ma, g, diag, K, C)
            assert np.abs(model.arrays.work.rows[:, sorted(tangent_only)]).max() > 0.0
        drive = evaluate_bearing(0.0, q, v, a, model.kernel_data(), False, ma, g, diag, K, C)
        out.append((drive, ma.copy(), g.copy(), diag.copy(), model.arrays.work.rows[:, sorted(cleared)].copy()))
    assert out[0][0] == out[1][0]
    for x, y in zip(out[0][1:], out[1][1:]):
        assert np.array_equal(x, y)
