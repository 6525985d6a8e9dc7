"""The HHT-α time loop compiled into numba, for problems whose forces are a numba kernel
(docs/model.md §9, "Compiled loop").

The Python loop (`time_loop.integrate`, `hht.HHTStepper`) reaches the problem and the linear
solver through Python several times per step, which costs the reference bearing about a tenth of
its run time (unboxing the kernel's ~40 borrowed arrays per call, the loop's own bookkeeping,
the accepted-step hook). A problem that offers its forces as a numba kernel runs
here: the same method, the same decisions (the numba pieces shared with the Python loop:
`newmark_kinematics`, `hht_residual`, `newton_verdict`, `needs_refactor`,
`scaled_difference_norm`, `proposed_step`) and so the same steps, in chunks of up to
`max_steps` accepted steps between which Python reports progress and checks its budget.

What a problem supplies (`CompiledProblem`), with K and C in block-arrow form
(`linear_solvers.Blocks`) and a diagonal mass:

    kernel(t, q, v, a, data, want_tangent, ma, g, diag, K, C) -> float
        fills ma = M a, g = g(t, q, v), its diagnostics `diag`, and K_t = -dg/dq,
        C_t = -dg/dv when want_tangent (as the protocol's evaluate / jacobian; Newton's
        iterations call it without);
    accepted(t, q, v, a, data, diag, hook) -> bool
        after each accepted step, from the diagnostics of its last evaluation; True asks
        for the chunk to end so that Python can drain what the hook collected;
    rows whose residual the kernel replaces by a prescribed velocity (`joints.py`).

Both are numba first-class function values (`KernelFunction`: one compiled overload, called
through the C entry numba compiles beside it), not dispatchers. A dispatcher call links the
callee into the loop, where LLVM optimises it a second time (four times the compile time for
the bearing's force kernel); a function value is an address the loop calls, so loop, kernel and
hook are separate libraries that compile apart, even in separate processes (`compile_loop`). It
also keeps the loop one cached function for every problem: numba cannot cache a function that
holds a jitted function as a run-time value, so a loop that called its hook through a dispatcher
would have to be inlined into one wrapper per problem: a copy of the loop's whole IR, which numba
makes block by block with the function's whole scope each time (time growing as blocks times
variables). numba's C entry cannot pass an exception on: it reports it through
`sys.unraisablehook` and returns 0.0 (False), so `integrate_compiled` collects those reports and
raises after the chunk (`kernel_errors`).

Output per chunk: Hermite samples at fixed times (`sampling.hermite_fill`), step-end
records (t, q, v, diag) at the first accepted step at or after each multiple of `record_dt`,
and a step log (t, h, residual evaluations, factorisations) every `log_every` steps.
"""

from __future__ import annotations

import contextlib
import math
import sys
import threading
import time
from dataclasses import dataclass, field
from typing import Callable, NamedTuple

import numba
import numpy as np
from numba.core import types as nbtypes

from .._speed.compile_policy import INTERNAL, KERNEL, NO_REFCOUNT

from .buffers import zeroed
from .hht import NEWTON_CONVERGED, NEWTON_DIVERGED, hht_residual, newmark_kinematics, newton_verdict, \
    predict_acceleration, subtract_inplace
from .joints import prescribe_velocity_blocks
from .linear_solvers import Blocks, BlockArrowMatrix, BlockArrowSolver, assemble_iteration_blocks, \
    block_arrow_factor, block_arrow_solve
from .newton import needs_refactor
from .problem import check_problem, checked_error_scales
from .results import IntegrationError, NewtonStallWatch, Result, Solution, SolverStats, damping_first
from .sampling import Samples, StepEnds, hermite_fill
from .settings import HHTSettings, JacobianReuse
from .step_control import AT_MIN_STEP, LAST_STEP_STRETCH, MACHINE_EPSILON, NEWTON_FLOOR, proposed_step, \
    scaled_difference_norm

