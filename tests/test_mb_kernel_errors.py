"""A force kernel that raises inside the compiled time loop (dynamics/multibody/compiled.py).

The loop calls its kernel as a numba first-class function value, through numba's C entry,
which cannot pass an exception on: it reports it to `sys.unraisablehook` and returns 0.0. The
run must still fail with the kernel's exception, not go on with half-filled forces. The
problem here is a two-coordinate damped oscillator in block-arrow form (one small block, one
border coordinate) whose kernel raises after a given time."""

from __future__ import annotations

import sys
import threading

import numba
import numpy as np
import pytest

from bearingsim.dynamics.multibody import IntegrationError, integrate
from bearingsim.dynamics.multibody.compiled import CompiledProblem, KernelFunction, integrate_compiled, \
    kernel_errors
from bearingsim.dynamics.multibody.linear_solvers import BlockArrowMatrix, BlockArrowSolver

STIFFNESS, DAMPING, MASS = 1.0e4, 2.0, 1.0  # N/m, N s/m, kg: a 16 Hz oscillator


@numba.njit(cache=True, _nrt=False)
def _oscillator_forces(t, q, v, a, data, want_tangent, ma, g, diag, K, C):
    """g = -k q - c v on both coordinates; raises once t passes data[0]."""
    if t > data[0]:
        raise ValueError("the oscillator's kernel fails past its given time")
    for i in range(2):
        ma[i] = MASS * a[i]
        g[i] = -STIFFNESS * q[i] - DAMPING * v[i]
    diag[0] = t
    if want_tangent:
        K.D[0, 0, 0], K.B[0, 0] = STIFFNESS, STIFFNESS
        C.D[0, 0, 0], C.B[0, 0] = DAMPING, DAMPING
    return 0.0


@numba.njit(cache=True, _nrt=False)
def _never_drain(t, q, v, a, data, diag, hook):
    """The accepted-step hook: raises once t passes hook[0], never asks for a drain."""
    if t > hook[0]:
        raise ValueError("the oscillator's hook fails past its given time")
    return bool(False)  # a plain bool: the constant False is typed as a literal, not the hook's return type


class Oscillator:
    """The multibody protocol (problem.py) with a compiled side (`compiled`)."""

    n_dof = 2
    rotation_slots = np.zeros(0, dtype=np.int64)
    error_weights = np.ones(2)

    def __init__(self, t_fail: float, t_hook_fails: float = np.inf) -> None:
        self.data = np.array([t_fail])
        self.hook = np.array([t_hook_fails])
        self.diag = np.zeros(1)
        self.K, self.C = (BlockArrowMatrix.zeros(1, 1, 1).blocks() for _ in range(2))

    def _kernel_args(self, t, q, v, a, want_tangent, ma, g):
        return float(t), q, v, a, self.data, bool(want_tangent), ma, g, self.diag, self.K, self.C

    def evaluate(self, t, q, v, a, ma_out, g_out) -> None:
        _oscillator_forces(*self._kernel_args(t, q, v, a, False, ma_out, g_out))

    def jacobian(self, t, q, v, a, c_m, c_v, c_q) -> BlockArrowMatrix:
        S = BlockArrowMatrix.zeros(1, 1, 1)
        S.D[0, 0, 0] = S.B[0, 0] = c_m * MASS + c_v * DAMPING + c_q * STIFFNESS
        return S

    def compiled(self, compile_kernel: bool = True) -> CompiledProblem:
        n = np.zeros(2)
        kernel = KernelFunction(_oscillator_forces, self._kernel_args(0.0, n, n, n, False, n, n), compile_kernel)
        accepted = KernelFunction(_never_drain, (0.0, n, n, n, self.data, self.diag, self.hook), compile_kernel,
                                  returns=numba.types.boolean)
        return CompiledProblem(kernel, accepted, self.data, self.hook, np.full(2, MASS),
                               np.zeros(0, dtype=np.int64), self.diag, self.K, self.C, lambda: None)


START = (np.array([1e-3, -1e-3]), np.zeros(2))


