"""Stage-1 artefacts: hinge.toml (values with units, fit quality, mesh statistics) and
one .vtu per load case (displacement, von Mises stress). Written atomically."""

from __future__ import annotations

import os
import pathlib
import tempfile
import tomllib
from dataclasses import dataclass

import numpy as np

HEADER = """\
# Viscoelastic hinge identified by FE (bearingsim stage 1, docs/model.md §3, fit M.2).
# [hinge] holds the scene's [hinge] keys: paste it into a scene with source = "given".
# translational: H_u [N/m], 3x3 symmetric; bending: H_psi [N m/rad] about x and y ([units]).
"""


def atomic_write_bytes(path: pathlib.Path, data: bytes) -> None:
    """Write to a temp file in the same directory, then rename over `path`."""
    path = pathlib.Path(path)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=path.name, suffix=".tmp")
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)


def write_hinge_toml(path: pathlib.Path, H_u: np.ndarray, H_psi: np.ndarray, meta: dict) -> None:
    """hinge.toml: [hinge] values, [units] theirs, then the tables of `meta` (fit, mesh, ...)."""
    import tomli_w

    doc = {
        "hinge": {
            "source": "fe",
            "translational": np.asarray(H_u, dtype=float).tolist(),
            "bending": np.asarray(H_psi, dtype=float).tolist(),
        },
        # apart from [hinge], which then pastes into a scene as it is; UDUNITS (docs/outputs.md)
        "units": {"translational": "N/m", "bending": "N m/rad"},
    }
    doc.update(_plain(meta))
    atomic_write_bytes(path, (HEADER + tomli_w.dumps(doc)).encode())


def read_hinge(path: pathlib.Path) -> tuple[np.ndarray, np.ndarray, dict]:
    """(H_u (3, 3) [N/m], H_psi (2,) [N*m/rad], everything else) from a hinge.toml."""
    with open(path, "rb") as fh:
        doc = tomllib.load(fh)
    hinge = doc.get("hinge", {})
    try:
        H_u = np.array(hinge["translational"], dtype=float)
        H_psi = np.array(hinge["bending"], dtype=float)
    except KeyError as err:
        raise ValueError(f"{path}: [hinge] lacks {err.args[0]!r}; is this a hinge.toml?") from None
    if H_u.shape == (3,):
        H_u = np.diag(H_u)
    if H_u.shape != (3, 3) or H_psi.shape != (2,):
        raise ValueError(f"{path}: translational must be 3 or 3x3 and bending 2 values [N/m, N*m/rad]")
    return H_u, H_psi, {k: v for k, v in doc.items() if k != "hinge"}


def _plain(value):
    """numpy -> TOML-able python (tomli_w knows no numpy types and no None)."""
    if isinstance(value, dict):
        return {str(k): _plain(v) for k, v in value.items() if v is not None}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, np.ndarray):
        return _plain(value.tolist())
    if isinstance(value, np.generic):
        return value.item()
    return value


def von_mises(model, u: np.ndarray) -> np.ndarray:
    """Von Mises stress [Pa] at each element centroid from the vector dof array u [m]."""
    from skfem import Basis

    centroid = (np.full((3, 1), 0.25), np.array([1.0 / 6.0]))
    basis = Basis(model.mesh, model.basis.elem, quadrature=centroid)
    U = u.reshape(-1, 3)
    grad = np.stack([basis.interpolate(U[:, c]).grad[:, :, 0] for c in range(3)])  # (3, 3, E)
    eps = 0.5 * (grad + grad.transpose(1, 0, 2))
    tr = np.trace(eps)
    sigma = 2.0 * model.mu * eps + model.lam * tr * np.eye(3)[:, :, None]
    dev = sigma - np.trace(sigma) / 3.0 * np.eye(3)[:, :, None]
    return np.sqrt(1.5 * np.einsum("ije,ije->e", dev, dev))


def write_case_vtu(path: pathlib.Path, model, u: np.ndarray, material_id: np.ndarray,
                   field_data: dict | None = None) -> None:
    """One load case of the 3-D model: quadratic (or linear) tetrahedra, point displacement,
    cell stress; `field_data` (name -> numbers) for ParaView and the renders."""
    basis = model.basis
    U = u.reshape(-1, 3)
    # the dofs are the nodes: P1 the vertices; P2 the vertices, then one node per edge, skfem's
    # local edge order (01, 12, 02, 03, 13, 23) being VTK's tetra10 order (curved edges included)
    cell_type = "tetra10" if basis.elem.__class__.__name__ == "ElementTetP2" else "tetra"
    write_vtu(path, basis.doflocs.T, (cell_type, basis.element_dofs.T), {"displacement": U},
              {"von_mises": von_mises(model, u), "material": material_id}, field_data=field_data)


