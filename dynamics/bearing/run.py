"""Run the bearing model from its quasi-static state (docs/model.md §10) with HHT-α (§9).

Samples are taken at the first accepted step at or after each multiple of the sample
interval: the saved state and every saved force are those of a converged step (no
interpolation, no re-solving), at times within one step (<= max_step) of the grid.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Callable, NamedTuple

import numpy as np

from ..multibody.crv import crv_from_rotation_vector, crv_to_matrix
from ..multibody.compiled import compile_loop, integrate_compiled
from ..multibody.results import IntegrationError
from ..multibody.settings import HHTSettings

from . import layout
from .channels import declared as declared_channels, read as read_channel
from .model import IMPACT_FIELDS, BearingModel
from .params import FP_OMEGA_I, BearingModelParams


def initial_coordinates(params: BearingModelParams, start: dict) -> tuple[np.ndarray, np.ndarray]:
    """q0, v0 from `dynamics.quasistatic.result.initial_state(...)`: balls at their
    equilibrium positions in pure rolling, inner race displaced and tilted as in equilibrium
    and spinning at its prescribed speed, cage turning at the mean orbital speed, centred on
    what guides it (the outer ring's axis, the inner race's centre, the ball set's centroid)
    and axially on the balls' mean plane, so that no pocket starts in contact with its ball."""
    Z = params.ball_count
    n = params.n_dof
    q, v = np.zeros(n), np.zeros(n)
    balls_q, balls_v = layout.ball_states(q, Z), layout.ball_states(v, Z)
    balls_q[:, :3] = start["ball_positions"]
    balls_v[:, :3] = start["ball_velocities"]
    balls_v[:, 3:] = start["ball_angular_velocities"]
    o = layout.inner_offset(Z)
    q[o:o + 3] = start["inner_race_displacement"]
    tilt = start["inner_race_tilt"]
    q[o + 3:o + 6] = crv_from_rotation_vector(np.array([tilt[0], tilt[1], 0.0]))
    v[o + 5] = params.fp[FP_OMEGA_I]  # material spin = prescribed inner-race speed
    if params.has_cage:
        c = layout.cage_offset(Z, True)
        balls = np.asarray(start["ball_positions"], dtype=float)
        guide = params.cage_guidance
        q[c:c + 2] = (q[o:o + 2] if guide == "inner" else balls[:, :2].mean(axis=0) if guide == "ball"
                      else 0.0)
        q[c + 2] = balls[:, 2].mean()
        v[c + 5] = start["cage_angular_speed"]
    return q, v


class RunSeries(NamedTuple):
    """One named series of a run: data (samples first), unit, description and the names of
    its dimensions ("time", then "xyz", "xy", "ball", ...)."""

    data: np.ndarray
    unit: str
    description: str
    dims: tuple[str, ...]


@dataclass
class BearingRun:
    """Sampled results of a run (arrays over samples), the impact log and the counters.
    `channels()` names every saved series; q, v and diag are the raw layouts (layout.py,
    channels.py) for code inside dynamics/bearing."""

    t: np.ndarray
    q: np.ndarray
    v: np.ndarray
    diag: np.ndarray
    impacts: np.ndarray
    energy: dict
    kinetic: np.ndarray
    stats: dict
    ball_count: int
    has_cage: bool
    step_history: np.ndarray = field(default_factory=lambda: np.zeros((0, 2)))
    impact_fields: tuple = IMPACT_FIELDS

    def channels(self) -> dict[str, RunSeries]:
        """Every saved series by name (the names of timeseries.h5): body states, the saved
        diagnostics of the channel table (channels.py; the cage's only with a cage), energies
        and the step history."""
        Z = self.ball_count
        T, V, B, BV = ("time",), ("time", "xyz"), ("time", "ball"), ("time", "ball", "xyz")
        o = layout.inner_offset(Z)
        balls_q, balls_v = layout.ball_states(self.q, Z), layout.ball_states(self.v, Z)
        R_i = _rotations(self.q[:, o + 3:o + 6])
        out = {
            "time": RunSeries(self.t, "s", "sample time (end of the first accepted step at or after each sample instant)", T),
            "inner_race/position": RunSeries(self.q[:, o:o + 3], "m", "inner-race centre, global frame", V),
            "inner_race/velocity": RunSeries(self.v[:, o:o + 3], "m/s", "inner-race centre velocity", V),
            "inner_race/axis": RunSeries(R_i[:, :, 2], "-", "inner-race axis (unit vector); its x, y are the tilts about -y, +x", V),
            "inner_race/angular_velocity": RunSeries(self.v[:, o + 3:o + 6], "rad/s", "material angular velocity", V),
            "inner_race/angle": RunSeries(spin_angle(R_i), "rad", "angle the inner race has turned about +z since "
                                          "t = 0 (unwrapped): its land's azimuth x is at x + angle", T),
            "balls/position": RunSeries(balls_q[:, :, :3], "m", "ball centres", BV),
            "balls/velocity": RunSeries(balls_v[:, :, :3], "m/s", "ball centre velocities", BV),
            "balls/angular_velocity": RunSeries(balls_v[:, :, 3:], "rad/s", "ball angular velocities (global frame)", BV),
            "energy/kinetic": RunSeries(self.kinetic, "J", "kinetic energy of all bodies", T),
            "solver/step_size": RunSeries(self.step_history, "s", "(time, step size) every 50 accepted steps", ("sample", "t_h")),
        }
        if self.has_cage:
            c = layout.cage_offset(Z, True)
            R_c = _rotations(self.q[:, c + 3:c + 6])
            omega = np.einsum("nij,nj->ni", R_c, self.v[:, c + 3:c + 6])
            out.update({
                "cage/position": RunSeries(self.q[:, c:c + 3], "m", "cage centre (guiding race at the origin)", V),
                "cage/velocity": RunSeries(self.v[:, c:c + 3], "m/s", "cage centre velocity", V),
                "cage/angular_velocity": RunSeries(omega, "rad/s", "cage angular velocity, global frame", V),
                "cage/speed": RunSeries(omega[:, 2], "rad/s", "cage rotation speed about +z", T),
                "cage/angle": RunSeries(spin_angle(R_c), "rad", "angle the cage has turned about +z since t = 0 "
                                        "(unwrapped): its rim's azimuth x is at x + angle", T),
            })
        for ch, per_ball in declared_channels(self.has_cage):
            dims = (B if per_ball else T) + (("xy",) if ch.width == 2 else ("xyz",) if ch.width == 3 else ())
            out[ch.name] = RunSeries(read_channel(self.diag, Z, ch.name), ch.unit, ch.description, dims)
        return out


def spin_angle(R: np.ndarray) -> np.ndarray:
    """The angle [rad] rotations R (n, 3, 3) turn +x about +z, unwrapped over the samples (the
    samples are close enough that a body turns less than half a turn between two)."""
    return np.unwrap(np.arctan2(R[:, 1, 0], R[:, 0, 0])) if len(R) else np.zeros(0)


def _rotations(c: np.ndarray) -> np.ndarray:
    """Rotation matrices (n, 3, 3) of the CRVs c (n, 3) (docs/model.md M.4b)."""
    c = np.ascontiguousarray(c, dtype=float)
    return np.array([crv_to_matrix(ci) for ci in c]).reshape(-1, 3, 3)


def simulate_bearing(params: BearingModelParams, start: dict, settings: HHTSettings,
                     duration: float, sample_interval: float,
                     progress: Callable[[float, float, float], None] | None = None) -> BearingRun:
    """Integrate the bearing for `duration` [s] from the quasi-static `start`.
    progress(t, t_end, h) is called about four times a second of wall time."""
    # the loop's tangent is the model's own, so its residuals may take the float32 traction passes
    params = params.with_float32_residual()
    model = BearingModel(params)
    q0, v0 = initial_coordinates(params, start)
    n = model.n_dof
    # The first calls compile the force kernels and the time loop (or load them from numba's
    # cache): timed apart, so that the integration's wall time is the integration's. Two steps
    # reach every kernel: residual, tangent, factorisation, solve, the loop.
    warm0 = time.perf_counter()
    warm_up_compiled_loop(model, q0, v0, settings, duration)
    model = BearingModel(params)  # a fresh impact log and energy balance
    # the initial diagnostics come from the initial-acceleration evaluation
    model.evaluate(0.0, q0, v0, np.zeros(n), np.zeros(n), np.zeros(n))
    kernel_load_time = time.perf_counter() - warm0
    model.on_accepted_step(0.0, q0, v0, np.zeros(n))
    wall = [time.perf_counter()]

    def report(t, h):
        if progress is not None and time.perf_counter() - wall[0] > 0.25:
            wall[0] = time.perf_counter()
            progress(t, duration, h)

    sol, rec = integrate_compiled(model, 0.0, duration, q0, v0, settings, record_dt=sample_interval,
                                  log_every=50, on_chunk=report)
    s = sol.stats
    stats = {k: getattr(s, k) for k in ("steps", "rejected_steps", "newton_failures", "newton_iterations",
                                       "factorizations", "residual_evaluations", "min_step_accepts",
                                       "wall_time")}
    stats["kernel_load_time"] = kernel_load_time
    kinetic = 0.5 * (rec.v * rec.v) @ model.mass
    return BearingRun(t=rec.t, q=rec.q, v=rec.v, diag=rec.diag, impacts=model.impact_log(),
                      energy=model.energy, kinetic=kinetic, stats=stats, ball_count=params.ball_count,
                      has_cage=params.has_cage, step_history=rec.log[:, :2].copy())


def load_kernels(params: BearingModelParams, start: dict, settings: HHTSettings) -> None:
    """Compile (or load from numba's cache) every kernel a run of `params` calls, with the
    first steps of the run (`warm_up_compiled_loop`). The caller may hold a lock around it so
    that processes sharing a cache compile once (pipeline.machine.kernel_cache), and times it."""
    params = params.with_float32_residual()
    model = BearingModel(params)
    q0, v0 = initial_coordinates(params, start)
    warm_up_compiled_loop(model, q0, v0, settings, 2.0 * settings.first_step)


def compile_time_loop(params: BearingModelParams, settings: HHTSettings) -> None:
    """Compile (or load) the time loop of a run of `params` alone, without its force kernel
    (`multibody.compiled.compile_loop`), so that another process may compile that meanwhile."""
    compile_loop(BearingModel(params.with_float32_residual()), settings)


def compile_force_kernel_and_loop(params: BearingModelParams, settings: HHTSettings) -> None:
    """Compile (or load) the force kernel of a run of `params` without its tangent kernel, for the
    argument types the time loop passes it (`BearingModel.force_kernel`), and the time loop
    (`compile_time_loop`): one half of the dynamic run's kernels, which a second process may
    compile while this one compiles the other (`compile_tangent_kernel`)."""
    BearingModel(params.with_float32_residual()).force_kernel(compile_force=True, compile_tangents=False)
    compile_time_loop(params, settings)


def compile_tangent_kernel(params: BearingModelParams) -> None:
    """Compile (or load) the tangent kernel of a run of `params` alone (`BearingModel.kernel_data`)."""
    BearingModel(params.with_float32_residual()).kernel_data(compile_tangents=True)


def warm_up_compiled_loop(model: BearingModel, q0, v0, settings: HHTSettings, duration: float) -> None:
    """Compile (or load from numba's cache) the time loop with the first steps of the run; the
    model's impact log and energy balance are left dirty.

    The steps are the run's own (same step control, so a first step that Newton cannot take
    is cut as the run would cut it), over two first steps at most. Numba compiles the whole
    loop at its first call, so a failure there has done its job: the run itself meets that
    failure again and reports it with its time and what to try."""
    horizon = min(2.0 * settings.first_step, duration)
    try:
        integrate_compiled(model, 0.0, horizon, q0, v0, settings)
    except IntegrationError:
        pass