# float state (`Work.state`)
S_T, S_H, S_H_PREV, S_ETA, S_H_FACTORED, S_STALE, S_NEXT_RECORD, S_T_LOGGED, S_T_FAIL, S_H_FAIL = range(10)
# counters (`Work.counters`)
(N_STEPS, N_REJECTED, N_NEWTON_FAILURES, N_NEWTON_ITERATIONS, N_FACTORIZATIONS, N_RESIDUALS, N_MIN_STEP_ACCEPTS,
 N_SAMPLES, N_RECORDS, N_LOGGED, N_CUR) = range(11)
# chunk outcomes; a failed step returns FAILED + its Result's index in FAILURES
DONE, CHUNK_END, FAILED = 0, 1, 10
FAILURES = (Result.NEWTON_DIVERGED, Result.NEWTON_MAX_ITER, Result.NAN_RESIDUAL, Result.SINGULAR_MATRIX)
_OK, _DIVERGED, _MAX_ITER, _NAN, _SINGULAR = -1, 0, 1, 2, 3
STATS_COUNTERS = {"steps": N_STEPS, "rejected_steps": N_REJECTED, "newton_failures": N_NEWTON_FAILURES,
                  "newton_iterations": N_NEWTON_ITERATIONS, "factorizations": N_FACTORIZATIONS,
                  "residual_evaluations": N_RESIDUALS, "min_step_accepts": N_MIN_STEP_ACCEPTS}


class LoopSettings(NamedTuple):
    """`HHTSettings` as plain numbers for the compiled loop (`loop_settings`)."""

    alpha: float
    beta: float
    gamma: float
    rtol: float
    atol: float
    newton_tol: float
    residual_tol: float
    refactor_rate: float
    refactor_step_ratio: float
    safety: float
    min_factor: float
    max_factor: float
    min_step: float
    max_step: float
    newton_failure_factor: float
    t0: float
    t1: float
    n_fixed: int
    adaptive: bool
    use_max: bool
    estimate_test: bool
    linear_predictor: bool
    full_newton: bool
    keep_across_steps: bool
    max_newton_iter: int


def loop_settings(s: HHTSettings, t0: float, t1: float) -> LoopSettings:
    n_fixed = 0 if s.adaptive else max(1, int(round((t1 - t0) / s.first_step)))
    return LoopSettings(
        alpha=s.alpha, beta=s.beta, gamma=s.gamma, rtol=s.rtol, atol=s.atol, newton_tol=s.newton_tol,
        residual_tol=s.residual_tol, refactor_rate=s.refactor_rate, refactor_step_ratio=s.refactor_step_ratio,
        safety=s.safety, min_factor=s.min_factor, max_factor=s.max_factor, min_step=s.min_step,
        max_step=s.max_step, newton_failure_factor=s.newton_failure_factor, t0=float(t0), t1=float(t1),
        n_fixed=n_fixed, adaptive=bool(s.adaptive), use_max=s.error_norm == "max",
        estimate_test=s.newton_test == "estimate", linear_predictor=s.predictor == "linear",
        full_newton=s.reuse_jacobian is JacobianReuse.NEWTON,
        keep_across_steps=s.reuse_jacobian is JacobianReuse.ADAPTIVE, max_newton_iter=int(s.max_newton_iter))


class Coordinates(NamedTuple):
    """What the loop needs of the problem's coordinates: the diagonal mass, the rows replaced
    by a prescribed velocity, CRV slots, error weights, and scales (`step_control`)."""

    mass: np.ndarray
    prescribed_rows: np.ndarray
    rotation_slots: np.ndarray
    weights: np.ndarray
    scales: np.ndarray


class Factors(NamedTuple):
    """The factored iteration matrix (`linear_solvers.block_arrow_factor`)."""

    LU_D: np.ndarray
    piv_D: np.ndarray
    Dinv_T: np.ndarray
    F_T: np.ndarray
    DinvE_T: np.ndarray
    schur: np.ndarray
    piv_S: np.ndarray


