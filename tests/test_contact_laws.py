"""Every contact law written once (docs/contact_laws.md): for each registry -- ball–race traction,
EHD film, ball–pocket, cage–land -- tests generated over its registered laws check that each
module offers what its kind asks and that the engine's path gives the law's own values; then a
toy law of each kind, registered through the public route (`LAWS.register(Law(...))`) and
nothing else, is chosen by a model and reaches the kernels.

The references are the laws' own functions, called from Python, and closed forms the toy laws
make simple: a Newtonian film's traction with a Barus viscosity (docs/model.md §6.4, the closed
form of tests/test_traction.py), a film of one thickness, a linear pocket spring, a land that
shares half and half.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numba
import numpy as np
import pytest

from bearingsim.dynamics.contact import pocket as pocket_contact_module
from bearingsim.dynamics.contact.pocket_laws import LAWS as POCKET_LAWS
from bearingsim.dynamics.journal import short_bearing
from bearingsim.dynamics.journal.dry import lundberg_load
from bearingsim.dynamics.journal.land_laws import LAWS as LAND_LAWS
from bearingsim.dynamics.lubrication.film_laws import LAWS as FILM_LAWS, nvm
from bearingsim.dynamics.lubrication.lubricant import load_builtin_lubricant
from bearingsim.dynamics.registry import Law
from bearingsim.dynamics.traction import quadrature
from bearingsim.dynamics.traction.contact import contact_traction
from bearingsim.dynamics.traction.fast import FastTraction, dry_traction_rule
from bearingsim.dynamics.traction.laws import LAWS as TRACTION_LAWS
from tests.lubrication_points import random_operating_points

REGISTRIES = {"traction": TRACTION_LAWS, "film": FILM_LAWS, "pocket": POCKET_LAWS, "land": LAND_LAWS}
REF_GRID = (128, 1024)  # the converged reference grid of tests/test_traction.py


@pytest.fixture(scope="module")
def o156():
    return load_builtin_lubricant("nato-o156")


def _options():
    from bearingsim.dynamics.bearing.options import ModelOptions

    return ModelOptions()


def _bundle(kind, name, lubricant):
    """A bundle of law `name` of registry `kind`, packed as the model packs it."""
    laws = REGISTRIES[kind]
    if kind in ("traction", "film"):
        return laws.pack(name, _options(), lubricant)
    if kind == "pocket":
        return laws.pack(name, 2.5e10, 0.7, "flores", 0.1)
    return laws.pack(name, 0.05)


# --- every registered law ---------------------------------------------------------------
@pytest.mark.parametrize("kind, name", [(k, n) for k, laws in REGISTRIES.items() for n in laws])
def test_each_law_module_offers_what_its_kind_asks(kind, name, o156):
    laws = REGISTRIES[kind]
    module = laws.module(name)  # raises TypeError naming what is missing
    bundle = _bundle(kind, name, o156)
    assert isinstance(bundle, module.Params) and isinstance(bundle, tuple) and hasattr(bundle, "_fields")
    assert set(module.UNITS) == set(bundle._fields)
    assert all(isinstance(v, (float, int)) for v in bundle)
    assert laws.law_of(type(bundle)).name == name
    assert laws[name].doc


@numba.njit
def _traction_through_the_engine(rule, F_n, a, b, p_h, h, du0, dv0, w_s, out):
    return contact_traction(rule, F_n, a, b, p_h, h, du0, dv0, w_s, 0.0, out, True)


# The force and moment tolerance of the engine against the reference quadrature: 2 % for the
# Eyring law, whose rule was tuned (tests/test_traction_fast.py); 8 % for every other film law,
# which runs through the engine's general pass untuned: its measured worst case over these
# points is 6.1 %, for limiting shear at a spin-dominated contact (docs/contact_laws.md).
TUNED_FORCE_TOLERANCE, UNTUNED_FORCE_TOLERANCE = 0.02, 0.08


def _engine_against_quadrature(name, o156, points=12, seed=13):
    """Worst (force, moment, Jacobian) error of the fast engine against the (128, 1024)
    quadrature of one bundle of film law `name`."""
    bundle = _bundle("traction", name, o156)
    rule = FastTraction.build(o156).with_law(bundle).traction_rule()
    worst = np.zeros(3)
    for a, b, p_h, h, du0, dv0, w_s in random_operating_points(points, seed=seed, lubricant=o156,
                                                               film=nvm.film_central_nvm):
        out = np.zeros(12)
        _traction_through_the_engine(rule, 1000.0, a, b, p_h, h, du0, dv0, w_s, out)
        Fx, Fy, Mz, J = quadrature.traction_quadrature(a, b, p_h, h, bundle, o156.model_code, o156.rheology_params(),
                                                       du0, dv0, w_s, REF_GRID)
        scale = math.hypot(Fx, Fy)
        worst = np.maximum(worst, (math.hypot(out[0] - Fx, out[1] - Fy) / scale,
                                   abs(out[2] - Mz) / max(abs(Mz), scale * b),
                                   np.abs(out[3:].reshape(3, 3) - J).max() / np.abs(J).max()))
    return worst


@pytest.mark.parametrize("name", [n for n in TRACTION_LAWS if TRACTION_LAWS[n].film])
def test_the_film_engine_gives_each_film_law(name, o156):
    """The fast engine (pole-centred nodes, the law through `operations`) against the reference
    quadrature of the same law bundle; the Jacobian within 3 %."""
    tolerance = TUNED_FORCE_TOLERANCE if name == "eyring" else UNTUNED_FORCE_TOLERANCE
    worst = _engine_against_quadrature(name, o156)
    print(f"{name}: force {worst[0]:.2%}, moment {worst[1]:.2%}, Jacobian {worst[2]:.2%}")
    assert worst[0] < tolerance and worst[1] < tolerance and worst[2] < 0.03, worst


@pytest.mark.xfail(strict=True, reason="the engine's nodes are placed for the Eyring field; limiting shear "
                                       "at a spin-dominated contact is 6 % off (docs/contact_laws.md)")
def test_limiting_shear_meets_the_tuned_accuracy(o156):
    worst = _engine_against_quadrature("limiting-shear", o156)
    assert worst[0] < TUNED_FORCE_TOLERANCE and worst[1] < TUNED_FORCE_TOLERANCE


@pytest.mark.parametrize("name", [n for n in TRACTION_LAWS if not TRACTION_LAWS[n].film])
def test_a_law_without_film_runs_its_own_kernel(name):
    bundle = _bundle("traction", name, None)
    module = TRACTION_LAWS.module(name)
    for F_n, a, b, du0, dv0, w_s in [(800.0, 2e-4, 1.5e-3, 0.3, -0.02, 40.0), (50.0, 1e-4, 9e-4, -1e-4, 2e-4, -3.0)]:
        out, expected = np.zeros(12), np.zeros(12)
        flag = _traction_through_the_engine(dry_traction_rule(bundle), F_n, a, b, 1e9, 1e-7, du0, dv0, w_s, out)
        module.dry_traction.py_func(bundle, F_n, a, b, du0, dv0, w_s, expected)
        assert flag == 0
        np.testing.assert_allclose(out, expected, rtol=1e-13, atol=0.0)


def _film_through_the_model(name, lubricant):
    """(film of every active contact from the force kernel, the law's own film at each) of the
    reference bearing with physics.film_formula = `name`."""
    from bearingsim.dynamics.bearing import BearingModel, ModelOptions
    from bearingsim.dynamics.bearing.params import FP_D, FP_DM, FP_E_EFF, FP_MIN_FILM, FP_RI, FP_RO
    from bearingsim.dynamics.bearing.race_forces import RC_ACTIVE, RC_ALPHA, RC_FILM, RC_Q, RC_USUM
    from bearingsim.dynamics.bearing.race_table import curvature_radii
    from bearingsim.dynamics.bearing.run import initial_coordinates
    from tests.bearing_fixtures import reference_model

    # no normal damping: the load in the contact row is then the elastic load the film takes
    options = ModelOptions(film_formula=name, cage_race="dry", contact_damping_ratio=0.0)
    params, start = reference_model(options=options, lubricant=lubricant)
    model = BearingModel(params)
    q, v = initial_coordinates(params, start)
    n = model.n_dof
    model.evaluate(0.0, q, v, np.zeros(n), np.zeros(n), np.zeros(n))
    fp, module = params.fp, FILM_LAWS.module(name)
    got, want = [], []
    for c, row in enumerate(model.arrays.work.rows):
        if row[RC_ACTIVE] == 0.0:
            continue
        outer = c % 2 == 1
        Rx, Ry = curvature_radii(abs(row[RC_ALPHA]), outer, fp[FP_D], fp[FP_DM], fp[FP_RO] if outer else fp[FP_RI])
        h = module.central_film.py_func(params.film, row[RC_Q], Rx, Ry, fp[FP_E_EFF], lubricant.eta0,
                                        lubricant.alpha_star, max(row[RC_USUM], 1e-6))
        got.append(row[RC_FILM])
        want.append(max(h, fp[FP_MIN_FILM]))
    return np.array(got), np.array(want)


@pytest.mark.parametrize("name", list(FILM_LAWS))
def test_the_force_kernel_takes_each_film_law(name, o156):
    """The residual's film of every loaded contact equals the law's own central film at the
    contact's curvature radii, load and entrainment speed (NVM through its tabulated terms and
    its vectorised batch, any other law contact by contact): 1e-8 covers the table's Hermite
    interpolation of the NVM terms (tests/test_bearing_model.py)."""
    got, want = _film_through_the_model(name, o156)
    assert got.size >= 20
    np.testing.assert_allclose(got, want, rtol=1e-8)


@pytest.mark.parametrize("name", list(POCKET_LAWS))
def test_the_pocket_contact_gives_each_pocket_law(name):
    module = POCKET_LAWS.module(name)
    p = pocket_contact_module.pocket_parameters(
        ball_diameter=0.01905, pocket_diameter=0.02023, pitch_radius=0.079, effective_modulus=1.45e11,
        restitution=0.7, friction_coefficient=0.1, law=name)
    clearance = 0.5 * (0.02023 - 0.01905)
    for delta, approach in [(2e-6, 0.05), (5e-7, -0.01), (1e-6, 0.0)]:
        x_ball = np.array([0.079, clearance + delta, 0.0])
        v_ball = np.array([0.0, approach, 0.0])
        out = pocket_contact_module.pocket_contact(x_ball, v_ball, np.zeros(3), np.zeros(3), np.eye(3), np.zeros(3),
                                                   np.zeros(3), 0.0, 0.2, p)
        f_n = module.normal_force.py_func(p.law, out[pocket_contact_module.P_OUT_DELTA], approach, 0.2)[0]
        assert out[pocket_contact_module.P_OUT_FN] == pytest.approx(f_n, rel=1e-12) and f_n > 0.0


def _journal(law_name, eps, lands=1):
    p = short_bearing.journal_parameters(
        short_bearing.JournalGeometry(radius=0.083, length=7.6e-3, clearance=0.29e-3, lands=lands),
        viscosity=5e-3, effective_modulus=1.2e11, friction_coefficient=0.1, eps0=0.05, mode=law_name)
    e = eps * p.clearance
    out = short_bearing.cage_race_journal(np.array([e, 0.0]), np.zeros(2), 300.0, 0.0, p)
    return p, out


@pytest.mark.parametrize("name", list(LAND_LAWS))
@pytest.mark.parametrize("eps", [0.5, 1.02, 1.3])
def test_the_journal_blends_by_each_land_law(name, eps):
    """With a centred cage spinning at 300 rad/s offset along +x: the force along -x (radial)
    is f_F x the film's push + (1 - f_F) x Lundberg's metal load, with the weights and the film
    clearance of the law's own `weights` (the static film: paper eq. 25)."""
    module = LAND_LAWS.module(name)
    p, out = _journal(name, eps)
    f_f, _, _, _, film_ratio, metal, clipped = module.weights.py_func(p.law, eps)
    c_film = p.clearance * film_ratio
    eps_h = min(eps * p.clearance / c_film, p.eps_clip) if clipped else eps * p.clearance / c_film
    film_push = 0.0
    if f_f > 0.0:
        film_push = short_bearing.ocvirk_force(eps_h, p.viscosity, 300.0, p.radius, p.length, c_film)[0]
    q_dry = lundberg_load(eps * p.clearance - p.clearance, p.length, p.e_eff)[0] if metal else 0.0
    assert -out[short_bearing.J_OUT_FORCE] == pytest.approx(f_f * film_push + (1.0 - f_f) * q_dry, rel=1e-10, abs=1e-12)
    assert out[short_bearing.J_OUT_METAL_FORCE] == pytest.approx((1.0 - f_f) * q_dry, rel=1e-12, abs=1e-12)


