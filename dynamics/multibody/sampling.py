"""Fixed-interval output of the state into preallocated arrays.

Between two accepted steps the state is interpolated (dense output):

* q: cubic Hermite in the increment space, p(0) = 0, p'(0) = v_n, p(h) = dq, p'(h) = v_{n+1},
  then q(s) = q_n (+) p(s) (multiplicative on CRV triples). Exact at step ends; the
  interpolation error is O(h^3) locally (the Hermite cubic would be O(h^4), but v_{n+1} at
  the end of a CRV triple is material at q_{n+1}, not at q_n: an O(h |Omega|) frame lag
  times h), below the O(h^2) global error of HHT-α.
* v: cubic Hermite with end slopes a_n, a_{n+1}; a: linear.

Sample times are t0 + k dt, k = 0..N; the caller chooses which coordinates to keep.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numba
import numpy as np

from .._speed.compile_policy import KERNEL

from .crv import update_configuration


class StepEnds(NamedTuple):
    """An accepted step from t_n to t_n + h: state at its start (q_n, v_n, a_n), velocity and
    acceleration at its end (v1, a1) and its increment dq (q_{n+1} = q_n (+) dq)."""

    q_n: np.ndarray
    v_n: np.ndarray
    a_n: np.ndarray
    v1: np.ndarray
    a1: np.ndarray
    dq: np.ndarray


class Samples(NamedTuple):
    """Sample times, the coordinates kept (q_idx, v_idx, a_idx), the output rows (out_q,
    out_v, out_a; one row per time) and two n_dof work vectors."""

    times: np.ndarray
    q_idx: np.ndarray
    v_idx: np.ndarray
    a_idx: np.ndarray
    out_q: np.ndarray
    out_v: np.ndarray
    out_a: np.ndarray
    p_work: np.ndarray
    q_work: np.ndarray


@numba.njit(**KERNEL)
def hermite_fill(t_n, h, step, rotation_slots, samples, k):
    """Fill samples k, k+1, ... with t_n < times[k] <= t_n + h from the `StepEnds` of one
    step (module docstring); returns the next k."""
    q_n, v_n, a_n, v1, a1 = step.q_n, step.v_n, step.a_n, step.v1, step.a1
    times, p_work, q_work = samples.times, samples.p_work, samples.q_work
    t_end = t_n + h
    while k < times.shape[0] and times[k] <= t_end * (1.0 + 1e-15) + 1e-300:
        th = (times[k] - t_n) / h
        th2 = th * th
        th3 = th2 * th
        h01 = -2.0 * th3 + 3.0 * th2
        h10 = th3 - 2.0 * th2 + th
        h11 = th3 - th2
        h00 = 1.0 - h01
        for i in range(q_n.shape[0]):
            p_work[i] = h10 * h * v_n[i] + h01 * step.dq[i] + h11 * h * v1[i]
        update_configuration(q_n, p_work, rotation_slots, q_work)
        for j in range(samples.q_idx.shape[0]):
            samples.out_q[k, j] = q_work[samples.q_idx[j]]
        for j in range(samples.v_idx.shape[0]):
            i = samples.v_idx[j]
            samples.out_v[k, j] = h00 * v_n[i] + h10 * h * a_n[i] + (1.0 - h00) * v1[i] + h11 * h * a1[i]
        for j in range(samples.a_idx.shape[0]):
            i = samples.a_idx[j]
            samples.out_a[k, j] = (1.0 - th) * a_n[i] + th * a1[i]
        k += 1
    return k


class FixedIntervalSampler:
    """Samples at t0 + k dt into arrays `t`, `q`, `v`, `a` (rows = samples).

    q_indices / v_indices / a_indices select the coordinates to keep (default: all q and v,
    no a). `count` is the number of samples filled so far.
    """

    def __init__(self, t0: float, t1: float, dt: float, n_dof: int, q_indices=None,
                 v_indices=None, a_indices=()) -> None:
        if not dt > 0.0 or not t1 >= t0:
            raise ValueError(f"sampling needs dt > 0 s and t1 >= t0; got dt = {dt}, "
                             f"[t0, t1] = [{t0}, {t1}]")
        n_samples = int(math.floor((t1 - t0) / dt * (1.0 + 1e-12))) + 1
        self.t = t0 + dt * np.arange(n_samples)
        every = np.arange(n_dof)
        self.q_indices = np.ascontiguousarray(every if q_indices is None else q_indices,
                                              dtype=np.int64)
        self.v_indices = np.ascontiguousarray(every if v_indices is None else v_indices,
                                              dtype=np.int64)
        self.a_indices = np.ascontiguousarray(a_indices, dtype=np.int64)
        self.q = np.full((n_samples, self.q_indices.size), np.nan)
        self.v = np.full((n_samples, self.v_indices.size), np.nan)
        self.a = np.full((n_samples, self.a_indices.size), np.nan)
        self.count = 0
        self._samples = Samples(self.t, self.q_indices, self.v_indices, self.a_indices, self.q, self.v,
                                self.a, np.zeros(n_dof), np.zeros(n_dof))

    @property
    def buffers(self) -> Samples:
        """The output arrays and work vectors as one bundle, for `hermite_fill` in a compiled loop."""
        return self._samples

    def start(self, t0: float, q0, v0, a0) -> None:
        """Record the initial state when the first sample time is t0."""
        if self.count == 0 and self.t.size and abs(self.t[0] - t0) <= 1e-15 * max(1.0, abs(t0)):
            self.q[0] = q0[self.q_indices]
            self.v[0] = v0[self.v_indices]
            self.a[0] = a0[self.a_indices]
            self.count = 1

    def observe(self, t_n: float, h: float, y_n, y_1, rotation_slots) -> None:
        """Interpolate the samples in (t_n, t_n + h] of an accepted step."""
        if self.count >= self.t.size or self.t[self.count] > t_n + h * (1.0 + 1e-12):
            return
        step = StepEnds(y_n.q, y_n.v, y_n.a, y_1.v, y_1.a, y_1.dq)
        self.count = hermite_fill(t_n, h, step, rotation_slots, self._samples, self.count)
