"""Rheology kernels and the built-in lubricant (docs/model.md §6.4)."""

import math

import numpy as np
import pytest

from bearingsim.dynamics.lubrication import rheology
from bearingsim.dynamics.lubrication.lubricant import Lubricant, builtin_lubricant_names, load_builtin_lubricant, lubricant_from_dict


@pytest.fixture(scope="module")
def o156():
    return load_builtin_lubricant("nato-o156")


def test_barus_is_exponential():
    # Barus (1893): ln(eta/eta0) = alpha p, closed form
    eta0, alpha = 0.01, 2e-8
    for p in (0.0, 1e8, 1e9):
        assert rheology.viscosity_barus(p, eta0, alpha) == pytest.approx(eta0 * math.exp(alpha * p), rel=1e-14)
    assert rheology.pressure_viscosity_coefficient(rheology.MODEL_BARUS, np.array([eta0, alpha])) == alpha


def test_roelands_closed_form_and_slope():
    # Roelands (1966): ln(eta/eta0) = (ln eta0 + 9.67)((1 + p/1.96e8)^z - 1); at p = p_r (2^z - 1)
    eta0, z = 0.0049, 0.6
    p = 1.96e8 * 3.0  # 1 + p/p_r = 4
    expected = eta0 * math.exp((math.log(eta0) + 9.67) * (4.0**z - 1.0))
    assert rheology.viscosity_roelands(p, eta0, z) == pytest.approx(expected, rel=1e-13)
    # initial slope z (ln eta0 + 9.67)/p_r vs a central difference of ln eta
    params = np.array([eta0, z])
    dp = 1e3
    fd = (math.log(rheology.viscosity(dp, 1, params)) - math.log(rheology.viscosity(-dp, 1, params))) / (2 * dp)
    assert rheology.pressure_viscosity_coefficient(1, params) == pytest.approx(fd, rel=1e-6)


def test_wlf_reduces_to_wlf_at_ambient_and_clamps_at_glass():
    # Yasutomi, Bair & Winer (1984): at p = 0, T_g = T_g0, F = 1 -> plain WLF in T - T_g0
    T, Tg0, C1, C2 = 373.15, 180.0, 16.0, 30.0
    expected = 10 ** (12.0 - C1 * (T - Tg0) / (C2 + T - Tg0))
    assert rheology.viscosity_wlf(0.0, T, Tg0, 200.0, 5e-10, 0.2, 1e-8, C1, C2) == pytest.approx(expected, rel=1e-13)
    # above the glass pressure the clamp holds eta at eta_g, finite for any p
    etas = [rheology.viscosity_wlf(p, T, Tg0, 200.0, 5e-10, 0.2, 1e-8, C1, C2) for p in np.linspace(0, 2e10, 200)]
    assert np.all(np.isfinite(etas)) and max(etas) == pytest.approx(1e12)
    assert np.all(np.diff(etas) >= 0.0)  # monotone in p for this set


def test_wlf_alpha_star_matches_finite_difference(o156):
    params = o156.rheology_params()
    for T in (40.0, 100.0, 150.0):
        par = o156.at_temperature(T).rheology_params()
        dp = 1e4
        fd = (math.log(rheology.viscosity(dp, 2, par)) - math.log(rheology.viscosity(0.0, 2, par))) / dp
        fd2 = (math.log(rheology.viscosity(2 * dp, 2, par)) - math.log(rheology.viscosity(0.0, 2, par))) / (2 * dp)
        richardson = 2 * fd - fd2  # one-sided, O(dp^2)
        assert rheology.pressure_viscosity_coefficient(2, par) == pytest.approx(richardson, rel=1e-6)
    assert params.flags["C_CONTIGUOUS"]


def test_kernels_equal_py_func_on_random_inputs():
    rng = np.random.default_rng(3)
    for _ in range(50):
        p = rng.uniform(0, 3e9)
        eta0, alpha, z = rng.uniform(1e-3, 0.1), rng.uniform(5e-9, 3e-8), rng.uniform(0.3, 0.9)
        wlf = np.array([rng.uniform(300, 450), rng.uniform(150, 200), rng.uniform(50, 250), rng.uniform(1e-10, 1e-9),
                        rng.uniform(0.05, 0.3), rng.uniform(1e-9, 3e-8), rng.uniform(12, 18), rng.uniform(20, 60)])
        for model, par in ((0, np.array([eta0, alpha])), (1, np.array([eta0, z])), (2, wlf)):
            assert rheology.viscosity(p, model, par) == pytest.approx(rheology.viscosity.py_func(p, model, par), rel=1e-12)
            assert rheology.pressure_viscosity_coefficient(model, par) == pytest.approx(
                rheology.pressure_viscosity_coefficient.py_func(model, par), rel=1e-12)


def test_nato_o156_meets_the_spec_targets(o156):
    # targets of docs/model.md §6.4 (eta 4.8-5.0 mPa.s at 100 C, ~25 mPa.s at 40 C, rho ~920 kg/m3,
    # alpha 1.0-1.1e-8 1/Pa at 100 C, tau0 ~5 MPa)
    assert "nato-o156" in builtin_lubricant_names()
    assert o156.temperature_degC == 100.0
    assert 4.8e-3 <= o156.eta0 <= 5.0e-3
    assert o156.at_temperature(40.0).eta0 == pytest.approx(25e-3, rel=0.04)
    assert 1.0e-8 <= o156.alpha_star <= 1.1e-8
    assert o156.density_at_temperature() == pytest.approx(920.0, rel=0.03)
    assert o156.eyring_stress == 5e6
    # MIL-PRF-23699: kinematic viscosity at 100 C between 4.90 and 5.40 cSt
    assert 4.90e-6 <= o156.eta0 / o156.density_at_temperature() <= 5.40e-6


def test_equivalent_barus_and_roelands_share_eta0_and_alpha(o156):
    for other in (o156.as_barus(), o156.as_roelands()):
        assert other.eta0 == pytest.approx(o156.eta0, rel=1e-12)
        assert other.alpha_star == pytest.approx(o156.alpha_star, rel=1e-12)


def test_bad_lubricant_values_are_explained():
    with pytest.raises(ValueError, match="viscosity_model"):
        Lubricant(name="x", viscosity_model="vogel", temperature_degC=100.0, eyring_stress=5e6)
    with pytest.raises(ValueError, match="ambient_viscosity"):
        Lubricant(name="x", viscosity_model="barus", temperature_degC=100.0, eyring_stress=5e6,
                  pressure_viscosity_coefficient=1e-8)
    with pytest.raises(ValueError, match=r"eyring_stress = -1.0 .*Pa"):
        Lubricant(name="x", viscosity_model="barus", temperature_degC=100.0, eyring_stress=-1.0,
                  ambient_viscosity=0.01, pressure_viscosity_coefficient=1e-8)
    with pytest.raises(ValueError, match="unknown key"):
        lubricant_from_dict({"name": "x", "viscosity_model": "barus", "temperatur": 100})
    with pytest.raises(ValueError, match="built-in sets are"):
        load_builtin_lubricant("nato-o999")
