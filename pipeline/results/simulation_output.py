"""Turn a dynamic run into files a user can open elsewhere: `timeseries.h5` (every variable
with units and a description), `impacts.csv`, the figures of docs/model.md §11, and the
numbers of `summary.json` (docs/scenes.md)."""

from __future__ import annotations

import io
from pathlib import Path

import numpy as np

from ..artefacts import atomic_write_text
from .cage_metrics import DEFAULT_LAND_ROUGHNESS, cage_summary
from .verdict import cage_verdict
from .timeseries import Series, write_timeseries


def _crv_to_matrix(c: np.ndarray) -> np.ndarray:
    """Rotation matrices (n, 3, 3) of the CRVs c (n, 3): M.4b, by the dynamics' own kernel."""
    from bearingsim.dynamics.multibody.crv import crv_to_matrix

    c = np.ascontiguousarray(c, dtype=float)
    return np.array([crv_to_matrix(ci) for ci in c]).reshape(-1, 3, 3)


def collect_series(run, params) -> dict[str, Series]:
    """Name, unit and describe every saved variable (see README 'Results')."""
    from bearingsim.dynamics.bearing import assembly as A
    from bearingsim.dynamics.bearing import layout

    Z = params.ball_count
    o = layout.inner_offset(Z)
    T = ("time",)
    V = ("time", "xyz")
    B = ("time", "ball")
    BV = ("time", "ball", "xyz")
    d = run.diag
    balls = run.q[:, :6 * Z].reshape(-1, Z, 6)
    ball_v = run.v[:, :6 * Z].reshape(-1, Z, 6)
    per_ball = d[:, A.N_DG:].reshape(-1, Z, A.DB)
    R_i = _crv_to_matrix(run.q[:, o + 3:o + 6])
    s = {
        "time": Series(run.t, "s", "sample time (end of the first accepted step at or after each sample instant)", T),
        "inner_race/position": Series(run.q[:, o:o + 3], "m", "inner-race centre, global frame", V),
        "inner_race/velocity": Series(run.v[:, o:o + 3], "m/s", "inner-race centre velocity", V),
        "inner_race/axis": Series(R_i[:, :, 2], "-", "inner-race axis (unit vector); its x, y are the tilts about -y, +x", V),
        "inner_race/angular_velocity": Series(run.v[:, o + 3:o + 6], "rad/s", "material angular velocity", V),
        "balls/position": Series(balls[:, :, :3], "m", "ball centres", BV, True),
        "balls/velocity": Series(ball_v[:, :, :3], "m/s", "ball centre velocities", BV, True),
        "balls/angular_velocity": Series(ball_v[:, :, 3:], "rad/s", "ball angular velocities (global frame)", BV, True),
        "contacts/inner_load": Series(per_ball[:, :, A.DB_QI], "N", "ball-inner race normal load", B, True),
        "contacts/outer_load": Series(per_ball[:, :, A.DB_QO], "N", "ball-outer race normal load", B, True),
        "contacts/inner_contact_angle": Series(per_ball[:, :, A.DB_AI], "rad", "inner contact angle (+: carries +z thrust on the inner race)", B, True),
        "contacts/outer_contact_angle": Series(per_ball[:, :, A.DB_AO], "rad", "outer contact angle", B, True),
        "contacts/inner_film": Series(per_ball[:, :, A.DB_HI], "m", "inner central film thickness (0: no film)", B, True),
        "contacts/outer_film": Series(per_ball[:, :, A.DB_HO], "m", "outer central film thickness", B, True),
        "contacts/inner_slide_roll": Series(per_ball[:, :, A.DB_SRRI], "-", "inner slide-to-roll ratio", B, True),
        "contacts/outer_slide_roll": Series(per_ball[:, :, A.DB_SRRO], "-", "outer slide-to-roll ratio", B, True),
        "contacts/inner_max_pressure": Series(per_ball[:, :, A.DB_PMI], "Pa", "inner maximum Hertz pressure", B, True),
        "contacts/outer_max_pressure": Series(per_ball[:, :, A.DB_PMO], "Pa", "outer maximum Hertz pressure", B, True),
        "energy/kinetic": Series(run.kinetic, "J", "kinetic energy of all bodies", T),
        "energy/hertz": Series(d[:, A.DG_V_HERTZ], "J", "elastic energy of the ball-race contacts", T),
        "energy/hinge": Series(d[:, A.DG_V_HINGE], "J", "elastic energy of the hinge", T),
        "power/drive": Series(d[:, A.DG_P_DRIVE], "W", "power of the drive holding the inner-race speed", T),
        "power/external": Series(d[:, A.DG_P_EXT], "W", "power of the applied loads", T),
        "power/dissipated": Series(d[:, A.DG_P_DISS], "W", "power dissipated by traction, damping and friction", T),
        "power/drive_moment": Series(d[:, A.DG_DRIVE], "N.m", "drive moment about the inner-race axis", T),
        "solver/step_size": Series(run.step_history, "s", "(time, step size) every 50 accepted steps", ("sample", "t_h")),
    }
    if params.has_cage:
        c = layout.cage_offset(Z, True)
        R_c = _crv_to_matrix(run.q[:, c + 3:c + 6])
        omega = np.einsum("nij,nj->ni", R_c, run.v[:, c + 3:c + 6])
        s.update({
            "cage/position": Series(run.q[:, c:c + 3], "m", "cage centre (guiding race at the origin)", V),
            "cage/velocity": Series(run.v[:, c:c + 3], "m/s", "cage centre velocity", V),
            "cage/angular_velocity": Series(omega, "rad/s", "cage angular velocity, global frame", V),
            "cage/speed": Series(omega[:, 2], "rad/s", "cage rotation speed about +z", T),
            "pocket/force": Series(per_ball[:, :, A.DB_POCKET], "N", "ball-pocket normal force", B, True),
            "cage_race/eccentricity_ratio": Series(d[:, A.DG_EPS], "-", "cage eccentricity / guide clearance", T),
            "cage_race/force": Series(d[:, A.DG_FX:A.DG_FY + 1], "N", "guide-land force on the cage (x, y)", ("time", "xy")),
            "cage_race/torque": Series(d[:, A.DG_TORQUE], "N.m", "guide-land torque on the cage about +z", T),
            "cage_race/metal_force": Series(d[:, A.DG_METAL], "N", "metal-to-metal normal force at the land", T),
            "cage_race/friction_power": Series(d[:, A.DG_FRICTION_POWER], "W", "metal-contact friction power (burn zone)", T),
            "cage_race/contact_azimuth": Series(d[:, A.DG_AZIMUTH], "rad", "azimuth of the land point facing the cage offset", T),
            "cage_race/film_power": Series(d[:, A.DG_FILM_POWER], "W", "viscous shear power of the land film (burn zone)", T),
            "cage_race/min_film": Series(d[:, A.DG_MIN_FILM], "m", "thinnest land film, C(1 + eps0) - e in the hybrid model", T),
        })
    return s


