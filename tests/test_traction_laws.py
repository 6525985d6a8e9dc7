"""Traction laws (dynamics/traction/laws): the registry, and the limiting-shear law of Bair &
Winer through the public routes -- the reference quadrature against closed forms, the fast
engine against the quadrature, and a bearing model that runs with it.

Limiting shear (docs/model.md M.79; Bair & Winer, J. Lubr. Technol. 101 (1979) 258-265):
tau = tau_L (1 - exp(-eta |s|/(tau_L h))), tau_L = Lambda 2 p_h/3.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from bearingsim.dynamics.lubrication.film_laws import nvm as film
from bearingsim.dynamics.lubrication.lubricant import load_builtin_lubricant
from bearingsim.dynamics.traction import laws
from bearingsim.dynamics.traction.laws.coulomb import Coulomb
from bearingsim.dynamics.traction.laws.limiting_shear import LimitingShear
from bearingsim.dynamics.traction import quadrature as traction
from bearingsim.dynamics.traction.fast import FastTraction
from tests.lubrication_points import random_operating_points

LAMBDA = 0.075
REF_GRID = (128, 1024)  # the converged reference grid of tests/test_traction.py


@pytest.fixture(scope="module")
def o156():
    return load_builtin_lubricant("nato-o156")


def _barus(eta0, alpha):
    return 0, np.array([eta0, alpha])


def test_registry_is_what_options_and_scenes_offer():
    from bearingsim.dynamics.bearing.options import ModelOptions

    choices = {f.name: f.metadata for f in ModelOptions.__dataclass_fields__.values()}["traction"]["choices"]
    assert choices is laws.LAWS  # the registry itself: a law registered later is a choice too
    assert set(choices) >= {"eyring", "limiting-shear", "coulomb", "none"}
    with pytest.raises(ValueError, match="has no film: choose one of eyring, limiting-shear"):
        FastTraction.build(load_builtin_lubricant("nato-o156")).with_law(Coulomb(0.1, 1e-3))


def test_limiting_shear_full_sliding_gives_lambda():
    # every point saturates (x = eta du/(tau_L h) >= eta0 du/(tau_L h) = 2000, tau_L = 5e7 Pa):
    # tau -> tau_L everywhere, so mu = |F_x| / W = tau_L pi a b / (2/3 pi a b p_h) = Lambda
    a, b, p_h, h, eta0, alpha, du = 2e-4, 1.5e-3, 1.0e9, 1e-7, 1000.0, 1e-8, 10.0
    model, par = _barus(eta0, alpha)
    Fx, Fy, Mz, _ = traction.traction_quadrature(a, b, p_h, h, LimitingShear(LAMBDA), model, par,
                                                 du, 0.0, 0.0, (48, 64))
    W = 2.0 / 3.0 * math.pi * a * b * p_h
    assert -Fx / W == pytest.approx(LAMBDA, rel=1e-12)
    assert abs(Fy) < 1e-12 * abs(Fx) and abs(Mz) < 1e-12 * abs(Fx) * b


def test_limiting_shear_small_slip_is_newtonian():
    # 1 - e^-x = x (1 - x/2 + ...): the Barus closed form of tests/test_traction.py,
    # f = 3 eta0 du [e^s (s-1) + 1]/(h p_h s^2), s = alpha p_h, to x/2; here x <= 3e-5 (eta at the
    # centre 0.005 e^18 = 3.3e5 Pa.s, tau_L = 6e7 Pa)
    a, b, p_h, h, eta0, alpha, du = 2e-4, 1.5e-3, 1.2e9, 2e-7, 0.005, 1.5e-8, 1e-9
    model, par = _barus(eta0, alpha)
    Fx, _, _, _ = traction.traction_quadrature(a, b, p_h, h, LimitingShear(LAMBDA), model, par,
                                               du, 0.0, 0.0, (48, 64))
    W = 2.0 / 3.0 * math.pi * a * b * p_h
    s = alpha * p_h
    f_closed = 3 * eta0 * du * (math.exp(s) * (s - 1) + 1) / (h * p_h * s * s)
    assert -Fx / W == pytest.approx(f_closed, rel=1e-4)


def test_limiting_shear_jacobian_matches_finite_differences(o156):
    point = list(random_operating_points(1, seed=3, lubricant=o156, film=film.film_central_nvm)[0])
    shear, grid = LimitingShear(LAMBDA), (24, 96)

    def ref(p):
        return traction.traction_quadrature(*p[:4], shear, o156.model_code, o156.rheology_params(), *p[4:], grid)

    J = ref(point)[3]
    for col in range(3):
        d = 1e-6 * max(abs(point[4 + col]), 1e-3) if col < 2 else 1e-6 * max(abs(point[6]), 1.0)
        hi, lo = list(point), list(point)
        hi[4 + col] += d
        lo[4 + col] -= d
        fd = (np.array(ref(hi)[:3]) - np.array(ref(lo)[:3])) / (2 * d)
        assert np.allclose(J[:, col], fd, rtol=1e-4, atol=1e-5 * np.abs(J[:, col]).max())


def test_fast_engine_agrees_with_the_quadrature_for_limiting_shear(o156):
    """The engine's pole-centred rule with the limiting-shear response, against the (128, 1024)
    reference: within the 2 % of the force and moment (3 % Jacobian) the Eyring rule is held to
    (tests/test_traction_fast.py)."""
    fast = FastTraction.build(o156).with_law(LimitingShear(LAMBDA))
    shear = LimitingShear(LAMBDA)
    worst, apart = np.zeros(3), 0.0
    eyring = FastTraction.build(o156)
    for a, b, p_h, h, du0, dv0, w_s in random_operating_points(24, seed=5, lubricant=o156, film=film.film_central_nvm):
        F, J, flag = fast.evaluate(a, b, p_h, h, du0, dv0, w_s)
        F_eyring = eyring.evaluate(a, b, p_h, h, du0, dv0, w_s)[0]
        apart = max(apart, math.hypot(*(F - F_eyring)[:2]) / math.hypot(*F[:2]))
        Fx, Fy, Mz, Jr = traction.traction_quadrature(a, b, p_h, h, shear, o156.model_code, o156.rheology_params(),
                                                      du0, dv0, w_s, REF_GRID)
        scale_F = math.hypot(Fx, Fy)
        eF = math.hypot(F[0] - Fx, F[1] - Fy) / scale_F
        eM = abs(F[2] - Mz) / max(abs(Mz), scale_F * b)
        eJ = np.abs(J - Jr).max() / np.abs(Jr).max()
        worst = np.maximum(worst, (eF, eM, eJ))
    print(f"limiting shear, fast against quadrature: F {worst[0]:.2%}, M {worst[1]:.2%}, J {worst[2]:.2%}")
    assert worst[0] < 0.02 and worst[1] < 0.02 and worst[2] < 0.03
    # and it is not the Eyring law: where the contacts slide, the two laws part
    assert apart > 0.1


def test_a_bearing_runs_with_the_limiting_shear_law():
    """The registry's law reaches the force kernel: a residual of the reference bearing with
    physics.traction = 'limiting-shear' is finite, and its traction differs from Eyring's."""
    from bearingsim.dynamics.bearing import BearingModel, ModelOptions
    from bearingsim.dynamics.bearing.run import initial_coordinates
    from tests.bearing_fixtures import reference_model

    lub = load_builtin_lubricant("nato-o156")
    g = {}
    for law in ("eyring", "limiting-shear"):
        params, start = reference_model(options=ModelOptions(traction=law), lubricant=lub)
        model = BearingModel(params)
        q, v = initial_coordinates(params, start)
        n = model.n_dof
        ma, gv = np.zeros(n), np.zeros(n)
        model.evaluate(0.0, q, v, np.zeros(n), ma, gv)
        assert np.all(np.isfinite(gv))
        g[law] = gv
    assert not np.allclose(g["eyring"], g["limiting-shear"], rtol=1e-6)
