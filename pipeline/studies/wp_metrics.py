"""Errors of a dynamic run against a reference run, on physical quantities.

Both runs are sampled at the same instants (Hermite dense output of HHT-α, or solve_ivp's
`t_eval`). Quantities, each compared as an RMS over the window:

* cage centre (x, y) [m] — the orbit that decides where the cage rubs (docs/model.md §8, §11);
* cage speed, material spin of the cage about its axis [rad/s];
* inner-race centre (x, y, z) [m];
* ball–pocket impact peak force [N] — impacts found the same way in both runs from the
  sampled states (`sampled_impacts`), matched by ball and time; an impact of the reference
  with no partner within `match_window` counts as a 100 % error.
"""

from __future__ import annotations

import numpy as np

QUANTITIES = ("cage_centre", "cage_speed", "inner_race", "impact_force")
UNITS = {"cage_centre": "m", "cage_speed": "rad/s", "inner_race": "m", "impact_force": "-"}
LABELS = {"cage_centre": "cage centre RMS error [µm]", "cage_speed": "cage speed RMS error [rad/s]",
          "inner_race": "inner-race centre RMS error [nm]", "impact_force": "impact peak RMS error [%]"}
DISPLAY_SCALE = {"cage_centre": 1e6, "cage_speed": 1.0, "inner_race": 1e9, "impact_force": 100.0}


def physical_series(params, q: np.ndarray, v: np.ndarray) -> dict:
    """Sampled quantities of a bearing run: cage centre (N, 2), cage speed (N,), inner race (N, 3)."""
    from ...dynamics.bearing import layout

    Z = params.ball_count
    o = layout.inner_offset(Z)
    out = {"inner_race": q[:, o:o + 3]}
    if params.has_cage:
        c = layout.cage_offset(Z, True)
        out["cage_centre"] = q[:, c:c + 2]
        out["cage_speed"] = v[:, c + 5]
    return out


def sampled_impacts(params, t: np.ndarray, q: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Impact log (model.IMPACT_FIELDS rows) of a run, re-detected from its samples.

    The model's forces are evaluated at every sampled state and fed to the same impact
    tracker the product uses, so every method (HHT-α with any step, solve_ivp) is measured
    on the same time grid. Cost: one residual evaluation per sample.
    """
    from ...dynamics.bearing import BearingModel

    model = BearingModel(params)
    n = model.n_dof
    ma, g, a = np.zeros(n), np.zeros(n), np.zeros(n)
    for i in range(t.size):
        if not (np.all(np.isfinite(q[i])) and np.all(np.isfinite(v[i]))):
            break
        model.evaluate(float(t[i]), q[i], v[i], a, ma, g)
        model.on_accepted_step(float(t[i]), q[i], v[i], a)
    return model.impact_log()


def impact_error(impacts: np.ndarray, reference: np.ndarray, match_window: float = 2e-4) -> tuple[float, int]:
    """(RMS relative peak-force error, matched count) of `impacts` against `reference`.

    Rows: (time, ball, orbital position, peak force, ...). Each reference impact is matched
    to the impact of the same ball nearest in time within `match_window` [s].
    """
    if reference.shape[0] == 0:
        return (0.0 if impacts.shape[0] == 0 else 1.0), 0
    errs, matched = [], 0
    for t_ref, ball, _, peak_ref, *_ in reference:
        same = impacts[impacts[:, 1] == ball] if impacts.size else impacts
        if same.shape[0]:
            j = np.argmin(np.abs(same[:, 0] - t_ref))
            if abs(same[j, 0] - t_ref) <= match_window:
                errs.append((same[j, 3] - peak_ref) / peak_ref)
                matched += 1
                continue
        errs.append(1.0)
    return float(np.sqrt(np.mean(np.square(errs)))), matched


def rms_vector_error(x: np.ndarray, x_ref: np.ndarray) -> float:
    """RMS over samples of the Euclidean norm of the difference (rows = samples); inf if
    the run stopped early (NaN samples)."""
    d = np.asarray(x) - np.asarray(x_ref)
    d = d.reshape(d.shape[0], -1)
    if not np.all(np.isfinite(d)):
        return float("inf")
    return float(np.sqrt(np.mean(np.sum(d * d, axis=1))))


def run_errors(params, t, q, v, ref: dict) -> dict:
    """Errors of one sampled run against `ref` = reference_data(...) (QUANTITIES keys)."""
    series = physical_series(params, q, v)
    out = {k: rms_vector_error(series[k], ref["series"][k]) for k in series}
    if params.has_cage:
        out["impact_force"], out["impacts_matched"] = impact_error(sampled_impacts(params, t, q, v),
                                                                   ref["impacts"])
    return out


def reference_data(params, t, q, v) -> dict:
    """What the errors are measured against: the series and the re-detected impacts."""
    return {"series": physical_series(params, q, v),
            "impacts": sampled_impacts(params, t, q, v) if params.has_cage else np.zeros((0, 6))}


def observed_order(h: np.ndarray, err: np.ndarray) -> float:
    """Least-squares slope of log(err) against log(h): the observed convergence order."""
    h, err = np.asarray(h, float), np.asarray(err, float)
    ok = (err > 0) & np.isfinite(err)
    if ok.sum() < 2:
        return float("nan")
    return float(np.polyfit(np.log(h[ok]), np.log(err[ok]), 1)[0])
