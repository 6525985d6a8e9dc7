"""Error control on physical scales and the Newton start/stop rules (docs/model.md M.99–M.102).

The reference numbers come from closed forms: the Hertz impact of a sphere on a flat (Johnson,
"Contact Mechanics", CUP 1985, §11.4: maximum approach delta* = (5 m V^2 / (4 k))^(2/5) and
contact duration 2.94 delta* / V for a force k delta^(3/2)) and the plane pendulum's elliptic
solution (test_mb_hht.pendulum_exact)."""

import math

import numpy as np
import pytest

from bearingsim.dynamics.multibody import HHTSettings, integrate
from bearingsim.dynamics.multibody.example_problems import Pendulum
from bearingsim.dynamics.multibody.step_control import scaled_difference_norm

from .test_mb_hht import pendulum_exact


class HertzDrop:
    """A mass m flying at speed -V onto a half-space with force k delta^(3/2) (delta = -x > 0);
    no gravity, so between contacts nothing changes. Its physical error scale is delta*."""

    n_dof = 1
    rotation_slots = np.zeros(0, dtype=np.int64)
    error_weights = np.ones(1)

    def __init__(self, m, k, V, with_scales=True):
        self.m, self.k, self.V = m, k, V
        self.delta_star = (5.0 * m * V * V / (4.0 * k)) ** 0.4
        self.S = np.zeros((1, 1))
        if with_scales:
            self.error_scales = lambda t0, q0, v0: np.array([self.delta_star])
        self.contact = []  # (t, x) of accepted steps

    def evaluate(self, t, q, v, a, ma, g):
        ma[0] = self.m * a[0]
        g[0] = self.k * (-q[0]) ** 1.5 if q[0] < 0.0 else 0.0

    def jacobian(self, t, q, v, a, c_m, c_v, c_q):
        k_t = 1.5 * self.k * math.sqrt(-q[0]) if q[0] < 0.0 else 0.0
        self.S[0, 0] = c_m * self.m + c_q * k_t
        return self.S

    def on_accepted_step(self, t, q, v, a):
        self.contact.append((t, q[0], v[0]))


def crossing_times(history):
    """Times where x changes sign, by linear interpolation between accepted steps."""
    h = np.array(history)
    t, x = h[:, 0], h[:, 1]
    out = []
    for i in np.flatnonzero(np.sign(x[1:]) != np.sign(x[:-1])):
        out.append(t[i] - x[i] * (t[i + 1] - t[i]) / (x[i + 1] - x[i]))
    return out


def test_norm_is_the_worst_coordinate_on_its_own_scale():
    e = np.array([1e-9, -4e-9, 2e-9])
    zero, q = np.zeros(3), np.array([0.08, 0.08, 0.08])
    w = np.array([1.0, 1.0, 0.0])  # the third coordinate is excluded
    scales = np.array([1e-3, 1e-2, 1.0])
    # max over weighted coordinates of |e_i| / (atol + rtol L_i): 1e-9/1e-9, 4e-9/1e-8
    assert scaled_difference_norm(e, zero, 1.0, q, q, w, scales, 0.0 + 1e-30, 1e-6, True) == pytest.approx(1.0)
    rms = math.sqrt((1.0 ** 2 + 0.4 ** 2) / 2)
    assert scaled_difference_norm(e, zero, 1.0, q, q, w, scales, 1e-30, 1e-6, False) == pytest.approx(rms)
    # without scales the relative part is of |q| (a problem that defines none)
    assert scaled_difference_norm(e, zero, 1.0, q, q, w, np.zeros(0), 1e-30, 1e-6, True) == \
        pytest.approx(4e-9 / (1e-6 * 0.08))
    assert scaled_difference_norm(np.array([np.nan, 0, 0]), zero, 1.0, q, q, w, scales, 1e-9, 0.0, True) == math.inf


def test_controller_shortens_steps_at_an_impact_and_meets_hertz_duration():
    m, k, V = 0.028, 1.0e10, 0.5  # a 19 mm steel ball, Hertz constant of steel on steel [N/m^1.5]
    drop = HertzDrop(m, k, V)
    t_c = 2.94 * drop.delta_star / V  # Johnson §11.4
    x0 = 10 * drop.delta_star
    settings = HHTSettings(alpha=0.0, rtol=1e-4, atol=1e-15, first_step=1e-7, min_step=1e-12, max_step=1e-4)
    sol = integrate(drop, 0.0, x0 / V + t_c + x0 / V, np.array([x0]), np.array([-V]), settings)
    times = crossing_times(drop.contact)
    assert len(times) == 2
    assert times[1] - times[0] == pytest.approx(t_c, rel=0.01)  # 2.94 is rounded to 3 digits
    assert sol.v[0] == pytest.approx(V, rel=1e-3)  # elastic: the ball leaves at its impact speed
    h = np.diff([0.0] + [row[0] for row in drop.contact])
    x = np.array([row[1] for row in drop.contact])
    in_contact, free = h[x < 0.0], h[x > 2 * drop.delta_star]
    assert in_contact.size >= 20 and in_contact.max() < t_c / 15  # the contact is resolved ...
    assert free.max() == pytest.approx(settings.max_step)  # ... and the free flight is not


