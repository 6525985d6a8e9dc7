"""HHT-α integrator (docs/model.md §9): convergence order, numerical dissipation, energy
conservation, step control, sampling, failures, and the block-arrow path."""

import numpy as np
import pytest
from scipy.special import ellipj, ellipk

from bearingsim.dynamics.multibody import (BlockArrowSolver, DenseSolver, FixedIntervalSampler,
                                HHTSettings, IntegrationError, JacobianReuse, SolverStats,
                                integrate)
from bearingsim.dynamics.multibody.hht import HHTState, HHTStepper
from bearingsim.dynamics.multibody.example_problems import ArrowSprings, ElasticPendulum, Pendulum


def pendulum_exact(theta0, omega0, t):
    """Plane pendulum released from rest at theta0: theta = 2 asin(k sn(K - omega0 t | m)),
    k = sin(theta0/2), m = k^2 (Lawden, "Elliptic Functions and Applications", Springer 1989,
    §5.2; also Landau & Lifshitz, Mechanics, §11 problem 1 for the period 4K/omega0)."""
    k = np.sin(theta0 / 2)
    sn = ellipj(ellipk(k * k) - omega0 * t, k * k)[0]
    return 2 * np.arcsin(k * sn)


def fixed(alpha, h, **kw):
    return HHTSettings(alpha=alpha, first_step=h, min_step=h, max_step=h, adaptive=False,
                       atol=1e-6, rtol=0.0, **kw)


@pytest.mark.parametrize("alpha", [0.0, 0.1])
def test_second_order_convergence_on_nonlinear_pendulum(alpha):
    omega0, theta0, T = 2.0, 1.0, 3.0
    ns = np.array([100, 200, 400, 800, 1600])
    errs = []
    for n in ns:
        sol = integrate(Pendulum(omega0), 0.0, T, np.array([theta0]), np.zeros(1),
                        fixed(alpha, T / n, newton_tol=1e-8))
        assert sol.stats.steps == n and sol.t == pytest.approx(T)
        errs.append(abs(sol.q[0] - pendulum_exact(theta0, omega0, T)))
    slope = np.polyfit(np.log(T / ns), np.log(errs), 1)[0]
    assert abs(slope - 2.0) < 0.15, (slope, errs)


class LinearOscillator:
    n_dof = 1
    rotation_slots = np.zeros(0, dtype=np.int64)
    error_weights = np.ones(1)

    def __init__(self, omega):
        self.omega = omega
        self.S = np.zeros((1, 1))

    def evaluate(self, t, q, v, a, ma, g):
        ma[0] = a[0]
        g[0] = -self.omega**2 * q[0]

    def jacobian(self, t, q, v, a, c_m, c_v, c_q):
        self.S[0, 0] = c_m + c_q * self.omega**2
        return self.S


def spectral_radius(alpha, h_omega):
    """Spectral radius of the one-step map (q, v, a)_n -> (q, v, a)_{n+1} of the actual
    stepper on x'' + omega^2 x = 0 with h = 1."""
    problem = LinearOscillator(h_omega)
    settings = HHTSettings(alpha=alpha, first_step=1.0, min_step=1.0, max_step=1.0,
                           newton_tol=1e-14, atol=1.0, rtol=0.0, reuse_jacobian="newton")
    stepper = HHTStepper(problem, settings, DenseSolver(), SolverStats())
    A = np.zeros((3, 3))
    for j in range(3):
        y = HHTState(1)
        y.q[0], y.v[0], y.a[0] = np.eye(3)[j]
        y.g[0] = -h_omega**2 * y.q[0]
        y1, _, result = stepper.step(0.0, 1.0, y)
        assert result.name == "SUCCESSFUL"
        A[:, j] = y1.q[0], y1.v[0], y1.a[0]
    return np.abs(np.linalg.eigvals(A)).max()


@pytest.mark.parametrize("alpha", [0.0, 0.05, 0.1, 0.2, 1.0 / 3.0])
def test_spectral_radius_at_infinite_frequency(alpha):
    # Hilber, Hughes & Taylor (1977), Earthq. Eng. Struct. Dyn. 5, 283: rho_inf =
    # (1 - alpha)/(1 + alpha) in the paper's sign convention (their alpha = -ours).
    rho = spectral_radius(alpha, 1e8)
    assert rho == pytest.approx((1 - alpha) / (1 + alpha), rel=1e-3)
    # and no dissipation of well-resolved modes: rho -> 1 as h omega -> 0
    assert spectral_radius(alpha, 1e-3) == pytest.approx(1.0, abs=1e-6)


def test_energy_of_spring_pendulum_does_not_drift_over_1000_periods():
    # alpha = 0 is the trapezoidal rule on (q, v), conjugate to the symplectic midpoint rule:
    # bounded O(h^2) energy oscillation, no secular drift (Hairer, Lubich & Wanner, Geometric
    # Numerical Integration, 2nd ed. 2006: §VI.8 conjugate symplecticity of the trapezoidal
    # rule, §IX.8 long-time energy conservation). Drift = change of the 20-period mean.
    m, k, L0, grav = 1.0, 100.0, 1.0, 9.81
    p = ElasticPendulum(m, k, L0, grav)
    L = L0 + m * grav / k
    period = 2 * np.pi * np.sqrt(L / grav)
    steps_per_period = 100
    q0 = np.array([L * np.sin(0.3), -1.02 * L * np.cos(0.3)])
    energies = []
    integrate(p, 0.0, 1000 * period, q0, np.zeros(2),
              fixed(0.0, period / steps_per_period, newton_tol=1e-9),
              on_step=lambda t, q, v, a: energies.append(p.energy(q, v)))
    E = np.array(energies)
    E0 = p.energy(q0, np.zeros(2))
    window = 20 * steps_per_period
    drift = abs(E[-window:].mean() - E[:window].mean()) / abs(E0)
    assert drift < 1e-6, drift
    # the test can see a drift: the oscillation itself is much larger than the bound
    assert np.abs(E - E0).max() / abs(E0) > 1e-6


