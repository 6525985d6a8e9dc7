"""Work–precision of the dynamic solver: error against wall time.

    python -m bearingsim.pipeline.studies.work_precision [SCENE] [--quick] [--out DIR]
    bearingsim bench SCENE [--quick]

For a scene, the bearing is integrated over a fixed window from its quasi-static start by
several methods, each over a range of tolerances, and compared with a tight reference run
(HHT-α, alpha 0.1, fixed step `reference_step`) on the quantities of `wp_metrics`:

* HHT-α fixed step h (h = 2e-6 s was the scene default before the physical error scales);
* HHT-α adaptive, the scene default's error control (each coordinate on its physical scale,
  docs/model.md M.99b–M.100) over a range of rtol, alpha 0.1, 0 and 0.3, and with one choice
  of the default undone at a time (Newton from a_n, the correction test, an RMS norm);
* HHT-α adaptive with a finite-difference ("exact") tangent instead of the model's
  approximate analytic one (`instrumented.fd_tangent`);
* scipy `solve_ivp` Radau and BDF on the same residual as a first-order ODE (the baseline
  of `benchmarks.bearing`, dense finite-difference Jacobian).

The HHT-α rows with the model's tangent take the float32 traction passes of a user's run; the
reference, the finite-difference tangent and scipy take the smooth float64 residual, which
finite differences need (dynamics/traction/fast.py). The fixed-step sequence also gives the
observed order of HHT-α (2 expected: Hilber, Hughes & Taylor 1977). Wall times are on whatever else the machine runs: the load average is
recorded with the table.
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import os
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ...dynamics.multibody.settings import HHTSettings

from . import wp_metrics as wm


@dataclass(frozen=True)
class Method:
    """One point of a work–precision curve: a curve label and its solver settings."""

    curve: str
    setting: str                 # the swept parameter, as text (e.g. "h = 1e-06 s")
    hht: dict = field(default_factory=dict)   # HHTSettings overrides
    exact_tangent: bool = False
    ivp: dict | None = None      # {"method", "rtol", "atol"} for solve_ivp


# the scene default's error control (each coordinate on its physical scale, M.99b, max norm): the
# scene's own solver settings, which every row replaces onto, with adaptive steps at the shipped
# rtol; one definition, so that a copy cannot drift from the scenes' settings
ADAPTIVE_DEFAULT = {"adaptive": True, "rtol": HHTSettings().rtol}


# fixed steps with the Newton rules of the previous default (start from a_n, correction test,
# refactor at a step ratio of 1.5; h = 2e-6 s was that default, and its errors are the accuracy bar).
# rtol only sets Newton's tolerance here: 1e-2 of the physical scales stops it at 1e-4 of them
# (0.6 nm on a ball radially), about where the previous |q|-relative test stopped; at the adaptive
# default's 1e-6 Newton chases round-off at the cage's landing (~8.5 ms) and a fixed step cannot retreat
PREVIOUS_NEWTON = {"predictor": "constant", "newton_test": "correction", "refactor_step_ratio": 1.5,
                   "rtol": 1e-2, "newton_tol": 1e-2}
PREVIOUS_DEFAULT_STEP = 2e-6  # [s]


def fixed_step_method(h: float, curve: str = "HHT a=0.1 fixed h") -> Method:
    """Fixed steps of h [s] with the previous default's Newton rules (PREVIOUS_NEWTON)."""
    return Method(curve, f"h = {h:g} s",
                  {"adaptive": False, "first_step": h, "max_step": h, "min_step": min(h, 1e-8), **PREVIOUS_NEWTON})