def write_impacts_csv(path: Path, impacts: np.ndarray, fields: tuple) -> None:
    units = {"time": "s", "ball": "-", "orbital_position": "rad", "peak_force": "N",
             "impact_speed": "m/s", "duration": "s"}
    buf = io.StringIO()
    buf.write(",".join(f"{f} [{units[f]}]" for f in fields) + "\n")
    for row in impacts:
        buf.write(",".join(str(int(x)) if f == "ball" else f"{x:.9g}" for f, x in zip(fields, row)) + "\n")
    atomic_write_text(path, buf.getvalue())


def land_boundary(scene) -> float:
    """eps0 of the land film, C_film = C (1 + eps0): physics.cage_race_boundary in the hybrid
    model, 0 in the purely hydrodynamic one (its film clearance is C)."""
    physics = scene.physics
    return float(physics.cage_race_boundary) if physics.cage_race == "hybrid" else 0.0


def land_roughness(scene) -> float:
    """Composite RMS roughness sigma of cage rim and land [m]: the scene's
    `cage.land_roughness` when it has one, else DEFAULT_LAND_ROUGHNESS (cage_metrics)."""
    value = getattr(scene.cage, "land_roughness", None) if scene.cage is not None else None
    return float(value) if value is not None else DEFAULT_LAND_ROUGHNESS


def guide_land_speed(scene) -> float:
    """Speed of the race whose land guides the cage [rad/s]: the inner race for an
    inner-guided cage, else the outer race, which the dynamic model keeps fixed."""
    return float(scene.speed.inner) if getattr(scene.cage, "guidance", "outer") == "inner" else 0.0


def write_simulation_results(out_dir: Path, scene, params, start, run, wall_time: float) -> dict:
    """Write all files of the simulate stage; return the summary dict."""
    from ..provenance import package_version

    series = collect_series(run, params)
    write_timeseries(out_dir / "timeseries.h5", series,
                     {"scene": scene.name, "bearingsim": package_version(),
                      "ball_count": params.ball_count, "guide_clearance_m": params.guide_clearance})
    write_impacts_csv(out_dir / "impacts.csv", run.impacts, run.impact_fields)
    stats = dict(run.stats)
    summary = {"duration": float(run.t[-1]), "wall_time": wall_time,
               "integration_wall_time": stats.pop("wall_time"), **stats,
               "energy": run.energy, "kinematic_cage_speed": float(start["cage_angular_speed"])}
    if params.has_cage:
        summary.update(cage_summary(
            run.t, series["cage/position"].data[:, :2], series["cage/speed"].data,
            series["cage_race/eccentricity_ratio"].data, series["cage_race/contact_azimuth"].data,
            series["cage_race/friction_power"].data, series["inner_race/position"].data[:, 2],
            run.impacts[:, 3] if len(run.impacts) else np.zeros(0),
            impact_times=run.impacts[:, 0] if len(run.impacts) else np.zeros(0),
            impact_orbital_positions=run.impacts[:, 2] if len(run.impacts) else np.zeros(0),
            film_power=series["cage_race/film_power"].data, min_film=series["cage_race/min_film"].data,
            land_force=series["cage_race/force"].data, metal_force=series["cage_race/metal_force"].data,
            guide_clearance=params.guide_clearance, land_boundary=land_boundary(scene),
            land_roughness=land_roughness(scene), land_film=scene.physics.cage_race in ("hybrid", "hydrodynamic"),
            land_speed=guide_land_speed(scene)))
        summary["verdict"] = cage_verdict(summary, guidance=getattr(scene.cage, "guidance", "outer"))
    else:
        summary["inner_race_axial_mean"] = float(np.mean(series["inner_race/position"].data[:, 2]))
    from .simulation_figures import draw_simulation_figures

    draw_simulation_figures(out_dir, series, run, params, start, scene.name)
    return summary
