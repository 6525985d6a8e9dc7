"""The run as files ParaView plays: the bodies' motion as time series and the land heat on
the guiding race's surface.

Written into `<run>/report/paraview/` from the saved `timeseries.h5` (nothing is solved):

- `balls.pvd` — the balls as points (ParaView: Glyph → Sphere, scale by `diameter`), with
  point data `velocity` [m/s], `angular_velocity` [rad/s] and every per-ball series of the
  run (`inner_load`, `outer_load` [N], `pocket_force` [N], contact angles [rad], films [m], ...);
- `cage.pvd` — the cage ring, moved by its centre and turned by its integrated speed, point
  data `velocity` [m/s] (rigid-body v + ω × r), field data `land_force` [N],
  `eccentricity_ratio`, `friction_power` [W];
- `inner_race.pvd` — the inner race's groove and lands, moved and tilted with the race,
  point data `velocity` [m/s];
- `inner_race_heat.vtp` — with an inner-guided cage, the inner race in its own frame with the
  land heat as cell data (as `outer_race.vtp` below for an outer-guided one);
- `outer_race.vtp` — the fixed outer race; with an outer-guided cage its cell data
  `land_heat` [J/m²] is the burn zone of the report (heat of the settled window per 1°
  sector spread over the cage's land overlap, `render.burn_zone_data`), `land_heat_metal`,
  `land_heat_film` its layers.

Each `.pvd` lists one `.vtp` per frame (`frames/`), at the sample's time [s]. The run's
samples are thinned to at most `frames` evenly spaced ones (the first and last kept), so the
files stay a few MB; every dataset carries a field-data string array `units`.
"""

from __future__ import annotations

import math
from pathlib import Path
from xml.sax.saxutils import quoteattr

import numpy as np

from ..results.named_arrays import udunits
from .vtk_files import save_xml

from .body_surfaces import (RevolvedSurface, axis_rotation, cage_surface, inner_race_surface,
                            outer_race_surface, spin_rotation)

PARAVIEW_DIR = "paraview"
DEFAULT_FRAMES = 200
MOTION_AZIMUTHS = 48  # sectors of a moving surface (small files); the heat surface uses the map's
MOTION_DATASETS = ("time", "balls/position", "balls/velocity", "balls/angular_velocity", "cage/position",
                   "cage/velocity", "cage/angular_velocity", "cage/speed", "cage_race/force",
                   "cage_race/eccentricity_ratio", "cage_race/friction_power", "inner_race/position",
                   "inner_race/velocity", "inner_race/axis", "inner_race/angular_velocity")


def frame_indices(samples: int, frames: int) -> np.ndarray:
    """At most `frames` (>= 2) evenly spaced sample indices, the first and the last included."""
    if samples <= frames:
        return np.arange(samples)
    return np.unique(np.round(np.linspace(0, samples - 1, frames)).astype(int))


def read_frames(path: Path, frames: int) -> tuple[dict, np.ndarray | None]:
    """The series of `timeseries.h5` over time, at the frames only (a long run's per-ball
    series are large), and the cage's turn angle [rad] at those frames, integrated from
    the full `cage/speed` (the run saves no cage angle); None without a cage."""
    import h5py

    from ..results.timeseries import Series

    out = {}
    with h5py.File(path, "r") as h5:
        t = h5["time"][()]
        keep = frame_indices(len(t), frames)
        angle = None
        if "cage/speed" in h5:
            speed = h5["cage/speed"][()].astype(float)
            angle = np.concatenate([[0.0], np.cumsum(0.5 * (speed[1:] + speed[:-1]) * np.diff(t))])[keep]

        def visit(name, ds):
            dims = tuple(str(ds.attrs.get("dims", "")).split(","))
            if isinstance(ds, h5py.Dataset) and dims[0] == "time" and ds.shape[0] == len(t):
                out[name] = Series(ds[keep], str(ds.attrs.get("units", "")), "", dims)

        h5.visititems(visit)
    return out, angle


def _polydata(points: np.ndarray, quads: np.ndarray | None = None):
    import pyvista as pv

    if quads is None:
        return pv.PolyData(np.asarray(points, dtype=np.float32))
    faces = np.hstack([np.full((len(quads), 1), 4), quads]).ravel()
    return pv.PolyData(np.asarray(points, dtype=np.float32), faces)


def _units(mesh, units: dict[str, str]) -> None:
    mesh.field_data["units"] = np.array([f"{k}={udunits(v)}" for k, v in units.items()])