class Work(NamedTuple):
    """State carried between chunks and scratch. Y[c] = (q, v, a, g, dq) of the current state
    (c = counters[N_CUR]) and of the attempted step (1 - c)."""

    Y: np.ndarray
    ma: np.ndarray
    r: np.ndarray
    da: np.ndarray
    zeros: np.ndarray
    da_prev: np.ndarray
    ma_t: np.ndarray
    g_t: np.ndarray
    diag: np.ndarray
    K: Blocks
    C: Blocks
    S: Blocks
    factors: Factors
    state: np.ndarray
    counters: np.ndarray


class Output(NamedTuple):
    """Where a chunk writes: Hermite samples, step-end records and the step log (any may
    have zero rows)."""

    samples: Samples
    record_t: np.ndarray
    record_q: np.ndarray
    record_v: np.ndarray
    record_diag: np.ndarray
    record_dt: float
    log: np.ndarray
    log_every: int


class KernelFunction(nbtypes.WrapperAddressProtocol):
    """One compiled overload of a kernel as a numba first-class function value: the overload of
    `dispatcher` for the types of `args` (compiled if needed), returning `returns`, called through
    the C entry numba compiles beside it (so the dispatcher keeps it: `compile_policy.FIRST_CLASS`).
    Without `compile` only its type is known (address 0), which is all that compiling a loop
    that takes it needs (`compile_loop`)."""

    def __init__(self, dispatcher, args, compile: bool = True, returns=nbtypes.float64) -> None:
        argtypes = tuple(numba.typeof(x) for x in args)
        self._signature = returns(*argtypes)
        self._address = 0
        if not compile:
            return
        dispatcher.compile(argtypes)
        cres = dispatcher.overloads[argtypes]
        if cres.signature.return_type != returns:
            raise TypeError(f"{dispatcher.__name__} returns {cres.signature.return_type}; the compiled loop "
                            f"calls it as a function returning {returns}")
        self._address = cres.library.get_pointer_to_function(cres.fndesc.llvm_cfunc_wrapper_name)
        if not self._address:
            raise TypeError(f"{dispatcher.__name__} has no C entry: compile it with compile_policy.FIRST_CLASS")

    def __wrapper_address__(self) -> int:
        return self._address

    def signature(self):
        return self._signature


# The threads inside `kernel_errors` blocks, each with the list its kernels' exceptions go to.
# numba's C entry reports an exception in the thread that called the kernel, so the reports
# are routed by thread: two runs in threads of one process (a threaded Dask worker) never see
# each other's, and outside any block they go to the hook that was there before.
_collecting: dict[int, list] = {}
_collecting_lock = threading.Lock()
_hook_outside: list = []


def _route_unraisable(unraisable) -> None:
    caught = _collecting.get(threading.get_ident())
    if caught is not None:
        caught.append(unraisable)
    else:
        (_hook_outside[0] if _hook_outside else sys.__unraisablehook__)(unraisable)


@contextlib.contextmanager
def kernel_errors():
    """Collect the exceptions a kernel raised under a first-class call in this thread: numba's C
    entry reports each through `sys.unraisablehook` and returns 0.0 to the loop, which runs on to
    the end of its chunk; the caller raises after the chunk (`integrate_compiled`). The hook is
    in place only while a block is open in some thread, then restored."""
    caught: list = []
    me = threading.get_ident()
    with _collecting_lock:
        if not _collecting:
            _hook_outside[:] = [sys.unraisablehook]
            sys.unraisablehook = _route_unraisable
        outer = _collecting.get(me)  # a block opened inside another in the same thread
        _collecting[me] = caught
    try:
        yield caught
    finally:
        with _collecting_lock:
            if outer is None:
                del _collecting[me]
            else:
                _collecting[me] = outer
            if not _collecting:
                sys.unraisablehook = _hook_outside.pop()


class CompiledProblem(NamedTuple):
    """A problem's compiled side for `hht_chunk`: `kernel` its compiled force kernel and
    `accepted` its accepted-step hook (`KernelFunction`s; the module docstring); data and hook
    the bundles they take; diag, K and C the buffers its kernel fills; `drain()` empties what
    the hook collected (called after every chunk)."""

    kernel: KernelFunction
    accepted: KernelFunction
    data: tuple
    hook: tuple
    mass: np.ndarray
    prescribed_rows: np.ndarray
    diag: np.ndarray
    K: Blocks
    C: Blocks
    drain: Callable[[], None]