def test_a_kernel_that_raises_stops_the_compiled_run_with_its_exception():
    hook_before = sys.unraisablehook
    with pytest.raises(IntegrationError) as failure:
        integrate_compiled(Oscillator(t_fail=5e-3), 0.0, 2e-2, *START, chunk_steps=50)
    error = failure.value
    assert isinstance(error.__cause__, ValueError)
    assert "ValueError" in error.reason and "fails past its given time" in error.reason
    assert error.t <= 5e-3  # the start of the chunk in which the kernel raised
    assert sys.unraisablehook is hook_before  # numba's reports go back where they went


def test_an_accepted_step_hook_that_raises_stops_the_compiled_run_too():
    """The hook is a first-class function value like the kernel, with the same C entry."""
    with pytest.raises(IntegrationError) as failure:
        integrate_compiled(Oscillator(t_fail=np.inf, t_hook_fails=5e-3), 0.0, 2e-2, *START, chunk_steps=50)
    assert isinstance(failure.value.__cause__, ValueError)
    assert "hook fails past its given time" in failure.value.reason
    assert failure.value.t <= 5e-3


def test_the_same_oscillator_runs_through_when_its_kernel_does_not_raise():
    """The control: without the failure the run ends at t1 and decays like the Python loop's."""
    sol, _ = integrate_compiled(Oscillator(t_fail=np.inf), 0.0, 2e-2, *START, chunk_steps=50)
    reference = integrate(Oscillator(t_fail=np.inf), 0.0, 2e-2, *START,
                          linear_solver=BlockArrowSolver(1, 1, 1))
    assert sol.t == pytest.approx(2e-2, abs=0.0)
    assert sol.stats.steps == reference.stats.steps
    np.testing.assert_allclose(sol.q, reference.q, rtol=1e-12, atol=1e-18)


def test_the_python_loop_raises_the_kernels_exception_where_it_happens():
    with pytest.raises(ValueError, match="fails past its given time"):
        integrate(Oscillator(t_fail=5e-3), 0.0, 2e-2, *START, linear_solver=BlockArrowSolver(1, 1, 1))


@numba.njit(cache=True, no_cfunc_wrapper=True)
def _no_c_entry(t, q, v, a, data, want_tangent, ma, g, diag, K, C):
    return 0.0


def test_a_kernel_without_a_c_entry_is_refused():
    problem = Oscillator(t_fail=np.inf)
    n = np.zeros(2)
    with pytest.raises(TypeError, match="no C entry"):
        KernelFunction(_no_c_entry, problem._kernel_args(0.0, n, n, n, False, n, n))


def test_runs_in_two_threads_get_their_own_kernels_errors():
    """A threaded worker may run two points at once: the reports of numba's C entry are routed
    to the run whose thread called the kernel. Chunks of 10 steps, so the threads alternate
    between chunks many times over the run."""
    outcomes: dict[str, object] = {}

    def run(name: str, t_fail: float) -> None:
        try:
            outcomes[name] = integrate_compiled(Oscillator(t_fail), 0.0, 2e-2, *START, chunk_steps=10)[0]
        except IntegrationError as exc:
            outcomes[name] = exc

    hook_before = sys.unraisablehook
    threads = [threading.Thread(target=run, args=("fails", 5e-3)), threading.Thread(target=run, args=("runs", np.inf))]
    for th in threads:
        th.start()
    for th in threads:
        th.join()
    assert isinstance(outcomes["fails"], IntegrationError)
    assert outcomes["runs"].t == pytest.approx(2e-2, abs=0.0)
    assert sys.unraisablehook is hook_before


def test_a_report_outside_any_run_goes_to_the_previous_hook():
    """While a run collects, a report from another thread reaches the hook that was in place."""
    seen = []
    previous = sys.unraisablehook
    sys.unraisablehook = seen.append
    try:
        with kernel_errors() as caught:
            other = threading.Thread(target=lambda: sys.unraisablehook("from another thread"))
            other.start()
            other.join()
            sys.unraisablehook("from this thread")
    finally:
        sys.unraisablehook = previous
    assert seen == ["from another thread"] and caught == ["from this thread"]
