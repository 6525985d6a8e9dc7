"""FE deflection renders of the identification load cases (docs/model.md §3, §11).

Input: the `case_<axis>.vtu` files of the identify stage (`fe_model/artefacts.py`):
cells (wedges: the section swept round the axis; or the tetrahedra of the engineer's mesh,
`fe.model = "mesh"`, with field data `reference_point` [m], where the cut passes) with point
data `displacement` [m] and cell data `von_mises` [Pa] and `material`. For each case one PNG, two panels of the same warped half model: |u| [µm]
and von Mises stress [MPa], each coloured from 0 to the case's maximum. The model is cut
by the plane through the bearing axis that contains the load's lateral direction (x-z
for fx, fz, my; y-z for fy, mx), so the bending of shaft and housing shows in the cut
face, and seen from a fixed camera derived from the undeformed mesh's bounds.

The warp scale is the largest 1-2-5 number keeping the largest displacement below 6 %
of the model's bounding-box diagonal; it is printed in the title and stored in the
`.vtu` written next to the PNG (`fe_<axis>.vtu`: the model's outer surface with
`displacement` [m], `displacement_magnitude` [m], `von_mises` [Pa] and `material`, and
field data `warp_scale` and `load` [N or N·m]), which opens in ParaView ("Warp By Vector" with that
scale reproduces the picture; the full volume fields stay in `identify/case_<axis>.vtu`).
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .offscreen import pyvista_offscreen, render_png
from .vtk_files import save_xml

WARP_FRACTION = 0.06  # largest warped displacement / bounding-box diagonal
SECTION_NORMAL = {"fx": "y", "fz": "y", "my": "y", "mz": "y", "fy": "x", "mx": "x"}
LOAD_UNIT = {"f": "N", "m": "N m"}
DISPLACEMENT_CMAP, STRESS_CMAP = "viridis", "plasma"


@dataclass(frozen=True)
class FECase:
    """One rendered load case: file, axis (fx ... my), applied load [N or N·m]."""

    path: Path
    axis: str
    load: float | None

    @property
    def label(self) -> str:
        if self.load is None:
            return f"load case {self.axis}"
        return f"load case {self.axis} = {self.load:+g} {LOAD_UNIT.get(self.axis[:1], '')}".rstrip()


def nice_scale(limit: float) -> float:
    """Largest 1, 2 or 5 × 10^k not above `limit` (> 0); 1 for a non-positive limit."""
    if not limit > 0.0 or not math.isfinite(limit):
        return 1.0
    exponent = math.floor(math.log10(limit))
    for mantissa in (5.0, 2.0, 1.0):
        value = mantissa * 10.0**exponent
        if value <= limit * (1.0 + 1e-12):
            return value
    return 10.0**exponent


def warp_scale(diagonal: float, max_displacement: float, fraction: float = WARP_FRACTION) -> float:
    """Warp factor so the largest displacement shows as ~`fraction` of the model size."""
    if max_displacement <= 0.0:
        return 1.0
    return nice_scale(fraction * diagonal / max_displacement)


def find_cases(identify_dir: Path) -> list[FECase]:
    """The `case_*.vtu` of an identify stage, with their loads from `hinge.toml` (the
    case of largest magnitude per axis, first of equals, as `identify_hinge` picks)."""
    identify_dir = Path(identify_dir)
    loads: dict[str, float] = {}
    hinge = identify_dir / "hinge.toml"
    if hinge.is_file():
        with open(hinge, "rb") as fh:
            doc = tomllib.load(fh)
        axes = ("fx", "fy", "fz", "mx", "my", "mz")
        for case in doc.get("cases", []):
            axis = str(case.get("name", "")).split("_")[0]
            if axis in axes and len(case.get("load", [])) > axes.index(axis):
                value = float(case["load"][axes.index(axis)])
                if axis not in loads or abs(value) > abs(loads[axis]):
                    loads[axis] = value
    cases = []
    for path in sorted(identify_dir.glob("case_*.vtu")):
        axis = path.stem[len("case_"):]
        cases.append(FECase(path, axis, loads.get(axis)))
    return cases


def prepare_case(mesh, case: FECase) -> dict:
    """Derived fields, warp scale and the cut half model of a case (no drawing)."""
    if "displacement" not in mesh.point_data:
        raise ValueError(f"{case.path}: no point array 'displacement' [m]; is this a case file "
                         "written by the identify stage (fe_model/artefacts.py)?")
    u = np.asarray(mesh.point_data["displacement"], dtype=float)
    magnitude = np.linalg.norm(u, axis=1)
    mesh.point_data["displacement_magnitude"] = magnitude
    mesh.point_data["displacement magnitude [µm]"] = magnitude * 1e6
    if "von_mises" in mesh.cell_data:
        mesh.cell_data["von Mises [MPa]"] = np.asarray(mesh.cell_data["von_mises"], dtype=float) / 1e6
    elif "von_mises" in mesh.point_data:
        mesh.point_data["von Mises [MPa]"] = np.asarray(mesh.point_data["von_mises"], dtype=float) / 1e6
    scale = warp_scale(mesh.length, float(magnitude.max(initial=0.0)))
    normal = SECTION_NORMAL.get(case.axis, "y")
    # keep the half facing the camera (see _camera): y > 0 for an x-z cut, x < 0 for y-z,
    # so that +x (or +y) points to the right in the picture
    keep = (0.0, -1.0, 0.0) if normal == "y" else (1.0, 0.0, 0.0)
    half = mesh.clip(normal=keep, origin=cut_origin(mesh), invert=True)
    return {"mesh": mesh, "half": half, "scale": scale, "normal": normal,
            "max_displacement": float(magnitude.max(initial=0.0)),
            "max_von_mises": float(np.max(mesh.cell_data["von_mises"], initial=0.0))
            if "von_mises" in mesh.cell_data else None}


def cut_origin(mesh) -> tuple[float, float, float]:
    """A point on the bearing axis for the cut: the reference point of a mesh-model case file
    (field data `reference_point`, the inner seat's centroid), else the model's centre (the
    axisymmetric assembly is centred on its axis)."""
    if "reference_point" in mesh.field_data:
        point = np.asarray(mesh.field_data["reference_point"], dtype=float).ravel()
        if point.size == 3 and np.isfinite(point).all():
            return tuple(float(v) for v in point)
    return tuple(float(v) for v in mesh.center)


def _camera(mesh, normal: str) -> list:
    """Fixed view of the cut face, a little off its normal and from above: from -y for the
    x-z cut (+x to the right), from +x for the y-z cut (+y to the right)."""
    cx, cy, cz = mesh.center
    d = 1.6 * mesh.length
    if normal == "x":
        eye = (cx + 0.85 * d, cy - 0.42 * d, cz + 0.42 * d)
    else:
        eye = (cx + 0.42 * d, cy - 0.85 * d, cz + 0.42 * d)
    return [eye, (cx, cy, cz), (0.0, 0.0, 1.0)]


def render_case(case: FECase, png_path: Path, vtu_path: Path | None, title: str = "",
                show: bool = False) -> dict:
    """Draw one load case (two panels: |u| and von Mises) and write its ParaView file."""
    pv = pyvista_offscreen()
    prep = prepare_case(pv.read(case.path), case)
    half, scale = prep["half"], prep["scale"]
    warped = half.warp_by_vector("displacement", factor=scale).extract_surface(algorithm=None)
    outline = half.extract_surface(algorithm=None).extract_feature_edges(
        feature_angle=30.0, boundary_edges=True, non_manifold_edges=False, manifold_edges=False)
    camera = _camera(prep["mesh"], prep["normal"])
    bounds = list(prep["mesh"].bounds)
    heading = (f"{title}\n" if title else "") + f"FE {case.label}, deformation x{scale:g}"
    fields = [("displacement magnitude [µm]", DISPLACEMENT_CMAP, prep["max_displacement"] * 1e6)]
    if "von Mises [MPa]" in half.array_names:
        fields.append(("von Mises [MPa]", STRESS_CMAP, (prep["max_von_mises"] or 0.0) / 1e6))

    def populate(plotter) -> None:
        for j, (name, cmap, top) in enumerate(fields):
            plotter.subplot(0, j)
            plotter.add_mesh(warped, scalars=name, cmap=cmap, clim=[0.0, top if top > 0.0 else 1.0],
                             scalar_bar_args={"title": name + "\n", "vertical": False, "fmt": "%.3g",
                                              "position_x": 0.2, "width": 0.6, "height": 0.08,
                                              "title_font_size": 16, "label_font_size": 14})
            plotter.add_mesh(outline, color="black", line_width=1, opacity=0.5)
            # placed in viewport coordinates, not as a corner text, which VTK shrinks to fit
            # its width: both panels' titles keep one size
            plotter.add_text(heading if j == 0 else "undeformed outline:\nthin black lines",
                             position=(0.01, 0.92), viewport=True, font_size=12)
            plotter.add_axes()
            plotter.camera_position = camera
            plotter.camera.view_angle = 30.0
            plotter.reset_camera(bounds=bounds)  # fit the undeformed model: same for all cases

    render_png(png_path, populate, shape=(1, len(fields)), window_size=(800 * len(fields), 800), show=show)
    if vtu_path is not None:
        write_case_surface(prep["mesh"], vtu_path, scale, case.load)
    return {"file": Path(png_path).name, "load_case": case.label, "warp_scale": scale,
            "max_displacement_m": prep["max_displacement"], "max_von_mises_Pa": prep["max_von_mises"]}


def write_case_surface(mesh, path: Path, scale: float, load: float | None) -> None:
    """The outer surface with SI fields, the warp scale and the load, for ParaView
    (numbers only in the field data: meshio cannot read string arrays). Atomic."""
    surface = mesh.extract_surface(algorithm=None).cast_to_unstructured_grid()
    for name in list(surface.array_names):
        if name not in ("displacement", "displacement_magnitude", "von_mises", "material"):
            surface.point_data.pop(name, None)
            surface.cell_data.pop(name, None)
    surface.field_data["warp_scale"] = [scale]
    if load is not None:
        surface.field_data["load"] = [load]  # N or N*m along the case's axis (file name)
    save_xml(surface, Path(path))  # atomic, and a full disk is an OSError (render.vtk_files)