@numba.njit(**KERNEL, **INTERNAL)
def _norm(ls, co, x, y, coef, q_a, q_b):
    """The step controller's scaled norm of x - y with the loop's settings and coordinates
    (`step_control.scaled_difference_norm`), for the three places in the loop that take it."""
    return scaled_difference_norm(x, y, coef, q_a, q_b, co.weights, co.scales, ls.atol, ls.rtol, ls.use_max)


# The loop's helpers below are inlined into `hht_chunk` in numba's IR (inline="always"). As
# functions of their own, numba compiled each into a library with its callees linked in, and
# LLVM optimised and emitted that code again at every level of the chain hht_chunk ->
# _attempt -> _newton -> _factor; inlined, the loop compiles in about two thirds of the time
# (`python -m benchmarks.cold_start`, docs/performance.md). The steps taken are the same.
@numba.njit(inline="always")
def _factor(kernel, data, ls, co, w, t1, q, v, a, h):
    """Rebuild S = M + (1 - alpha)(gamma h C_t + beta h^2 K_t) at (t1, q, v, a) and factor it."""
    # bool(True), not True: numba types a constant as a literal type of its own, which is not the
    # argument type of the kernel's function value (`KernelFunction`)
    kernel(t1, q, v, a, data, bool(True), w.ma_t, w.g_t, w.diag, w.K, w.C)
    c_v = (1.0 - ls.alpha) * ls.gamma * h
    assemble_iteration_blocks(w.K, w.C, co.mass, 1.0, c_v, (1.0 - ls.alpha) * ls.beta * h * h, w.S)
    for i in co.prescribed_rows:
        prescribe_velocity_blocks(w.S, i, 1.0, c_v, 1.0)
    w.counters[N_FACTORIZATIONS] += 1
    f = w.factors
    ok = block_arrow_factor(w.S.D, w.S.E, w.S.F, w.S.B, f.LU_D, f.piv_D, f.Dinv_T, f.F_T, f.DinvE_T, f.schur, f.piv_S)
    w.state[S_H_FACTORED] = h if ok else 0.0
    w.state[S_STALE] = 0.0 if ok else 1.0
    return ok


@numba.njit(inline="always")
def _newton(kernel, data, ls, co, w, t1, h, y, y1, fresh):
    """Newton on a_{n+1} (as `HHTStepper._newton`); returns _OK or a failure index."""
    q, v, a, g = y[0], y[1], y[2], y[3]
    q1, v1, a1, g1, dq1 = y1[0], y1[1], y1[2], y1[3], y1[4]
    f = w.factors
    rebuild = False
    corr_prev = math.inf
    floor = NEWTON_FLOOR * _norm(ls, co, q, w.zeros, MACHINE_EPSILON, q, q)
    for k in range(ls.max_newton_iter):
        newmark_kinematics(q, v, a, a1, h, ls.beta, ls.gamma, co.rotation_slots, dq1, q1, v1)
        kernel(t1, q1, v1, a1, data, bool(False), w.ma, g1, w.diag, w.K, w.C)
        w.counters[N_RESIDUALS] += 1
        r_max = hht_residual(w.ma, g1, g, ls.alpha, w.r)
        if r_max == math.inf:
            return _NAN
        if k > 0 and r_max <= ls.residual_tol:
            return _OK
        if rebuild:
            if not _factor(kernel, data, ls, co, w, t1, q1, v1, a1, h):
                return _SINGULAR
            fresh, rebuild = True, False
        block_arrow_solve(f.Dinv_T, f.F_T, f.DinvE_T, f.schur, f.piv_S, w.r, w.da)
        subtract_inplace(a1, w.da)
        w.counters[N_NEWTON_ITERATIONS] += 1
        corr = _norm(ls, co, w.da, w.zeros, ls.beta * h * h, q, q1)
        verdict, eta, rebuild = newton_verdict(k, corr, corr_prev, w.state[S_ETA], ls.estimate_test, ls.newton_tol,
                                               floor, fresh, ls.full_newton, ls.refactor_rate)
        w.state[S_ETA] = eta
        if verdict == NEWTON_CONVERGED:
            newmark_kinematics(q, v, a, a1, h, ls.beta, ls.gamma, co.rotation_slots, dq1, q1, v1)
            return _OK
        if verdict == NEWTON_DIVERGED:
            return _DIVERGED
        corr_prev = corr
    return _MAX_ITER