def method_grid(quick: bool) -> list[Method]:
    """The methods and tolerances of the study (`quick`: CI-sized subset)."""
    steps = (4e-6, 2e-6, 1e-6) if quick else (4e-6, 2e-6, 1e-6, 5e-7)
    # down to 1e-8: scipy's Radau at rtol 1e-4 is more accurate on the cage centre than rtol 1e-7,
    # and a speed-up is only read inside HHT-alpha's curve (no extrapolation)
    rtols = (3e-6, 1e-6) if quick else (1e-5, 3e-6, 1e-6, 3e-7, 1e-7, 3e-8, 1e-8)
    short = (1e-5, 1e-6)
    adaptive = ADAPTIVE_DEFAULT
    grid = [fixed_step_method(h) for h in steps]
    grid += [Method("HHT a=0.1 adaptive", f"rtol = {r:g}", {**adaptive, "rtol": r}) for r in rtols]
    if not quick:
        for alpha in (0.0, 0.3):
            grid += [Method(f"HHT a={alpha:g} adaptive", f"rtol = {r:g}", {**adaptive, "rtol": r, "alpha": alpha})
                     for r in short]
        # what each choice of the default buys, one change at a time (docs/model.md M.100, M.102)
        grid += [Method("HHT a=0.1 adaptive, Newton from a_n", f"rtol = {r:g}",
                        {**adaptive, "rtol": r, "predictor": "constant"}) for r in short]
        grid += [Method("HHT a=0.1 adaptive, correction test", f"rtol = {r:g}",
                        {**adaptive, "rtol": r, "newton_test": "correction"}) for r in short]
        grid += [Method("HHT a=0.1 adaptive, newton_tol 0.01", f"rtol = {r:g}",
                        {**adaptive, "rtol": r, "newton_tol": 1e-2}) for r in short]
        grid += [Method("HHT a=0.1 adaptive, RMS norm", f"rtol = {r:g}",
                        {**adaptive, "rtol": r, "error_norm": "rms"}) for r in (1e-6, 1e-7)]
    grid += [Method("HHT a=0.1 adaptive, FD tangent", f"rtol = {r:g}", {**adaptive, "rtol": r}, True)
             for r in (short[:1] if quick else short)]
    ivp = [("Radau", 1e-3), ("Radau", 1e-4), ("BDF", 1e-3)] if not quick else [("Radau", 1e-3)]
    if not quick:
        ivp += [("Radau", 1e-5), ("BDF", 1e-4)]
    grid += [Method(f"solve_ivp {m}", f"rtol = {r:g}", ivp={"method": m, "rtol": r, "atol": r * 1e-5})
             for m, r in ivp]
    if not quick:
        # the block-arrow pattern as jac_sparsity: measured, because a careful scipy user would try it
        grid += [Method(f"solve_ivp {m}, jac_sparsity", f"rtol = {r:g}",
                        ivp={"method": m, "rtol": r, "atol": r * 1e-5, "sparse": True})
                 for m, r in (("Radau", 1e-3), ("Radau", 1e-4), ("BDF", 1e-3), ("BDF", 1e-4))]
    return grid


@dataclass(frozen=True)
class StudyConfig:
    window: float          # simulated window [s]
    sample_interval: float  # comparison grid [s]
    reference_step: float  # fixed HHT step of the reference [s]
    wall_budget: float     # per run [s]

    @classmethod
    def for_mode(cls, quick: bool) -> "StudyConfig":
        # the first pocket impacts come at ~5 ms, the cage reaches the land at ~8.5 ms (case b)
        return cls(0.006, 1e-5, 2.5e-7, 60.0) if quick else cls(0.015, 5e-6, 1e-7, 240.0)


def run_method(method: Method, params, start, base_settings, cfg: StudyConfig) -> dict:
    """Run one method over the window: samples (t, q, v), wall time, counters, error text."""
    if method.ivp is not None:
        return _run_solve_ivp(method.ivp, params, start, cfg)
    from .instrumented import bearing_window

    settings = dataclasses.replace(base_settings, **method.hht)
    run, _ = bearing_window(params, start, settings, cfg.window, cfg.sample_interval,
                            exact_tangent=method.exact_tangent, wall_budget=cfg.wall_budget)
    s = run.stats
    return {"t": run.t, "q": run.q, "v": run.v, "wall": run.wall, "error": run.error,
            "steps": s.get("steps"), "newton_iterations": s.get("newton_iterations"),
            "factorizations": s.get("factorizations"), "rejected": s.get("rejected_steps"),
            "h_history": run.history[:, :2]}