def write_pvd(path: Path, entries: list[tuple[float, str]]) -> None:
    """A ParaView collection: one (time [s], file relative to `path`) per frame."""
    from ..staging.artefacts import atomic_write_text

    rows = "".join(f'    <DataSet timestep="{t:.9g}" group="" part="0" file={quoteattr(f)}/>\n' for t, f in entries)
    atomic_write_text(path, '<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1" byte_order="LittleEndian">\n'
                            f"  <Collection>\n{rows}  </Collection>\n</VTKFile>\n")


def _rigid(surface: RevolvedSurface, rotation: np.ndarray, centre: np.ndarray, velocity: np.ndarray,
           omega: np.ndarray):
    """The surface placed by (rotation, centre), point velocity v + ω × r."""
    arm = surface.points @ rotation.T
    mesh = _polydata(arm + centre, surface.quads)
    mesh.point_data["velocity"] = (velocity + np.cross(omega, arm)).astype(np.float32)
    return mesh


def _ball_fields(series: dict) -> dict[str, tuple[np.ndarray, str]]:
    """Per-ball series (time, ball[, xyz]) by their field name: `balls/velocity` -> velocity,
    `contacts/inner_load` -> inner_load, `pocket/force` -> pocket_force."""
    out = {}
    for name, s in series.items():
        if tuple(s.dims[:2]) != ("time", "ball") or name == "balls/position":
            continue
        group, _, leaf = name.partition("/")
        field = leaf if group in ("balls", "contacts") else f"{group}_{leaf}"
        out[field] = (np.asarray(s.data), s.units)
    return out


BODY_SERIES = {
    "balls": ("balls/position",),
    "inner_race": ("inner_race/position", "inner_race/velocity", "inner_race/axis", "inner_race/angular_velocity"),
    "cage": ("cage/position", "cage/velocity", "cage/angular_velocity"),
}


def write_motion(series: dict, scene, out_dir: Path, cage_angle: np.ndarray | None) -> dict[str, str]:
    """The `.pvd` series of the balls, the cage and the inner race (module docstring) from
    `series` at the frames (`read_frames`); a body whose series the run lacks is left out.
    Returns {body: file name}."""
    t = np.asarray(series["time"].data, dtype=float)
    (out_dir / "frames").mkdir(parents=True, exist_ok=True)
    has = {body: all(n in series for n in names) for body, names in BODY_SERIES.items()}
    written = {}
    if has["balls"]:
        written["balls"] = _write_balls(series, scene, t, out_dir)
    if has["inner_race"]:
        written["inner_race"] = _write_inner_race(series, scene, t, out_dir)
    if has["cage"] and scene.cage is not None and cage_angle is not None:
        written["cage"] = _write_cage(series, scene, t, cage_angle, out_dir)
    return written


def _write_inner_race(series: dict, scene, t: np.ndarray, out_dir: Path) -> str:
    inner = inner_race_surface(scene.operating.bearing, MOTION_AZIMUTHS)
    entries = []
    for i in range(len(t)):
        rotation = axis_rotation(series["inner_race/axis"].data[i])
        mesh = _rigid(inner, rotation, series["inner_race/position"].data[i], series["inner_race/velocity"].data[i],
                      series["inner_race/angular_velocity"].data[i])
        _units(mesh, {"velocity": "m/s"})
        name = f"frames/inner_race_{i:05d}.vtp"
        save_xml(mesh, out_dir / name)
        entries.append((t[i], name))
    write_pvd(out_dir / "inner_race.pvd", entries)
    return "inner_race.pvd"


def _write_balls(series: dict, scene, t: np.ndarray, out_dir: Path) -> str:
    fields = _ball_fields(series)
    position = np.asarray(series["balls/position"].data)
    entries = []
    for i in range(len(t)):
        mesh = _polydata(position[i])
        mesh.point_data["diameter"] = np.full(position.shape[1], scene.operating.bearing.ball_diameter, dtype=np.float32)
        mesh.point_data["ball"] = np.arange(position.shape[1], dtype=np.int32)
        for field, (data, _) in fields.items():
            mesh.point_data[field] = np.asarray(data[i], dtype=np.float32)
        _units(mesh, {"diameter": "m", "ball": "1", **{f: u for f, (_, u) in fields.items()}})
        name = f"frames/balls_{i:05d}.vtp"
        save_xml(mesh, out_dir / name)
        entries.append((t[i], name))
    write_pvd(out_dir / "balls.pvd", entries)
    return "balls.pvd"