# Volume .vtu of the axisymmetric model: a uniform section mesh of VIEW_WALL_FRACTION x the
# thinnest wall swept through VIEW_SECTORS sectors into wedges (what the renders and ParaView
# need; the solution itself lives on the graded section mesh and is interpolated onto it).
VIEW_SECTORS = 40
VIEW_WALL_FRACTION = 0.4


@dataclass
class RevolvedView:
    """The body of revolution as wedges, with what it takes to put a case's fields on it."""

    solution: object  # axisymmetric.HarmonicSolution
    points: np.ndarray  # (S P, 3) m
    wedges: np.ndarray  # (S E, 6)
    material: np.ndarray  # (S E,) int32
    nodes: object  # SectionProbe at the section nodes
    centroids: object  # SectionProbe at the section triangles' centroids
    sectors: int

    @classmethod
    def of(cls, solution, geometry, cache_dir: pathlib.Path, material_ids: dict[str, int],
           sectors: int = VIEW_SECTORS) -> "RevolvedView":
        """The view of `solution` on the housing `geometry` (its section mesh cached in
        `cache_dir`); `material_ids` maps a part name to the cell data `material`."""
        from .axisymmetric import SectionProbe
        from ..meshes.cache import cached_section_mesh
        from ..meshes.housing import thinnest_wall
        from ..meshes.section import revolved_points, revolved_wedges

        section, _, _ = cached_section_mesh(geometry, VIEW_WALL_FRACTION * thinnest_wall(geometry), cache_dir)
        part = np.zeros(section.n_elements, dtype=np.int32)
        for name, tris in section.volumes.items():
            part[tris] = material_ids.get(name, 0)
        centroids = section.points[section.triangles].mean(axis=1)
        return cls(solution, revolved_points(section.points, sectors),
                   revolved_wedges(section.triangles, section.n_nodes, sectors), np.tile(part, sectors),
                   SectionProbe(solution.model, section.points), SectionProbe(solution.model, centroids), sectors)

    def fields(self, load: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(displacement (S P, 3) [m], von Mises (S E,) [Pa]) of a load (F, M) [N, N*m]:
        displacement at the nodes, stress at the centroid of each wedge (mid-sector angle)."""
        angles = 2.0 * np.pi * np.arange(self.sectors) / self.sectors
        model, cells = self.solution.model, self.centroids.cells
        u = self.solution.displacement(self.nodes, angles, load)
        vm = self.solution.von_mises(self.centroids, angles + np.pi / self.sectors, load,
                                     model.lam[cells], model.mu[cells])
        return u, vm


def write_revolved_case_vtu(path: pathlib.Path, view: RevolvedView, load: np.ndarray) -> None:
    """One load case of the axisymmetric model on its revolved view: wedges, point
    displacement, cell von Mises stress and material."""
    u, vm = view.fields(load)
    write_vtu(path, view.points, ("wedge", view.wedges), {"displacement": u},
              {"von_mises": vm, "material": view.material})


def write_vtu(path: pathlib.Path, points, cells: tuple[str, np.ndarray], point_data: dict, cell_data: dict,
              compression: str | None = "zlib", field_data: dict | None = None) -> None:
    """A volume .vtu, written atomically (temp file in the same directory, then rename).
    Real arrays are stored as float32 (7 digits: plenty for ParaView and the renders; half
    the bytes), connectivity as int32."""
    import meshio

    def compact(a):
        a = np.asarray(a)
        return a.astype(np.float32) if a.dtype.kind == "f" else a.astype(np.int32) if a.dtype.kind in "iu" else a

    out = meshio.Mesh(compact(points), [(cells[0], compact(cells[1]))],
                      point_data={k: compact(v) for k, v in point_data.items()},
                      cell_data={k: [compact(v)] for k, v in cell_data.items()},
                      field_data={k: np.atleast_1d(np.asarray(v, dtype=float)) for k, v in (field_data or {}).items()})
    path = pathlib.Path(path)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=path.name, suffix=".tmp.vtu")
    os.close(fd)
    try:
        out.write(tmp, file_format="vtu", compression=compression)
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)