# --- a toy law of each kind, through the public route ------------------------------------
TOYS = {"traction": ("toy-newtonian", "tests.toy_laws.newtonian", True),
        "film": ("toy-constant", "tests.toy_laws.constant_film", True),
        "pocket": ("toy-linear", "tests.toy_laws.linear_pocket", False),
        "land": ("toy-half-film", "tests.toy_laws.half_film_land", True)}


@pytest.fixture(scope="module")
def toys():
    for kind, (name, module, film) in TOYS.items():
        REGISTRIES[kind].register(Law(name, module, doc=f"a toy {kind} law of the tests", film=film,
                                      flags={"load_exponent": 1.0, "boundary": False}))
    yield {kind: name for kind, (name, _, _) in TOYS.items()}
    for kind, (name, _, _) in TOYS.items():
        REGISTRIES[kind].unregister(name)


def test_a_registered_toy_law_is_a_choice_of_the_scene(toys):
    from bearingsim.dynamics.bearing.options import ModelOptions

    options = ModelOptions(traction=toys["traction"], film_formula=toys["film"], pocket_law=toys["pocket"],
                           cage_race=toys["land"])
    assert options.traction == "toy-newtonian"
    with pytest.raises(ValueError, match="toy-newtonian"):  # the error lists it among the choices
        ModelOptions(traction="toy-none-such")