@numba.njit(inline="always")
def _attempt(kernel, data, ls, co, w, t, h, y, y1):
    """One attempted step (as `HHTStepper.step`): (error norm, _OK or a failure index)."""
    t1 = t + h
    h_prev = w.state[S_H_PREV]
    predict_acceleration(y[2], w.da_prev, h / h_prev if h_prev > 0.0 else 0.0, ls.linear_predictor, y1[2])
    fresh = False
    if needs_refactor(w.state[S_STALE] > 0.0, w.state[S_H_FACTORED], h, ls.keep_across_steps,
                      ls.refactor_step_ratio):
        newmark_kinematics(y[0], y[1], y[2], y1[2], h, ls.beta, ls.gamma, co.rotation_slots, y1[4], y1[0], y1[1])
        if not _factor(kernel, data, ls, co, w, t1, y1[0], y1[1], y1[2], h):
            return math.inf, _SINGULAR
        fresh = True
    result = _newton(kernel, data, ls, co, w, t1, h, y, y1, fresh)
    if result != _OK:
        w.state[S_STALE] = 1.0
        return math.inf, result
    return _norm(ls, co, y1[2], y[2], (ls.beta - 1.0 / 6.0) * h * h, y[0], y1[0]), _OK


@numba.njit(inline="always")
def _hermite_samples(w, out, t_n, h, y, y1, co):
    """Hermite samples in (t_n, t_n + h] of an accepted step (y -> y1)."""
    c = w.counters
    smp = out.samples
    if c[N_SAMPLES] < smp.times.shape[0] and smp.times[c[N_SAMPLES]] <= t_n + h * (1.0 + 1e-12):
        c[N_SAMPLES] = hermite_fill(t_n, h, StepEnds(y[0], y[1], y[2], y1[1], y1[2], y1[4]), co.rotation_slots,
                                    smp, c[N_SAMPLES])


@numba.njit(inline="always")
def _record(ls, w, out, t, y):
    """Step-end record (t, q, v, diag) and step log after an accepted step ending at t."""
    c = w.counters
    i = c[N_RECORDS]
    if i < out.record_t.shape[0] and t >= w.state[S_NEXT_RECORD] - 1e-15:
        out.record_t[i] = t
        for j in range(y.shape[1]):  # element-wise: a row copy may allocate, and the loop may run without NRT
            out.record_q[i, j] = y[0, j]
            out.record_v[i, j] = y[1, j]
        for j in range(w.diag.shape[0]):
            out.record_diag[i, j] = w.diag[j]
        c[N_RECORDS] = i + 1
        w.state[S_NEXT_RECORD] = ls.t0 + (i + 1) * out.record_dt
    if out.log.shape[0] > 0 and c[N_STEPS] % out.log_every == 0:
        j = c[N_LOGGED]
        if j < out.log.shape[0]:
            out.log[j, 0] = t
            out.log[j, 1] = t - w.state[S_T_LOGGED]
            out.log[j, 2] = c[N_RESIDUALS]
            out.log[j, 3] = c[N_FACTORIZATIONS]
            c[N_LOGGED] = j + 1
    w.state[S_T_LOGGED] = t


