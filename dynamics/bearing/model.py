"""`BearingModel`: the ball bearing as a `dynamics.multibody` residual problem.

Implements the protocol of dynamics/multibody/problem.py: `evaluate` and `jacobian` call
the force kernel (assembly.evaluate_bearing, which calls assembly.bearing_tangents for the
tangents); `on_accepted_step` logs ball–pocket impacts
and integrates the energy balance from the diagnostics of the converged state.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numba
import numpy as np

from .._speed.compile_policy import FIRST_CLASS, INTERNAL, KERNEL
from ..contact.pocket import N_POCKET_OUT
from ..journal.short_bearing import N_JOURNAL_OUT
from ..journal.squeeze_film import N_SQUEEZE_OUT
from ..multibody.compiled import CompiledProblem, KernelFunction
from ..multibody.joints import prescribe_velocity_blocks
from ..multibody.linear_solvers import BlockArrowMatrix, assemble_iteration_blocks

from . import channels, layout
from .assembly import bearing_tangents, evaluate_bearing, mass_diagonal
from .params import IP_CAGE, IP_Z
from .bundles import BearingData, Body, BorderLoads, CageArrays, ModelArrays, ResidualWork
from .race_forces import N_RC, contact_scratch
from .channels import (
    DB, DB_POCKET, DB_POCKET_APPROACH, DB_POCKET_IN_CONTACT, DB_POCKET_ORBITAL, DG_P_DISS, DG_P_DRIVE,
    DG_P_EXT, N_DG, diag_size,
)
from .params import BearingModelParams

IMPACT_FIELDS = ("time", "ball", "orbital_position", "peak_force", "impact_speed", "duration")


@numba.njit(**KERNEL)
def track_impacts(t, diag, Z, state, events, impact_speeds):
    """Update per-pocket impact state from the accepted step's diagnostics (docs/model.md §7).

    Also keeps v_0 of the hysteresis law (`impact_speeds`, Z): while a pocket is open its
    approach speed is remembered, so the speed it hits with is known when contact starts.

    state (Z, 6): in contact, peak force, time of peak, orbital position at peak, impact
    speed (approach speed when contact began), start time. A finished contact becomes a row
    of `events` (IMPACT_FIELDS); returns the number of rows written.
    """
    n = 0
    for k in range(Z):
        d = N_DG + DB * k
        force, touching = diag[d + DB_POCKET], diag[d + DB_POCKET_IN_CONTACT]
        approach, orbital = diag[d + DB_POCKET_APPROACH], diag[d + DB_POCKET_ORBITAL]
        if touching <= 0.0:
            impact_speeds[k] = max(approach, 0.0)
        if touching > 0.0:
            if state[k, 0] == 0.0:
                state[k, 0], state[k, 1], state[k, 4], state[k, 5] = 1.0, 0.0, max(approach, 0.0), t
            if force > state[k, 1]:
                state[k, 1], state[k, 2], state[k, 3] = force, t, orbital
        elif state[k, 0] > 0.0:
            events[n, 0], events[n, 1], events[n, 2] = state[k, 2], k, state[k, 3]
            events[n, 3], events[n, 4], events[n, 5] = state[k, 1], state[k, 4], t - state[k, 5]
            n += 1
            state[k, 0] = 0.0
    return n


class AcceptedStepLog(NamedTuple):
    """What `accepted_step` keeps between steps: per-pocket impact state (Z, 6) and the rows
    `track_impacts` finished in one step (Z, 6); the impact log `events` (rows IMPACT_FIELDS)
    with its fill count[0]; the energies [J] (drive, external, dissipated) and the powers of
    the previous accepted step (t, P_drive, P_ext, P_diss, 1 once set); threshold[0] [N]."""

    impact_state: np.ndarray
    step_events: np.ndarray
    events: np.ndarray
    count: np.ndarray
    energy: np.ndarray
    last: np.ndarray
    threshold: np.ndarray


@numba.njit(**FIRST_CLASS, **INTERNAL)  # called only by the compiled loop, as a function value
def accepted_step(t, q, v, a, data, diag, log):
    """Impact log and energy balance from the accepted step's diagnostics (docs/model.md §7,
    §10); returns True when the impact log is nearly full (empty it: `BearingModel.drain`).
    data: `bundles.BearingData`."""
    model = data.arrays
    return log_step(t, diag, model.ip[IP_Z], model.ip[IP_CAGE] != 0, model.cage.impact_speeds, log)


@numba.njit(**KERNEL)
def log_step(t, diag, Z, has_cage, impact_speeds, log):
    """`accepted_step` on the few arrays it reads (a cheaper call from Python)."""
    if has_cage:
        n = track_impacts(t, diag, Z, log.impact_state, log.step_events, impact_speeds)
        for i in range(n):
            if log.step_events[i, 3] >= log.threshold[0]:
                for j in range(log.events.shape[1]):  # element-wise: a row copy may allocate (no NRT here)
                    log.events[log.count[0], j] = log.step_events[i, j]
                log.count[0] += 1
    powers = (diag[DG_P_DRIVE], diag[DG_P_EXT], diag[DG_P_DISS])
    if log.last[4] > 0.0:
        dt = t - log.last[0]
        for i in range(3):
            log.energy[i] += 0.5 * dt * (powers[i] + log.last[1 + i])
    log.last[0] = t
    for i in range(3):
        log.last[1 + i] = powers[i]
    log.last[4] = 1.0
    return log.count[0] > log.events.shape[0] - Z


def cage_arrays(pocket, journal, psi, impact_speeds) -> CageArrays:
    """`bundles.CageArrays` with the cosines and sines of the pocket azimuths (math.cos and
    math.sin: the same libm the kernels would call, so the same bits)."""
    return CageArrays(pocket, journal, impact_speeds, np.array([math.cos(p) for p in psi]),
                      np.array([math.sin(p) for p in psi]))


def residual_work(Z: int) -> ResidualWork:
    """Fresh scratch of the residual kernel for a bearing of Z balls (`bundles.ResidualWork`)."""
    return ResidualWork(
        rows=np.zeros((2 * Z, N_RC)), pocket_rows=np.zeros((Z, N_POCKET_OUT)),
        scratch=contact_scratch(2 * Z),
        loads=BorderLoads(np.zeros(3), np.zeros(3), np.zeros(3), np.zeros(3)),
        outer=Body(np.zeros(3), np.eye(3), np.zeros(3), np.zeros(3)),
        R_inner=np.zeros((3, 3)), w_inner=np.zeros(3), R_cage=np.zeros((3, 3)), w_cage=np.zeros(3),
        ext_f=np.zeros(3), ext_m=np.zeros(3), moment_contact=np.zeros(3), moment_load=np.zeros(3),
        moment_cage=np.zeros(3),
        journal_row=np.zeros(N_JOURNAL_OUT), journal_squeeze=np.zeros(N_SQUEEZE_OUT), fixed_reaction=np.zeros((2, 3)))


class _Kernel:
    """The force kernel `evaluate_bearing` bound to one model's bundles.

    numba's per-call type dispatch types every array of every nested bundle in Python, more
    than a tenth of a residual; after the first call this
    calls the compiled overload directly (`Dispatcher.get_overload`), which unboxes the
    arguments without typing them. Its unboxing does not check an array's dtype or layout, so
    the state arrays, the only arguments that change between calls, are checked here
    (float64, 1-D, contiguous, of the model's length) and anything else goes through the
    dispatcher.
    """

    def __init__(self, n_dof: int):
        self.n = n_dof
        self.entry = None  # the compiled overload, once a call with state arrays that fit found it

    def _fits(self, x) -> bool:
        return (type(x) is np.ndarray and x.dtype == np.float64 and x.ndim == 1 and x.shape[0] == self.n
                and x.flags.c_contiguous)

    def __call__(self, t, q, v, a, data, want_tangent, ma, g, diag, K, C):
        args = (float(t), q, v, a, data, bool(want_tangent), ma, g, diag, K, C)
        fits = self._fits(q) and self._fits(v) and self._fits(a) and self._fits(ma) and self._fits(g)
        if self.entry is not None and fits:
            return self.entry(*args)
        drive = evaluate_bearing(*args)
        if self.entry is None and fits:
            self.entry = evaluate_bearing.get_overload(tuple(numba.typeof(x) for x in args))
        return drive


class BearingModel:
    """Races, Z balls and (optionally) the cage; see layout.py for the coordinates."""

    def __init__(self, params: BearingModelParams, impact_force_threshold: float = 0.0):
        P = self.params = params
        Z, has_cage = P.ball_count, P.has_cage
        self.n_dof = layout.n_dof(Z, has_cage)
        self.rotation_slots = layout.rotation_slots(Z, has_cage)
        self.nb = layout.border_size(has_cage)
        w = np.ones(self.n_dof)
        radius = 0.5 * P.pitch_diameter  # rotation errors read as arc lengths [m]
        layout.ball_states(w, Z)[:, 3:] = 0.0  # ball orientation never enters a force
        for s in self.rotation_slots:
            w[s:s + 3] = radius
        w[layout.spin_row(Z)] = 0.0
        self.error_weights = w
        self.mass = mass_diagonal(P.fp, P.ip, self.n_dof)
        self.K = BlockArrowMatrix.zeros(Z, layout.BALL_DOF, self.nb)
        self.C = BlockArrowMatrix.zeros(Z, layout.BALL_DOF, self.nb)
        self.S = BlockArrowMatrix.zeros(Z, layout.BALL_DOF, self.nb)
        self.diag = np.zeros(diag_size(Z))
        self._ma = np.zeros(self.n_dof)
        self._g = np.zeros(self.n_dof)
        self.impact_speeds = np.zeros(Z)
        self.arrays = ModelArrays(
            fp=P.fp, ip=P.ip, mass=self.mass, races=P.races, traction=P.traction, film=P.film,
            cage=cage_arrays(P.pocket, P.journal, P.pocket_psi, self.impact_speeds), hinge=P.hinge,
            work=residual_work(Z))
        self._blocks = (self.K.blocks(), self.C.blocks())
        self._data = None
        self._kernel_call = _Kernel(self.n_dof)
        self.impact_threshold = impact_force_threshold
        width = len(IMPACT_FIELDS)
        self.log = AcceptedStepLog(np.zeros((Z, 6)), np.zeros((Z, width)), np.zeros((64 * Z, width)),
                                   np.zeros(1, dtype=np.int64), np.zeros(3), np.zeros(5),
                                   np.array([float(impact_force_threshold)]))
        self.impacts: list[np.ndarray] = []

    # --- protocol --------------------------------------------------------------------
    def _kernel(self, t, q, v, a, ma, g, want_tangent):
        K, C = self._blocks
        return self._kernel_call(t, q, v, a, self.kernel_data(), want_tangent, ma, g, self.diag, K, C)

    def evaluate(self, t, q, v, a, ma_out, g_out) -> None:
        self._kernel(t, q, v, a, ma_out, g_out, False)

    def jacobian(self, t, q, v, a, c_m, c_v, c_q):
        self._kernel(t, q, v, a, self._ma, self._g, True)
        K, C = self._blocks
        S = self.S.blocks()
        assemble_iteration_blocks(K, C, self.mass, c_m, c_v, c_q, S)
        prescribe_velocity_blocks(S, layout.spin_row(self.params.ball_count), c_m, c_v, 1.0)
        return self.S

    def error_scales(self, t0, q0, v0) -> np.ndarray:
        """Physical scale L_i of each weighted coordinate for the step controller (M.99b) [m]:
        the displacement that changes the coordinate's elastic force by a mean ball-race load,
        Q_mean / K_ii, from the tangent stiffness at the initial state (rotations as arcs at the
        pitch radius, like their error weights). A coordinate that carries no elastic force there
        moves freely over its clearance, which is its scale: a ball or the cage along the orbit
        within the pocket clearance, the cage across within its guide clearance."""
        P, Z, n = self.params, self.params.ball_count, self.n_dof
        w = self.error_weights
        # the tangent's evaluation also leaves the start state's diagnostics (its loads) behind
        S = self.jacobian(t0, q0, v0, np.zeros(n), 0.0, 0.0, 1.0)
        loads = np.concatenate([self.channel("contacts/inner_load"), self.channel("contacts/outer_load")])
        q_mean = float(np.mean(loads))
        k_diag = np.concatenate([np.einsum("kii->ki", S.D).ravel(), np.diag(S.B)])
        free = np.full(n, 0.5 * P.ball_diameter)  # no cage: a ball's orbital position acts on nothing
        if P.has_cage:
            free[:] = P.pocket.pocket_radius - P.pocket.ball_radius
            c = layout.cage_offset(Z, True)
            free[c:c + 3] = P.guide_clearance
        k_weighted = k_diag / np.where(w > 0.0, w * w, 1.0)  # stiffness per unit of weighted error
        with np.errstate(divide="ignore", invalid="ignore"):
            elastic = np.where(k_weighted > 0.0, q_mean / k_weighted, np.inf)
        return np.minimum(elastic, free) if q_mean > 0.0 else free

    def on_accepted_step(self, t, q, v, a) -> None:
        """Impact log and energy balance from the converged state's diagnostics."""
        P = self.params
        log_step(t, self.diag, P.ball_count, P.has_cage, self.impact_speeds, self.log)
        self.drain()

    def drain(self) -> None:
        """Move the impacts `accepted_step` logged into `impacts`."""
        n = int(self.log.count[0])
        if n:
            self.impacts.extend(self.log.events[:n].copy())
            self.log.count[0] = 0

    @property
    def energy(self) -> dict:
        """Energy balance so far [J]: work of the drive and of the external loads, dissipated."""
        return dict(zip(("drive", "external", "dissipated"), map(float, self.log.energy)))

    def kernel_data(self, compile_tangents: bool = True) -> BearingData:
        """The force kernel's `bundles.BearingData`: the arrays and the tangent kernel
        (`assembly.bearing_tangents`) as a first-class function value, compiled (or loaded) once;
        without `compile_tangents` only typed, which is all that compiling a caller needs."""
        if self._data is not None:
            return self._data
        K, C = self._blocks
        n = np.zeros(self.n_dof)  # the tangent kernel's argument types, as the force kernel passes them
        tangents = KernelFunction(bearing_tangents, (n, n, self.arrays, K, C), compile=compile_tangents)
        data = BearingData(self.arrays, tangents)
        if compile_tangents:
            self._data = data
        return data

    def force_kernel(self, compile_force: bool = True, compile_tangents: bool = True) -> KernelFunction:
        """The force kernel (`assembly.evaluate_bearing`) as a first-class function value for the
        argument types the time loop passes it, compiled (or loaded) or only typed. Compiled
        without its tangent kernel, it is for compiling alone (another process may compile the
        tangent kernel meanwhile) and must not be called."""
        K, C = self._blocks
        n = np.zeros(self.n_dof)
        args = (0.0, n, n, n, self.kernel_data(compile_tangents), False, n, n, self.diag, K, C)
        return KernelFunction(evaluate_bearing, args, compile=compile_force)

    def compiled(self, compile_kernel: bool = True) -> CompiledProblem:
        """The compiled side for `multibody.compiled.integrate_compiled`; without `compile_kernel`
        the force and tangent kernels are not compiled, only typed
        (`multibody.compiled.compile_loop`). The accepted-step hook is compiled (or loaded) either
        way: it is small and goes with the loop, so the process that compiles the loop ahead of a
        machine's first run compiles it too (pipeline/cli/compile_ahead.py)."""
        rows = np.array([layout.spin_row(self.params.ball_count)], dtype=np.int64)
        K, C = self._blocks
        # one kernel for the tangent calls and Newton's residual-only calls (want_tangent at run time)
        kernel = self.force_kernel(compile_kernel, compile_kernel)
        data = self.kernel_data(compile_kernel)
        n = np.zeros(self.n_dof)  # the hook's argument types, as the time loop passes them
        accepted = KernelFunction(accepted_step, (0.0, n, n, n, data, self.diag, self.log),
                                  returns=numba.types.boolean)
        return CompiledProblem(kernel, accepted, data, self.log, self.mass, rows, self.diag, K, C, self.drain)

    # --- results -----------------------------------------------------------------------
    def channel(self, name: str) -> np.ndarray | float:
        """Diagnostic `name` (channels.py) of the last evaluated state: a float, or an array
        (per ball, or of a channel's width)."""
        value = channels.read(self.diag, self.params.ball_count, name)
        return float(value) if value.ndim == 0 else value.copy()

    def kinetic_energy(self, v) -> float:
        """T = sum of m v^2/2 + J Omega^2/2 over all bodies [J] (diagonal mass)."""
        return 0.5 * float(np.sum(self.mass * v * v))

    def impact_log(self) -> np.ndarray:
        return np.array(self.impacts).reshape(-1, len(IMPACT_FIELDS))