def test_a_toy_traction_law_reaches_the_engine(toys, o156):
    """A Newtonian film, tau = eta(p) s / h, with a Barus viscosity and pure rolling slip du:
    F_x = -(3 eta0 du/(h p_h s^2)) (e^s (s - 1) + 1) W, s = alpha p_h, W = (2/3) pi a b p_h
    (docs/model.md §6.4; tests/test_traction.py checks the quadrature against it). The fast
    engine, with nothing but the toy's module and its registry entry, gives it within its 2 %."""
    from bearingsim.dynamics.lubrication.lubricant import Lubricant

    module = TRACTION_LAWS.module(toys["traction"])
    law = module.pack(None, None)
    barus = Lubricant(name="barus-test", viscosity_model="barus", ambient_viscosity=0.005,
                      pressure_viscosity_coefficient=1.2e-8, temperature_degC=70.0, eyring_stress=5e6, density=870.0)
    rule = FastTraction.build(barus).with_law(law).traction_rule()
    a, b, p_h, h, du = 2e-4, 1.5e-3, 1.0e9, 2e-7, 1e-3
    out = np.zeros(12)
    _traction_through_the_engine(rule, 1000.0, a, b, p_h, h, du, 0.0, 0.0, out)
    s = barus.alpha_star * p_h
    W = 2.0 / 3.0 * math.pi * a * b * p_h
    closed = -3.0 * barus.eta0 * du / (h * p_h * s * s) * (math.exp(s) * (s - 1.0) + 1.0) * W
    assert out[0] == pytest.approx(closed, rel=0.02)