def test_adaptive_steps_meet_tolerance_with_rejections_and_sampling():
    omega0, theta0, T = 2.0, 2.5, 10.0
    end_errors = []
    for atol in (1e-6, 1e-8):
        settings = HHTSettings(alpha=0.1, first_step=0.5, min_step=1e-8, max_step=1.0,
                               rtol=0.0, atol=atol)
        sampler = FixedIntervalSampler(0.0, T, 0.01, 1)
        step_errors = []
        sol = integrate(Pendulum(omega0), 0.0, T, np.array([theta0]), np.zeros(1), settings,
                        sampler=sampler, on_step=lambda t, q, v, a: step_errors.append(
                            abs(q[0] - pendulum_exact(theta0, omega0, t))))
        assert sol.t == pytest.approx(T, rel=1e-14)
        st = sol.stats
        assert st.rejected_steps > 0  # first_step = 0.5 s is far too large
        assert st.steps == len(step_errors)
        assert st.newton_iterations >= st.steps and st.residual_evaluations >= st.steps
        assert 0 < st.factorizations < st.newton_iterations  # the matrix was reused
        assert sampler.count == sampler.t.size == 1001
        sample_err = np.abs(sampler.q[:, 0] - pendulum_exact(theta0, omega0, sampler.t)).max()
        # interpolation adds little to the integration error at the step ends
        assert sample_err < 1.5 * max(step_errors)
        end_errors.append(abs(sol.q[0] - pendulum_exact(theta0, omega0, T)))
    # global error follows the local tolerance (error per step ~ atol, O(h^3) local error)
    assert end_errors[1] < end_errors[0] / 10


@pytest.mark.parametrize("policy", list(JacobianReuse))
def test_reuse_policies_agree(policy):
    p = Pendulum(2.0, damping=0.3)
    s = HHTSettings(alpha=0.1, first_step=1e-3, min_step=1e-8, max_step=0.05, rtol=0.0,
                    atol=1e-8, newton_tol=1e-6, reuse_jacobian=policy)
    sol = integrate(p, 0.0, 2.0, np.array([1.0]), np.zeros(1), s)
    ref = integrate(p, 0.0, 2.0, np.array([1.0]), np.zeros(1),
                    HHTSettings(alpha=0.1, first_step=1e-3, min_step=1e-8, max_step=0.05,
                                rtol=0.0, atol=1e-8, newton_tol=1e-6))
    assert sol.q[0] == pytest.approx(ref.q[0], abs=1e-6)
    if policy is JacobianReuse.NEWTON:
        assert sol.stats.factorizations >= sol.stats.newton_iterations
    if policy is JacobianReuse.STEP:
        assert sol.stats.factorizations >= sol.stats.steps


def test_block_arrow_solver_gives_the_dense_trajectory():
    Z = 8
    rng = np.random.default_rng(3)
    q0 = rng.normal(size=3 * Z + 3) * 2e-4
    v0 = rng.normal(size=3 * Z + 3) * 0.05
    s = HHTSettings(alpha=0.1, first_step=1e-6, min_step=1e-9, max_step=2e-5, rtol=0.0,
                    atol=1e-9)
    block = integrate(ArrowSprings(Z, "block"), 0.0, 2e-3, q0, v0, s,
                      linear_solver=BlockArrowSolver(Z, 3, 3))
    dense = integrate(ArrowSprings(Z, "dense"), 0.0, 2e-3, q0, v0, s,
                      linear_solver=DenseSolver())
    assert block.stats.steps == dense.stats.steps
    np.testing.assert_allclose(block.q, dense.q, rtol=1e-9, atol=1e-15)


class NaNAfter(Pendulum):
    def evaluate(self, t, q, v, a, ma_out, g_out):
        super().evaluate(t, q, v, a, ma_out, g_out)
        if t > 0.5:
            g_out[0] = np.nan


def test_nan_residual_raises_with_time_reason_and_hint():
    s = HHTSettings(alpha=0.1, first_step=1e-2, min_step=1e-4, max_step=1e-2)
    with pytest.raises(IntegrationError) as info:
        integrate(NaNAfter(2.0), 0.0, 1.0, np.array([1.0]), np.zeros(1), s)
    err = info.value
    assert 0.49 < err.t <= 0.5 and err.h == pytest.approx(1e-4)
    assert "NaN" in str(err) and "minimum step" in str(err) and "Try:" in str(err)


def test_settings_errors_name_key_value_and_range():
    with pytest.raises(ValueError, match=r"solver.alpha = 0.5 .*le 0.333333"):
        HHTSettings(alpha=0.5)
    with pytest.raises(ValueError, match="min_step <= first_step <= max_step"):
        HHTSettings(first_step=1.0, max_step=1e-3)