def _run_solve_ivp(opts: dict, params, start, cfg: StudyConfig) -> dict:
    """scipy's Radau/BDF (dense finite-difference Jacobian, or with `opts["sparse"]` the block-arrow
    sparsity pattern) stepped by hand, so that the model's accepted-step hook runs after
    every step as in HHT-α: the pocket contacts' hysteresis remembers the approach speed of
    each impact there (`BearingModel.on_accepted_step`); without it the ODE is another model."""
    from scipy import integrate as si

    from ...dynamics.bearing import BearingModel, layout
    from ...dynamics.bearing.run import initial_coordinates

    from .instrumented import WallClockExceeded
    from .scipy_baseline import jac_sparsity, ode_rhs

    model = BearingModel(params)
    q0, v0 = initial_coordinates(params, start)
    rhs, _ = ode_rhs(model, model.rotation_slots, layout.spin_row(params.ball_count))
    n = model.n_dof
    y0 = np.concatenate([q0, v0])
    rhs(0.0, y0)  # compile / load before timing
    dt = cfg.sample_interval  # the comparison grid of instrumented.run_window: [0, window)
    t_eval = dt * np.arange(int(math.floor((cfg.window - 0.5 * dt) / dt * (1 + 1e-12))) + 1)
    y = np.full((t_eval.size, 2 * n), np.nan)
    y[0], k, steps, error = y0, 1, 0, None
    t0 = time.perf_counter()
    sparse = {"jac_sparsity": jac_sparsity(params.ball_count, params.has_cage, model.rotation_slots)} \
        if opts.get("sparse") else {}
    solver = getattr(si, opts["method"])(rhs, 0.0, y0, cfg.window, rtol=opts["rtol"], atol=opts["atol"], **sparse)
    zero = np.zeros(n)
    while solver.status == "running":
        if time.perf_counter() - t0 > cfg.wall_budget:
            error = str(WallClockExceeded(solver.t, cfg.wall_budget))
            break
        t_old = solver.t
        message = solver.step()
        if solver.status == "failed":
            error = f"solve_ivp {opts['method']} failed at t = {solver.t:.6g} s: {message}"
            break
        steps += 1
        qs, vs = np.array(solver.y[:n]), np.array(solver.y[n:])
        model.evaluate(solver.t, qs, vs, zero, np.zeros(n), np.zeros(n))
        model.on_accepted_step(solver.t, qs, vs, zero)
        if k < t_eval.size and t_eval[k] <= solver.t:
            dense = solver.dense_output()
            while k < t_eval.size and t_old < t_eval[k] <= solver.t:
                y[k] = dense(t_eval[k])
                k += 1
    return {"t": t_eval, "q": y[:, :n], "v": y[:, n:], "wall": time.perf_counter() - t0, "error": error,
            "steps": steps, "newton_iterations": solver.nfev, "factorizations": solver.nlu, "rejected": None}


def reference_run(params, start, base_settings, cfg: StudyConfig):
    """The study's reference: HHT-α at fixed steps of `cfg.reference_step` over the window.
    Returns (the run, `wp_metrics.reference_data` of it); raises if the run failed."""
    from .instrumented import bearing_window

    h = cfg.reference_step
    ref_settings = dataclasses.replace(base_settings, adaptive=False, first_step=h, max_step=h,
                                       min_step=min(h, base_settings.min_step))
    bearing_window(params, start, ref_settings, 4 * h, 2 * h)  # numba compile / cache load
    # the reference keeps the float64 residual (scipy's model); the HHT-alpha rows run the float32
    # traction passes of a user's run, so their errors include what those passes cost
    ref_run, _ = bearing_window(params, start, ref_settings, cfg.window, cfg.sample_interval,
                                float32_residual=False)
    if not ref_run.completed:
        raise RuntimeError(f"the reference run failed, so no error can be measured: {ref_run.error}")
    return ref_run, wm.reference_data(params, ref_run.t, ref_run.q, ref_run.v)


