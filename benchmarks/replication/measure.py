"""The numbers docs/replication.md shows for one run directory.

The cage statistics are the product's own (`summary.json`, over its settled window: what a user
of `bearingsim run` reads). The inner race's motion, the balls' spacing, the land torque and the
pocket forces are measured here from `timeseries.h5` over the same window, and set beside the
closed-form estimates of `estimates.py`.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from . import estimates

CLIP_BAND = 0.021  # the torque clip of docs/model.md (M.90) acts where f_C < 2.1 %
ARC = 60.0         # deg, width of the impact regions compared with the paper's (45-65° wide)


def _deg(rad):
    return None if rad is None else math.degrees(rad) % 360.0


def cage_statistics(summary: dict) -> dict:
    """The product's settled-window statistics of the cage, in the units the page shows."""
    s = summary
    start, end = s["settled_window"]
    v = s.get("verdict") or {}
    screen = s.get("crush_screen") or {}
    regions = [[math.degrees(a) % 360.0, math.degrees(b) % 360.0, share]
               for a, b, share in (s.get("pocket_impact_regions") or [])]
    return {
        "class": v.get("class"), "risk": v.get("risk"), "sector_deg": v.get("sector_deg"),
        "settled_window_s": [start, end], "settled_revolutions": s.get("settled_revolutions"),
        "eps_mean": s["cage_eps_mean"], "eps_max": s["cage_eps_max"],
        "metal_fraction": s["cage_metal_contact_fraction"],
        "offset_azimuth_deg": _deg(s.get("cage_offset_azimuth_mean")), "offset_spread_rad": s.get("cage_offset_spread"),
        "whirl_ratio": s["cage_whirl_ratio"],
        "speed_variation": s["cage_speed_variation"],
        "cage_slip": 1.0 - s["cage_speed_mean"] / s["kinematic_cage_speed"],
        "land_force_mean_N": s["cage_land_force_mean"], "land_force_max_N": s["cage_land_force_max"],
        "land_film_min_um": 1e6 * s["land_film_min"],
        "impacts": s["pocket_impacts"], "impacts_per_s": s["pocket_impacts"] / (end - start),
        "impact_p95_N": s["pocket_impact_force_p95"], "impact_regions_deg": regions,
        "inner_axial_mm": 1e3 * s["inner_race_axial_mean"],
        "burn_zone_deg": [math.degrees(a) for a in s["burn_zone_sector"]] if s.get("burn_zone_sector") else None,
        "non_guiding_gap_min_um": 1e6 * s["non_guiding_gap_min"] if s.get("non_guiding_gap_min") is not None else None,
        "screen_regime": screen.get("regime"), "crush_margin": screen.get("crush_margin"),
        "startup_land_force_peak_N": (s.get("startup") or {}).get("land_force_peak"),
        "integration_wall_time_s": s.get("integration_wall_time"), "steps": s.get("steps"),
        "newton_failures": s.get("newton_failures"),
    }


def impact_arcs(positions_deg: np.ndarray, width: float = ARC, step: float = 5.0) -> list[list[float]]:
    """The two orbital regions the pocket impacts concentrate in, as the paper describes its case b:
    the arc of `width` degrees holding the most impacts, and the densest such arc whose centre is
    at least 90° from the first. [[start, end, share], [start, end, share]] (degrees, 0-360;
    an even spread puts width/360 of the impacts in any arc); [] without impacts."""
    pos = np.mod(np.asarray(positions_deg, dtype=float), 360.0)
    if pos.size == 0:
        return []
    starts = np.arange(0.0, 360.0, step)
    inside = np.mod(pos[None, :] - starts[:, None], 360.0) < width
    share = inside.mean(axis=1)
    first = int(np.argmax(share))
    centre = starts + 0.5 * width
    apart = np.abs(np.mod(centre - centre[first] + 180.0, 360.0) - 180.0) >= 90.0
    second = int(np.flatnonzero(apart)[np.argmax(share[apart])])
    return [[float(starts[i]), float((starts[i] + width) % 360.0), float(share[i])] for i in (first, second)]


def _series(path: Path, names: tuple[str, ...]) -> dict[str, np.ndarray]:
    import h5py

    with h5py.File(path) as f:
        return {n: f[n][:] for n in names}


def _peak_frequency(t: np.ndarray, x: np.ndarray) -> float:
    """Frequency [Hz] of the largest line of x's spectrum (mean removed, Hann window, padded
    eightfold so that the line is placed between the window's bins)."""
    x = (x - x.mean()) * np.hanning(x.size)
    n = 8 * x.size
    spectrum = np.abs(np.fft.rfft(x, n))
    freq = np.fft.rfftfreq(n, float(np.median(np.diff(t))))
    return float(freq[1:][np.argmax(spectrum[1:])])