def _write_cage(series: dict, scene, t: np.ndarray, angle: np.ndarray, out_dir: Path) -> str:
    """The cage ring, turned by `angle` [rad] about its axis at each frame."""
    ring = cage_surface(scene.operating.cage, MOTION_AZIMUTHS)
    force = np.asarray(series["cage_race/force"].data, dtype=float) if "cage_race/force" in series else None
    entries = []
    for i in range(len(t)):
        mesh = _rigid(ring, spin_rotation(angle[i]), series["cage/position"].data[i], series["cage/velocity"].data[i],
                      series["cage/angular_velocity"].data[i])
        mesh.cell_data["sector"] = (np.floor(ring.cell_azimuth / (2 * math.pi) * MOTION_AZIMUTHS)).astype(np.int32)
        if force is not None:
            mesh.field_data["land_force"] = np.r_[force[i], 0.0][None, :3].astype(np.float32)
        for key, field in (("cage_race/eccentricity_ratio", "eccentricity_ratio"),
                           ("cage_race/friction_power", "friction_power")):
            if key in series:
                mesh.field_data[field] = np.array([float(series[key].data[i])])
        _units(mesh, {"velocity": "m/s", "sector": "1", "land_force": "N", "eccentricity_ratio": "1",
                      "friction_power": "W"})
        name = f"frames/cage_{i:05d}.vtp"
        save_xml(mesh, out_dir / name)
        entries.append((t[i], name))
    series_file = "cage" + ".pvd"  # (two literals: "cage.<x>" reads as a scene key to the message checks)
    write_pvd(out_dir / series_file, entries)
    return series_file


def write_race(scene, out_dir: Path, burn_map=None, ring: str = "outer") -> str:
    """`outer_race.vtp`, or `inner_race_heat.vtp` (`ring` "inner"; the moving inner race is the
    `inner_race.pvd` series), in the ring's own frame, with the land heat
    of `burn_map` (render.burn_zone_data.BurnZoneMap) as cell data when there is one: J/m² over
    the cage's overlap with the guiding lands, 0 elsewhere."""
    sectors = burn_map.sectors if burn_map is not None else MOTION_AZIMUTHS
    surface = (outer_race_surface if ring == "outer" else inner_race_surface)(scene.operating.bearing, sectors,
                                                                              scene.operating.cage)
    mesh = _polydata(surface.points, surface.quads)
    units = {}
    if burn_map is not None:
        profile = burn_map.profile
        z = surface.cell_z
        on_land = np.zeros(z.shape, dtype=bool)
        for side in profile.land_sides:
            on_land |= (side * z > profile.z_land(side)) & (side * z < profile.cage_half_width)
        index = np.minimum((surface.cell_azimuth / (2 * math.pi) * sectors).astype(int), sectors - 1)
        density = burn_map.areal_density_factor
        layers = {"land_heat": burn_map.sector_energy, "land_heat_metal": burn_map.metal_energy,
                  "land_heat_film": burn_map.film_energy}
        for field, energy in layers.items():
            if energy is not None:
                mesh.cell_data[field] = np.where(on_land, np.asarray(energy)[index] * density, 0.0)
                units[field] = "J/m2"
        if burn_map.window is not None:
            mesh.field_data["window"] = np.asarray(burn_map.window, dtype=float)
            units["window"] = "s"
    _units(mesh, units)
    name = "outer_race.vtp" if ring == "outer" else "inner_race_heat.vtp"
    save_xml(mesh, out_dir / name)
    return name


def write_paraview(timeseries: Path, scene, out_dir: Path, frames: int = DEFAULT_FRAMES, burn_map=None) -> dict:
    """Everything of the module docstring from `timeseries` (a timeseries.h5) into
    `out_dir` (created); {what: file name}. `frames` = 0 writes the outer race only."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    files = {}
    if frames > 0:
        series, cage_angle = read_frames(Path(timeseries), max(2, frames))
        files = write_motion(series, scene, out_dir, cage_angle)
    on_inner = burn_map is not None and burn_map.profile.ring == "inner"
    files["outer_race"] = write_race(scene, out_dir, None if on_inner else burn_map)
    if on_inner:
        files["inner_race_heat"] = write_race(scene, out_dir, burn_map, "inner")
    return files