def run_study(params, start, base_settings, quick: bool, progress=print,
              methods: list[Method] | None = None, cfg: StudyConfig | None = None) -> dict:
    """Reference run, then every method; returns {"config", "reference", "rows", "load"}."""
    cfg = cfg or StudyConfig.for_mode(quick)
    methods = method_grid(quick) if methods is None else methods
    progress(f"reference: HHT alpha {base_settings.alpha}, fixed h = {cfg.reference_step:g} s "
             f"over {cfg.window * 1e3:g} ms")
    ref_run, ref = reference_run(params, start, base_settings, cfg)
    rows = []
    for m in methods:
        progress(f"{m.curve}: {m.setting}")
        out = run_method(m, params, start, base_settings, cfg)
        errs = wm.run_errors(params, out["t"], out["q"], out["v"], ref) if out["error"] is None else {}
        rows.append({"curve": m.curve, "setting": m.setting, "wall": out["wall"], "error_text": out["error"],
                     **{k: out.get(k) for k in ("steps", "newton_iterations", "factorizations", "rejected")},
                     **{q: errs.get(q, math.inf) for q in wm.QUANTITIES},
                     "impacts_matched": errs.get("impacts_matched")})
    fixed = [r for r in rows if r["curve"].endswith("fixed h")]
    # the inner race moves from t = 0 (the cage only after the first impacts): its error is
    # the cleanest measure of the order
    order = wm.observed_order([float(r["setting"].split()[2]) for r in fixed], [r["inner_race"] for r in fixed])
    centre = ref["series"].get("cage_centre")
    excursion = float(np.max(np.hypot(*(centre - centre[0]).T))) if centre is not None and len(centre) else None
    return {"config": dataclasses.asdict(cfg), "quick": quick,
            "reference": {"wall": ref_run.wall, "impacts": int(ref["impacts"].shape[0]),
                          "steps": ref_run.stats.get("steps"), "alpha": base_settings.alpha,
                          "cage_excursion_max": excursion},
            "rows": rows, "observed_order_fixed_h": order, "load_average": os.getloadavg()[0]}


DEFAULT_CURVE = "HHT a=0.1 adaptive"


def speedup_at_equal_error(rows: list[dict], quantity: str = "cage_centre", curve: str = DEFAULT_CURVE) -> dict:
    """For every solve_ivp row: its wall time over the wall time HHT-α (`curve`) needs for the same
    error on `quantity`, interpolated linearly in log(error) -> log(wall) between the curve's
    points; None when the row's error lies outside the curve's range (no extrapolation)."""
    pts = sorted((r[quantity], r["wall"]) for r in rows
                 if r["curve"] == curve and not r["error_text"] and math.isfinite(r[quantity]) and r[quantity] > 0)
    if len(pts) < 2:
        return {}
    log_e = np.log([p[0] for p in pts])
    log_w = np.log([p[1] for p in pts])
    out = {}
    for r in rows:
        if not r["curve"].startswith("solve_ivp") or r["error_text"] or not r[quantity] > 0:
            continue
        e = math.log(r[quantity])
        out[f"{r['curve']}, {r['setting']}"] = (
            r["wall"] / math.exp(float(np.interp(e, log_e, log_w))) if log_e[0] <= e <= log_e[-1] else None)
    return out


DEFAULT_SETTING = f"rtol = {ADAPTIVE_DEFAULT['rtol']:g}"  # the scene default's row of DEFAULT_CURVE


def scipy_at_default_error(rows: list[dict], quantity: str = "cage_centre", curve: str = DEFAULT_CURVE,
                           setting: str = DEFAULT_SETTING) -> dict:
    """The other reading of "equal error": for every solve_ivp curve, the wall time it needs for the
    scene default's error on `quantity` (row `curve`, `setting`) over the default's own wall time.

    A curve's time at that error is read off the lower envelope of its points (a point that another
    one beats on both error and time is dropped: scipy's error is not monotonic in its rtol) and
    interpolated linearly in log(error) -> log(wall): {"speedup": x, "bound": False}. When every
    envelope point is more accurate than the default, the loosest one's time bounds what the curve
    needs from above: {"speedup": x, "bound": True} (x is then an upper bound). None when the curve
    never reached the default's error."""
    default = [r for r in rows if r["curve"] == curve and r["setting"] == setting and not r["error_text"]]
    if not default or not default[0][quantity] > 0:
        return {}
    e0, w0 = math.log(default[0][quantity]), default[0]["wall"]
    curves: dict[str, list[tuple[float, float]]] = {}
    for r in rows:
        if r["curve"].startswith("solve_ivp") and not r["error_text"] and math.isfinite(r[quantity]) and r[quantity] > 0:
            curves.setdefault(r["curve"], []).append((r[quantity], r["wall"]))
    out: dict = {}
    for name, pts in curves.items():
        envelope = []
        for err, wall in sorted(pts):
            if not envelope or wall < envelope[-1][1]:
                envelope.append((err, wall))
        log_e = np.log([p[0] for p in envelope])
        log_w = np.log([p[1] for p in envelope])
        if e0 < log_e[0]:
            out[name] = None
        elif e0 > log_e[-1]:
            out[name] = {"speedup": envelope[-1][1] / w0, "bound": True}
        else:
            out[name] = {"speedup": math.exp(float(np.interp(e0, log_e, log_w))) / w0, "bound": False}
    return out