@numba.njit(**NO_REFCOUNT)
def hht_chunk(kernel, accepted, data, hook, ls, co, w, out, max_steps):
    """Up to `max_steps` accepted HHT-α steps (the control flow of `time_loop.integrate`).

    Returns DONE at t1, CHUNK_END after max_steps or when the hook asks for a drain, or
    FAILED + index into FAILURES (state[S_T_FAIL], state[S_H_FAIL] say where) when Newton
    fails at the minimum (or the fixed) step."""
    st, c = w.state, w.counters
    t, h = st[S_T], st[S_H]
    taken = 0
    while t < ls.t1 and (ls.adaptive or c[N_STEPS] < ls.n_fixed):
        if taken >= max_steps:
            break
        if ls.adaptive:
            if t + LAST_STEP_STRETCH * h >= ls.t1:  # land on t1 without leaving a sliver of a step
                h = ls.t1 - t
        else:
            h = (ls.t1 - ls.t0) / ls.n_fixed
        cur = c[N_CUR]
        y, y1 = w.Y[cur], w.Y[1 - cur]
        err, result = _attempt(kernel, data, ls, co, w, t, h, y, y1)
        if result != _OK:
            c[N_REJECTED] += 1
            c[N_NEWTON_FAILURES] += 1
            if not ls.adaptive or h <= ls.min_step * AT_MIN_STEP:
                st[S_T_FAIL], st[S_H_FAIL] = t, h
                st[S_T], st[S_H] = t, h
                return FAILED + result
            h = max(h * ls.newton_failure_factor, ls.min_step)
            continue
        if ls.adaptive and err > 1.0:
            if h > ls.min_step * AT_MIN_STEP:
                c[N_REJECTED] += 1
                h = proposed_step(h, err, ls.safety, ls.min_factor, ls.max_factor, ls.min_step, ls.max_step)
                continue
            c[N_MIN_STEP_ACCEPTS] += 1
        _hermite_samples(w, out, t, h, y, y1, co)
        t = ls.t0 + (c[N_STEPS] + 1) * h if not ls.adaptive else t + h
        for i in range(w.da_prev.shape[0]):
            w.da_prev[i] = y1[2, i] - y[2, i]
        st[S_H_PREV] = h
        c[N_CUR] = 1 - cur
        c[N_STEPS] += 1
        taken += 1
        drain = accepted(t, y1[0], y1[1], y1[2], data, w.diag, hook)
        _record(ls, w, out, t, y1)
        if ls.adaptive:
            h = proposed_step(h, err, ls.safety, ls.min_factor, ls.max_factor, ls.min_step, ls.max_step)
        if drain:
            break
    st[S_T], st[S_H] = t, h
    return CHUNK_END if t < ls.t1 and (ls.adaptive or c[N_STEPS] < ls.n_fixed) else DONE


def new_work(n: int, diag: np.ndarray, K: Blocks, C: Blocks) -> Work:
    """Zeroed state and scratch for a problem of n unknowns whose kernel fills diag, K and C."""
    Z, m, nb = K.E.shape
    S = BlockArrowMatrix.zeros(Z, m, nb).blocks()
    factors = Factors(LU_D=np.zeros((Z, m, m)), piv_D=np.zeros((Z, m), dtype=np.int64), Dinv_T=np.zeros((Z, m, m)),
                      F_T=np.zeros((Z, m, nb)), DinvE_T=np.zeros((Z, nb, m)), schur=np.zeros((nb, nb)),
                      piv_S=np.zeros(nb, dtype=np.int64))
    return Work(Y=np.zeros((2, 5, n)), ma=np.zeros(n), r=np.zeros(n), da=np.zeros(n), zeros=np.zeros(n),
                da_prev=np.zeros(n), ma_t=np.zeros(n), g_t=np.zeros(n), diag=diag, K=K, C=C, S=S, factors=factors,
                state=np.zeros(10), counters=np.zeros(11, dtype=np.int64))


def _samples(sampler, n: int) -> Samples:
    if sampler is not None:
        return sampler.buffers
    e1 = np.zeros(0, dtype=np.int64)
    return Samples(np.zeros(0), e1, e1, e1, np.zeros((0, 0)), np.zeros((0, 0)), np.zeros((0, 0)),
                   np.zeros(n), np.zeros(n))