def motion_statistics(run) -> dict:
    """Inner race, ball spacing, land torque and pocket forces over the settled window, with the
    closed-form estimates of the inner race's ball-passage motion (estimates.py)."""
    s, q, scene = run.summary, run.quasistatic, run.scene
    names = ("time", "inner_race/position", "inner_race/axis", "balls/position", "pocket/force",
             "cage_race/torque", "cage_race/eccentricity_ratio", "cage/position")
    ts = _series(Path(run.run_dir) / "simulate" / "timeseries.h5", names)
    t = ts["time"]
    w = (t >= s["settled_window"][0]) & (t <= s["settled_window"][1])
    pos, axis = ts["inner_race/position"], ts["inner_race/axis"]
    xy = pos[w, :2] - pos[w, :2].mean(axis=0)
    radial_rms = float(np.sqrt(np.mean(np.sum(xy ** 2, axis=1))))
    # the start is the quasi-static pose, where the hinge is unstrained (docs/model.md §5)
    offset = pos[w].mean(axis=0) - pos[0]
    tilt = axis[w, :2] - axis[0, :2]  # small angles [rad]
    tilt_offset = tilt.mean(axis=0)
    tilt_rms = float(np.sqrt(np.mean(np.sum((tilt - tilt_offset) ** 2, axis=1))))
    eps0 = scene.physics.cage_race_boundary

    # the balls' loads of the quasi-static solution, as a pattern over the orbit
    balls = q["balls"]
    psi0 = np.array([b["azimuth"] for b in balls])
    load = np.array([b["inner_load"] for b in balls])
    alpha = np.array([b["inner_contact_angle"] for b in balls])
    half_pitch, radius = 0.5 * scene.bearing.pitch_diameter, 0.5 * scene.bearing.ball_diameter

    def g_of_psi(psi):
        p = np.mod(psi, 2.0 * math.pi)
        qq = np.interp(p, psi0, load, period=2.0 * math.pi)
        aa = np.interp(p, psi0, alpha, period=2.0 * math.pi)
        return estimates.spacing_sensitivity(
            estimates.ball_loads_on_inner_race(qq, aa, p, half_pitch - radius * np.cos(aa)))

    hinge = run.hinge
    diag = ([*np.diag(np.asarray(hinge["translational"])), *hinge["bending"]] if hinge else [0.0] * 5)
    c = estimates.compliance(np.asarray(q["stiffness"]), diag)
    bp = ts["balls/position"][w]
    psi = np.arctan2(bp[:, :, 1], bp[:, :, 0])
    deviation, fluctuation = estimates.spacing_deviation(psi)
    sigma = float(np.sqrt(np.mean(fluctuation ** 2)))
    response = estimates.spacing_response(g_of_psi, psi, fluctuation, c)
    rxy = response[:, :2] - response[:, :2].mean(axis=0)

    k = estimates.hertz_pattern_ratio(load.min(), load.max())
    vc_force = estimates.varying_compliance_force(k, len(balls), float(load.mean()), float(alpha.mean()))
    radial_stiffness = 1.0 / c[0, 0]
    torque = ts["cage_race/torque"][w]
    eps = ts["cage_race/eccentricity_ratio"][w]
    pocket = ts["pocket/force"][w]
    imp = run.impacts()
    when = (imp["time"].values >= s["settled_window"][0]) & (imp["time"].values <= s["settled_window"][1])
    hinge_force = float(np.linalg.norm(np.asarray(diag[:3]) * offset)) if hinge else None
    hinge_moment = float(np.linalg.norm(np.asarray(diag[3:]) * tilt_offset)) if hinge else None
    return {
        "inner_radial_rms_um": 1e6 * radial_rms,
        "inner_axial_rms_um": 1e6 * float(np.std(pos[w, 2])),
        "inner_offset_um": 1e6 * float(np.linalg.norm(offset)),
        "inner_tilt_offset_mrad": 1e3 * float(np.linalg.norm(tilt_offset)),
        "inner_tilt_rms_mrad": 1e3 * tilt_rms,
        "inner_radial_peak_hz": _peak_frequency(t[w], pos[w, 0]),
        "hinge_force_N": hinge_force, "hinge_moment_Nm": hinge_moment, "hinge_diagonal": [float(v) for v in diag],
        "spacing_rms_mm": 1e3 * half_pitch * float(np.sqrt(np.mean(deviation ** 2))),
        "spacing_fluctuation_rms_mm": 1e3 * half_pitch * sigma,
        "estimate_scatter_radial_rms_um": 1e6 * estimates.scatter_radial_rms(g_of_psi(psi0), c, sigma),
        "estimate_response_radial_rms_um": 1e6 * float(np.sqrt(np.mean(np.sum(rxy ** 2, axis=1)))),
        "vc_load_ratio_k": k, "vc_harmonic_decay": estimates.harmonic_decay(k),
        "vc_force_pp_N": vc_force, "vc_radial_pp_um": 1e6 * vc_force / radial_stiffness,
        "radial_stiffness_N_per_m": radial_stiffness,
        "cage_passage_hz": len(balls) * s["cage_speed_mean"] / (2.0 * math.pi),
        "cage_hz": s["cage_speed_mean"] / (2.0 * math.pi),
        "land_torque_mean_Nm": float(np.mean(np.abs(torque))),
        "land_torque_pocket_force_N": float(np.mean(np.abs(torque))) / (0.5 * scene.cage.mean_diameter),
        "pocket_force_sum_mean_N": float(np.mean(pocket.sum(axis=1))),
        "pocket_force_per_ball_mean_N": float(np.mean(pocket)),
        "impact_arcs_deg": impact_arcs(imp["orbital_position"].values[when]),
        "torque_clip_share": float(np.mean(eps > 1.0 + eps0 * (1.0 - CLIP_BAND))),
        "cage_axial_mean_mm": 1e3 * float(np.mean(ts["cage/position"][w, 2])),
        "cage_axial_std_mm": 1e3 * float(np.std(ts["cage/position"][w, 2])),
    }


def measure(run_dir: Path) -> dict:
    import bearingsim

    run = bearingsim.open_run(run_dir)
    return {**cage_statistics(run.summary), **motion_statistics(run)}