def markdown_table(study: dict) -> str:
    """The study as a markdown table (what `bearingsim bench` prints)."""
    head = ("| method | setting | wall [s] | steps | Newton it. / nfev | LU | cage centre [µm] | "
            "cage speed [rad/s] | inner race [nm] | impact peaks [%] |")
    lines = [head, "|" + "---|" * 10]
    for r in study["rows"]:
        if r["error_text"]:
            lines.append(f"| {r['curve']} | {r['setting']} | {r['wall']:.2f} | failed: {r['error_text'][:80]} |||||||")
            continue
        cells = [f"{r[q] * wm.DISPLAY_SCALE[q]:.3g}" for q in wm.QUANTITIES]
        lines.append(f"| {r['curve']} | {r['setting']} | {r['wall']:.2f} | {_int(r['steps'])} | "
                     f"{_int(r['newton_iterations'])} | {_int(r['factorizations'])} | " + " | ".join(cells) + " |")
    c, ref = study["config"], study["reference"]
    lines.append("")
    lines.append(f"Window {c['window'] * 1e3:g} ms, compared every {c['sample_interval'] * 1e6:g} us against "
                 f"HHT alpha {ref['alpha']} at fixed h = {c['reference_step']:g} s ({ref['wall']:.1f} s wall, "
                 f"{ref['impacts']} pocket impacts). Observed order of HHT fixed-h (inner-race error): "
                 f"{study['observed_order_fixed_h']:.2f} (2 expected). Load average {study['load_average']:.1f}.")
    excursion = ref.get("cage_excursion_max")
    if excursion is not None:
        lines.append("")
        lines.append(f"The reference's cage centre moves at most {excursion * 1e6:.3g} µm from its start in the window"
                     + (": the quick window ends about when the cage starts to move (its first pocket impacts), so "
                        "the cage-centre errors and the solve_ivp comparisons built on them say little; the study "
                        "without --quick covers the cage's way to its land." if study.get("quick") else "."))
    speedups = speedup_at_equal_error(study["rows"])
    if speedups:
        lines.append("")
        lines.append(f"Wall time of solve_ivp over that of {DEFAULT_CURVE} at the same cage-centre error "
                     "(interpolated along its curve): " + "; ".join(
                         f"{k} {'outside the curve' if x is None else f'{x:.1f}x'}" for k, x in speedups.items()) + ".")
    at_default = scipy_at_default_error(study["rows"])
    if at_default:
        lines.append("")
        lines.append(f"Wall time solve_ivp needs for the cage-centre error of the scene default ({DEFAULT_CURVE}, "
                     f"{DEFAULT_SETTING}; along the lower envelope of its points) over the default's: " + "; ".join(
                         f"{k} " + ("never as accurate" if x is None else
                                    f"{'at most ' if x['bound'] else ''}{x['speedup']:.1f}x")
                         for k, x in at_default.items()) + ".")
    return "\n".join(lines)


def _int(x) -> str:
    return "-" if x is None else str(int(x))


def write_study(study: dict, out_dir: Path) -> list[Path]:
    """work_precision.json, .md and .png in `out_dir` (atomic writes)."""
    from . import write_study_files
    from .wp_plots import plot_work_precision

    return write_study_files(study, out_dir, "work_precision", markdown_table(study),
                             lambda path: plot_work_precision(study, path))


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scene", nargs="?", default="helicopter-b-given-hinge")
    ap.add_argument("--quick", action="store_true", help="CI-sized variant (short window, few tolerances)")
    ap.add_argument("--out", type=Path, default=Path("runs/bench"))
    ap.add_argument("--set", action="append", default=[], dest="overrides")
    args = ap.parse_args(argv)
    from ..scene.load import load_scene
    from ..stages.simulate import build_model

    scene = load_scene(args.scene, args.overrides)
    params, start = build_model(scene, None)
    study = run_study(params, start, scene.solver, args.quick)
    write_study(study, args.out)
    print(markdown_table(study))


if __name__ == "__main__":
    main()