def test_without_physical_scales_an_offset_coordinate_defeats_the_relative_tolerance():
    """The failure the physical scales remove: the same impact far from the origin (x0 ~ 0.08 m,
    like a ball's absolute position) is not resolved by the same rtol relative to |q|."""
    m, k, V = 0.028, 1.0e10, 0.5
    offset = 0.08

    class Offset(HertzDrop):
        def evaluate(self, t, q, v, a, ma, g):
            super().evaluate(t, q - offset, v, a, ma, g)

        def jacobian(self, t, q, v, a, c_m, c_v, c_q):
            return super().jacobian(t, q - offset, v, a, c_m, c_v, c_q)

    settings = HHTSettings(alpha=0.0, rtol=1e-4, atol=1e-15, first_step=1e-7, min_step=1e-12, max_step=1e-4)
    runs = {}
    for scaled in (True, False):
        drop = Offset(m, k, V, with_scales=scaled)
        t_c = 2.94 * drop.delta_star / V
        x0 = offset + 10 * drop.delta_star
        integrate(drop, 0.0, 2 * (x0 - offset) / V + t_c, np.array([x0]), np.array([-V]), settings)
        h = np.diff([0.0] + [row[0] for row in drop.contact])
        runs[scaled] = h[np.array([row[1] for row in drop.contact]) < offset].size
    assert runs[True] >= 20 and runs[False] * 5 <= runs[True], runs


@pytest.mark.parametrize("alpha", [0.0, 0.1])
def test_newton_estimate_and_linear_start_save_iterations_at_equal_accuracy(alpha):
    omega0, theta0, T = 2.0, 1.0, 3.0
    base = dict(alpha=alpha, rtol=1e-7, atol=1e-9, first_step=1e-4, min_step=1e-8, max_step=0.05)
    out = {}
    for name, kw in {"default": {}, "old": {"predictor": "constant", "newton_test": "correction"}}.items():
        sol = integrate(Pendulum(omega0), 0.0, T, np.array([theta0]), np.zeros(1), HHTSettings(**base, **kw))
        out[name] = (sol.stats.newton_iterations / sol.stats.steps, abs(sol.q[0] - pendulum_exact(theta0, omega0, T)),
                     sol.stats.steps)
    its_new, err_new, _ = out["default"]
    its_old, err_old, _ = out["old"]
    assert its_new < 1.3 and its_old > 1.9, out
    assert err_new < 2.0 * err_old + 1e-9, out


def test_first_iteration_shortcut_refused_for_a_large_correction():
    """An impact: the first correction exceeds the error tolerance, so Newton iterates again even
    though the last step contracted fast (M.102)."""
    drop = HertzDrop(0.028, 1.0e10, 0.5)
    settings = HHTSettings(alpha=0.0, rtol=1e-4, atol=1e-15, first_step=1e-7, min_step=1e-12, max_step=1e-4)
    x0 = 10 * drop.delta_star
    sol = integrate(drop, 0.0, 2 * x0 / 0.5 + 3 * drop.delta_star / 0.5, np.array([x0]), np.array([-0.5]), settings)
    assert sol.stats.newton_iterations > sol.stats.steps  # at least the contact steps iterate twice


class SkewedTangent:
    """Two free unit masses under constant forces f, with a deliberately wrong tangent
    J_a = M (I - G)^-1: Newton's error then evolves as e_{k+1} = G e_k. With G = [[0, c], [0, 0]]
    the second correction is as large as the first before the iteration converges exactly (the
    non-normal transient of a prescribed row, seen in the bearing at t = 0.313 s); with G = g I,
    g > 1, it truly diverges."""

    n_dof = 2
    rotation_slots = np.zeros(0, dtype=np.int64)
    error_weights = np.ones(2)

    def __init__(self, G, f=(1.0, 1.0)):
        self.f = np.array(f)
        self.J = np.linalg.inv(np.eye(2) - np.array(G, dtype=float))

    def evaluate(self, t, q, v, a, ma, g):
        ma[:] = a
        g[:] = self.f

    def jacobian(self, t, q, v, a, c_m, c_v, c_q):
        return c_m * self.J


def _one_step(problem, settings):
    from bearingsim.dynamics.multibody.hht import HHTState, HHTStepper
    from bearingsim.dynamics.multibody.linear_solvers import DenseSolver
    from bearingsim.dynamics.multibody.results import SolverStats

    stepper = HHTStepper(problem, settings, DenseSolver(), SolverStats())
    y = HHTState(2)
    problem.evaluate(0.0, y.q, y.v, y.a, np.zeros(2), y.g)  # a_n = 0 against forces f: Newton must move a
    return stepper.step(0.0, settings.first_step, y)


@pytest.mark.parametrize("c, f, expect", [
    (2.0, (0.0, 1.0), "SUCCESSFUL"),       # corrections (2, 1) then (2, 0) within tolerance: converges
    (2.0, (0.0, 1e6), "NEWTON_DIVERGED"),  # the same transient far beyond the tolerance
])
def test_non_contracting_correction_within_tolerance_is_not_a_divergence(c, f, expect):
    # error scale atol = 1e-3 m, beta h^2 = 0.3025e-4: a correction of 1 m/s^2 is 0.03 tolerance
    settings = HHTSettings(alpha=0.1, rtol=0.0, atol=1e-3, first_step=1e-2, min_step=1e-2, max_step=1e-2,
                           adaptive=False, predictor="constant", newton_test="correction", reuse_jacobian="step")
    y1, err, result = _one_step(SkewedTangent([[0.0, c], [0.0, 0.0]], f), settings)
    assert result.name == expect
    if expect == "SUCCESSFUL":
        np.testing.assert_allclose(y1.a, f, atol=1e-12)  # M a = (1 - alpha) f + alpha g_n, g_n = f


def test_true_divergence_is_still_reported():
    settings = HHTSettings(alpha=0.1, rtol=0.0, atol=1e-9, first_step=1e-2, min_step=1e-2, max_step=1e-2,
                           adaptive=False, reuse_jacobian="step")
    _, _, result = _one_step(SkewedTangent(np.eye(2) * 1.5), settings)
    assert result.name == "NEWTON_DIVERGED"