class Records(NamedTuple):
    """Step-end records (t, q, v, diag at the first accepted step at or after each multiple
    of record_dt, the first at t0) and the step log (t, h, residual evaluations and
    factorisations so far), trimmed to what was written."""

    t: np.ndarray
    q: np.ndarray
    v: np.ndarray
    diag: np.ndarray
    log: np.ndarray


@dataclass
class RunTrace:
    """What a run has done so far, kept for a caller that stops it (`on_chunk` raises) or sees
    it fail: the solver counters, filled after every chunk, and the step log, one (k, 4)
    array a chunk (t, h, residual evaluations and factorisations so far)."""

    stats: SolverStats = field(default_factory=SolverStats)
    log: list = field(default_factory=list)


# a raising kernel is a defect, not a numerical difficulty that a setting avoids
_KERNEL_ERROR_HINT = ("report it with the scene; `time_loop.integrate`, the Python loop, runs the same problem and "
                      "raises the kernel's exception where it happens")


def integrate_compiled(problem, t0: float, t1: float, q0, v0, settings: HHTSettings | None = None, *,
                       sampler=None, record_dt: float = 0.0, log_every: int = 0,
                       on_chunk: Callable[[float, float], None] | None = None,
                       chunk_steps: int = 1000, trace: RunTrace | None = None) -> tuple[Solution, Records]:
    """`time_loop.integrate` for a problem with a compiled side (`problem.compiled()` ->
    `CompiledProblem`): the same steps, run in numba chunks of `chunk_steps` accepted steps.

    sampler: a `FixedIntervalSampler` (Hermite samples). record_dt > 0 [s]: keep step-end
    records (`Records`). log_every > 0: log every log_every-th step. on_chunk(t, h) is called
    after every chunk (progress, wall-clock budgets; it may raise to stop the run). Raises
    IntegrationError as `integrate` does. `trace` (filled in place) keeps what a stopped run
    did.
    """
    from .time_loop import initial_acceleration

    settings = settings or HHTSettings()
    check_problem(problem)
    cp = problem.compiled()
    trace = trace if trace is not None else RunTrace()
    stats = trace.stats
    wall0 = time.perf_counter()
    solver = BlockArrowSolver(*cp.K.E.shape)
    scales = checked_error_scales(problem, t0, q0, v0) if hasattr(problem, "error_scales") else np.zeros(0)
    a0, g0 = initial_acceleration(problem, solver, t0, np.asarray(q0, dtype=float), np.asarray(v0, dtype=float))
    logged = trace.log
    w, out, co, ls = _loop_arguments(problem, cp, settings, (t0, t1), (q0, v0, a0, g0, scales), sampler,
                                     record_dt, log_every, chunk_steps)
    stall = NewtonStallWatch(settings.alpha, settings.max_newton_iter)
    while True:
        t_chunk = w.state[S_T]
        with kernel_errors() as raised:
            status = hht_chunk(cp.kernel, cp.accepted, cp.data, cp.hook, ls, co, w, out, chunk_steps)
        if raised:
            error = raised[0]
            raise IntegrationError(t_chunk, w.state[S_H], f"a kernel raised {error.exc_type.__name__}: "
                                   f"{error.exc_value} in the chunk from this time on", _KERNEL_ERROR_HINT) \
                from error.exc_value
        cp.drain()
        logged.append(out.log[:int(w.counters[N_LOGGED])].copy())
        w.counters[N_LOGGED] = 0
        _finish(stats, w, wall0)
        if sampler is not None:
            sampler.count = int(w.counters[N_SAMPLES])
        if status >= FAILED:
            result = FAILURES[status - FAILED]
            where = "at the minimum step" if settings.adaptive else "at the fixed step"
            raise IntegrationError(w.state[S_T_FAIL], w.state[S_H_FAIL], f"{result.value} {where}",
                                   damping_first(result.hint, settings.alpha))
        stall.check(w.state[S_T], w.state[S_H], stats.steps, stats.newton_failures)
        if on_chunk is not None:
            on_chunk(w.state[S_T], w.state[S_H])
        if status == DONE:
            break
    _finish(stats, w, wall0)
    c = int(w.counters[N_CUR])
    h = w.state[S_H]
    sol = Solution(t=float(w.state[S_T]), q=w.Y[c, 0].copy(), v=w.Y[c, 1].copy(), a=w.Y[c, 2].copy(),
                   h_next=h if math.isfinite(h) else settings.first_step, stats=stats)
    k = int(w.counters[N_RECORDS])
    return sol, Records(out.record_t[:k], out.record_q[:k], out.record_v[:k], out.record_diag[:k],
                        np.concatenate(logged) if logged else np.zeros((0, 4)))