def test_a_toy_film_law_reaches_the_force_kernel(toys, o156):
    got, want = _film_through_the_model(toys["film"], o156)
    assert got.size >= 20
    np.testing.assert_allclose(got, 3.0e-7, rtol=0.0)
    np.testing.assert_allclose(want, 3.0e-7, rtol=0.0)


def test_a_toy_pocket_law_reaches_the_pocket_contact(toys):
    p = pocket_contact_module.pocket_parameters(
        ball_diameter=0.01905, pocket_diameter=0.02023, pitch_radius=0.079, effective_modulus=1.45e11,
        restitution=0.7, friction_coefficient=0.0, law=toys["pocket"])
    clearance = 0.5 * (0.02023 - 0.01905)
    x_ball = np.array([0.079, clearance + 2e-6, 0.0])
    out = pocket_contact_module.pocket_contact(x_ball, np.array([0.0, 0.01, 0.0]), np.zeros(3), np.zeros(3),
                                               np.eye(3), np.zeros(3), np.zeros(3), 0.0, 0.0, p)
    delta = out[pocket_contact_module.P_OUT_DELTA]
    assert out[pocket_contact_module.P_OUT_FN] == pytest.approx(1e8 * delta + 50.0 * 0.01, rel=1e-10)


def test_a_toy_land_law_reaches_the_journal(toys):
    """Half film, half metal: at eps = 1.2 the radial force is 0.5 (film at the clip) + 0.5
    (Lundberg's load), whatever the hybrid law would do there (metal alone)."""
    p, out = _journal(toys["land"], 1.2)
    film = short_bearing.ocvirk_force(p.eps_clip, p.viscosity, 300.0, p.radius, p.length, p.clearance)[0]
    metal = lundberg_load(0.2 * p.clearance, p.length, p.e_eff)[0]
    assert -out[short_bearing.J_OUT_FORCE] == pytest.approx(0.5 * film + 0.5 * metal, rel=1e-10)
    _, hybrid = _journal("hybrid", 1.2)
    assert -hybrid[short_bearing.J_OUT_FORCE] == pytest.approx(metal, rel=1e-10)


def test_a_bundle_of_no_law_is_refused_by_name():
    class Stray(NamedTuple):
        x: float = 1.0

    with pytest.raises(TypeError, match="bundle of no traction law"):
        TRACTION_LAWS.law_of(Stray)
    with pytest.raises(KeyError, match="no land law 'wet'; choose from hybrid"):
        LAND_LAWS["wet"]
