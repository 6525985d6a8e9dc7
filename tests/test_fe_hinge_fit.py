"""The M.2 fit on synthetic hinge responses, and the Richardson estimate."""

import dataclasses
import math

import numpy as np
import pytest

from bearingsim.fe_model import FEConfig, fit_hinge, richardson
from bearingsim.fe_model.identify import load_cases


def _random_hinge(seed: int):
    rng = np.random.default_rng(seed)
    A = rng.normal(size=(3, 3))
    H_u = 1e8 * (A @ A.T + 3.0 * np.eye(3))  # SPD, N/m
    H_psi = rng.uniform(1e5, 1e7, 2)  # N*m/rad
    return H_u, H_psi


def _hinge_responses(loads, H_u, H_psi, coupling=None):
    """Responses of the hinge of M.17 to loads at its centre: u = H_u^-1 F, psi = M / H_psi."""
    u = np.linalg.solve(H_u, loads[:, :3].T).T
    psi = loads[:, 3:5] / H_psi
    responses = np.column_stack([u, psi, np.zeros(len(loads))])
    if coupling is not None:
        responses[:, :5] += loads[:, :5] @ coupling.T
    return responses


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_fit_recovers_a_known_hinge_to_round_off(seed):
    H_u, H_psi = _random_hinge(seed)
    loads, groups, _ = load_cases(FEConfig())
    fit = fit_hinge(loads, _hinge_responses(loads, H_u, H_psi), groups)
    np.testing.assert_allclose(fit.H_u, H_u, rtol=1e-12, atol=1e-12 * np.abs(H_u).max())
    np.testing.assert_allclose(fit.H_psi, H_psi, rtol=1e-12)
    assert fit.relative_residual < 1e-13
    assert fit.magnitude_spread < 1e-12
    assert fit.coupling["translation_rotation_max"] < 1e-12
    assert fit.coupling["bending_cross"] < 1e-12


def test_fit_is_invariant_to_the_load_magnitudes():
    H_u, H_psi = _random_hinge(5)
    fits = []
    for forces, moments in [((-1000.0, 1000.0), (250.0,)), ((1.0, 17.0, -333.0), (-1000.0, 0.5, 999.0))]:
        config = dataclasses.replace(FEConfig(), perturbation_forces=forces, perturbation_moments=moments)
        loads, groups, _ = load_cases(config)
        fits.append(fit_hinge(loads, _hinge_responses(loads, H_u, H_psi), groups))
    np.testing.assert_allclose(fits[0].H_u, fits[1].H_u, rtol=1e-12, atol=1e-12 * np.abs(H_u).max())
    np.testing.assert_allclose(fits[0].H_psi, fits[1].H_psi, rtol=1e-12)


def test_unrepresented_coupling_is_reported_and_leaves_the_fit_least_squares():
    H_u, H_psi = np.diag([1e9, 1e9, 5e8]), np.array([1e6, 2e6])
    coupling = np.zeros((5, 5))
    coupling[0, 4] = coupling[4, 0] = 2e-7  # u_x per M_y and theta_y per F_x (Maxwell pair)
    loads, groups, _ = load_cases(FEConfig())
    fit = fit_hinge(loads, _hinge_responses(loads, H_u, H_psi, coupling), groups)
    # force and moment cases are separate: the coupling cannot bias H_u or H_psi
    np.testing.assert_allclose(fit.H_u, H_u, rtol=1e-12, atol=1e-3)
    expected = 2e-7 / math.sqrt(1e-9 * 0.5e-6)  # G_xy / sqrt(G_xx G_yy), flexibilities
    assert fit.coupling["translation_rotation_max"] == pytest.approx(expected, rel=1e-10)
    assert fit.relative_residual > 0.01


def test_cases_missing_an_axis_cannot_determine_the_hinge():
    H_u, H_psi = _random_hinge(1)
    loads, groups, _ = load_cases(FEConfig())
    keep = loads[:, 2] == 0.0  # no axial force
    with pytest.raises(ValueError, match="do not determine"):
        fit_hinge(loads[keep], _hinge_responses(loads[keep], H_u, H_psi))


def test_a_non_positive_compliance_is_an_error():
    loads, _, _ = load_cases(FEConfig())
    responses = _hinge_responses(loads, np.eye(3) * 1e8, np.array([1e6, 1e6]))
    with pytest.raises(ValueError, match="positive definite"):
        fit_hinge(loads, -responses)


def test_richardson_recovers_limit_and_order_of_a_power_law():
    # f = f0 + C h^p exactly: the extrapolation must return f0 and p (Roache 1998, §5.4)
    h = np.array([0.02, 0.013, 0.009, 0.006])
    f0, p = richardson(h, 7.0e8 + 3.0e11 * h**2.3)
    assert f0 == pytest.approx(7.0e8, rel=1e-9)
    assert p == pytest.approx(2.3, rel=1e-8)


def test_richardson_without_monotone_convergence_says_so():
    f0, p = richardson(np.array([0.02, 0.01, 0.005]), np.array([1.0, 1.1, 1.05]))
    assert math.isnan(p) and f0 == 1.05