def _loop_arguments(problem, cp: CompiledProblem, settings: HHTSettings, span, start, sampler, record_dt: float,
                    log_every: int, chunk_steps: int) -> tuple:
    """(work, output, coordinates, loop settings) of the chunk for a run over span = (t0, t1) from
    start = (q0, v0, a0, g0, error scales) (`integrate_compiled`'s arguments otherwise)."""
    t0, t1 = span
    q0, v0, a0, g0, scales = start
    n = problem.n_dof
    w = new_work(n, cp.diag, cp.K, cp.C)
    w.Y[0, 0], w.Y[0, 1], w.Y[0, 2], w.Y[0, 3] = q0, v0, a0, g0
    w.state[S_T], w.state[S_H], w.state[S_ETA], w.state[S_STALE] = t0, settings.first_step, 1.0, 1.0
    w.state[S_T_LOGGED] = t0
    w.counters[N_FACTORIZATIONS] = w.counters[N_RESIDUALS] = 1  # the initial acceleration's
    n_rec = int(math.floor((t1 - t0) / record_dt + 1e-9)) + 2 if record_dt > 0.0 else 0
    n_log = chunk_steps // log_every + 2 if log_every > 0 else 0  # per chunk, drained after each
    # the records are hundreds of MB for a long run: in ordinary pages (buffers.py)
    out = Output(_samples(sampler, n), zeroed(n_rec), zeroed((n_rec, n)), zeroed((n_rec, n)),
                 zeroed((n_rec, cp.diag.size)), record_dt if record_dt > 0.0 else 1.0,
                 np.zeros((n_log, 4)), max(log_every, 1))
    if n_rec:
        out.record_t[0], out.record_q[0], out.record_v[0], out.record_diag[0] = t0, q0, v0, cp.diag
        w.counters[N_RECORDS] = 1
        w.state[S_NEXT_RECORD] = t0 + record_dt
    if sampler is not None:
        sampler.start(t0, w.Y[0, 0], w.Y[0, 1], w.Y[0, 2])
        w.counters[N_SAMPLES] = sampler.count
    co = Coordinates(cp.mass, cp.prescribed_rows, np.ascontiguousarray(problem.rotation_slots, dtype=np.int64),
                     np.ascontiguousarray(problem.error_weights, dtype=float), np.ascontiguousarray(scales))
    return w, out, co, loop_settings(settings, t0, t1)


def compile_loop(problem, settings: HHTSettings | None = None, chunk_steps: int = 1000) -> None:
    """Compile (or load from numba's cache) the time loop of `problem` for the argument types
    `integrate_compiled` passes it, without compiling its force kernel
    (`problem.compiled(compile_kernel=False)`): the two are separate libraries (the kernel is a
    first-class function value, `KernelFunction`), so a second process can compile the kernel
    meanwhile."""
    settings = settings or HHTSettings()
    cp = problem.compiled(compile_kernel=False)
    z = np.zeros(problem.n_dof)
    w, out, co, ls = _loop_arguments(problem, cp, settings, (0.0, settings.first_step), (z, z, z, z, np.zeros(0)),
                                     None, 0.0, 0, chunk_steps)
    args = (cp.kernel, cp.accepted, cp.data, cp.hook, ls, co, w, out, chunk_steps)
    hht_chunk.compile(tuple(numba.typeof(x) for x in args))


def _finish(stats: SolverStats, w: Work, wall0: float) -> None:
    for name, i in STATS_COUNTERS.items():
        setattr(stats, name, int(w.counters[i]))
    stats.wall_time = time.perf_counter() - wall0
