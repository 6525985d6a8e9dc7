"""What is checked on the engineer's mesh before anything is assembled (docs/housing-mesh.md).

Every check runs on the mesh's arrays alone, so a wrong mesh is refused before any solve and
nothing is written. An error is a `MeshInputError` naming the scene key and the region; a
doubt is a warning (text) kept with the result.

- the regions named by fe.inner_seat, fe.outer_seat, fe.fixed and [fe.materials] exist, are
  non-empty and of the right kind (surface or volume); every tetrahedron has one material;
- each seat is where the bearing sits: a cylinder round an axis parallel to z whose radius lies
  within the ring's (a mesh in mm read as m puts it 1000 times too far out); its length is
  compared with the ring width, and a seat in several pieces is a warning;
- every connected body of the mesh touches the clamped region at three or more points not on
  one line, so the clamp removes all six rigid-body modes of each body exactly; a free body
  is named by its volume regions.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

# a seat's radius may lie this far outside the ring's radial extent: room for a sleeve or a
# raceway surface, while a wrong unit (a factor of 10 or more) is refused
SEAT_RADIUS_MARGIN = 0.2
# largest (max - min) / mean of a seat's facet radii round its axis: a cylinder faceted by
# its mesh stays far below; a seat round another axis (x or y) does not
SEAT_ROUNDNESS = 0.3
# a seat shorter than half or longer than twice the ring width is a warning
SEAT_LENGTH_RATIO = 2.0


class MeshInputError(ValueError):
    """A mesh that cannot be used as the scene describes it; `key` is the scene key to fix."""

    def __init__(self, key: str, message: str):
        self.key = key
        super().__init__(message)


@dataclass
class CheckedRegions:
    """The facets of the seats and the clamp, the reference point [m] and the warnings."""

    inner_seat: np.ndarray
    outer_seat: np.ndarray | None
    fixed: np.ndarray
    centre: np.ndarray
    warnings: list[tuple[str, str]] = field(default_factory=list)  # (scene key, message)
    seats: dict = field(default_factory=dict)  # what was measured on each seat (for hinge.toml)


def check_mesh(mesh, config, ring, default_outer_seat: str = "outer_seat") -> CheckedRegions:
    """Check the skfem `mesh` (subdomains, boundaries) against the `[fe]` config and the
    ring (fe_model.RingSeat). Raises MeshInputError; returns the regions to use."""
    have = sorted({*(mesh.subdomains or {}), *(mesh.boundaries or {})})
    boundaries = mesh.boundaries or {}
    warnings: list[tuple[str, str]] = []
    inner = _surface(mesh, "fe.inner_seat", config.inner_seat, have)
    fixed = _surface(mesh, "fe.fixed", config.fixed, have)
    outer = None
    if config.outer_seat in boundaries or config.outer_seat != default_outer_seat:
        outer = _surface(mesh, "fe.outer_seat", config.outer_seat, have)
    else:
        warnings.append(("fe.outer_seat", f"the mesh has no region {config.outer_seat!r}; the loads are reacted "
                        f"by the clamped region {config.fixed!r} and the hinge is measured against the ground, "
                        "so it includes the structure between the outer-ring seat and the clamp"))
    _check_materials(mesh, config, have)
    seats = {}
    r_in = (0.5 * ring.inner_bore_diameter, 0.5 * ring.inner_outer_diameter)
    seats["inner_seat"], centre = _check_seat(mesh, inner, "fe.inner_seat", config, ring, r_in,
                                              "bearing.inner_bore_diameter / 2 to bearing.inner_shoulder_diameter / 2",
                                              warnings)
    if outer is not None:
        r_out = (0.5 * ring.inner_outer_diameter, 0.5 * ring.outer_outside_diameter)
        seats["outer_seat"], _ = _check_seat(mesh, outer, "fe.outer_seat", config, ring, r_out,
                                             "bearing.inner_shoulder_diameter / 2 to "
                                             "bearing.outer_outside_diameter / 2", warnings)
    _check_clamp(mesh, fixed, config)
    return CheckedRegions(inner, outer, fixed, centre, warnings, seats)


def _surface(mesh, key: str, name: str, have: list[str]) -> np.ndarray:
    boundaries = mesh.boundaries or {}
    if name not in boundaries:
        kind = " (it is a volume region: name a surface)" if name in (mesh.subdomains or {}) else ""
        raise MeshInputError(key, f"{key} = {name!r}: the mesh has no surface region of that name{kind}; "
                                  f"its regions: {', '.join(have) or 'none'}")
    facets = np.asarray(boundaries[name])
    if facets.size == 0:
        raise MeshInputError(key, f"{key} = {name!r}: the region is empty (no face of the tetrahedra); "
                                  "export it as triangles on the volume mesh or as a node set of its nodes")
    return facets


def _check_materials(mesh, config, have: list[str]) -> None:
    subdomains = mesh.subdomains or {}
    owner = np.full(mesh.nelements, -1, dtype=np.int64)
    for k, material in enumerate(config.materials):
        key = f"fe.materials.{material.region}"
        if material.region not in subdomains:
            kind = " (it is a surface region: name a volume)" if material.region in (mesh.boundaries or {}) else ""
            raise MeshInputError(key, f"[{key}]: the mesh has no volume region {material.region!r}{kind}; its "
                                      f"regions: {', '.join(have) or 'none'}")
        cells = np.asarray(subdomains[material.region])
        if cells.size == 0:
            raise MeshInputError(key, f"[{key}]: the volume region {material.region!r} holds no tetrahedra")
        clash = cells[owner[cells] >= 0]
        if clash.size:
            other = config.materials[int(owner[clash[0]])].region
            raise MeshInputError(key, f"[{key}]: {clash.size} tetrahedra of {material.region!r} also belong to "
                                      f"{other!r}, which has a material too; give each tetrahedron one material")
        owner[cells] = k
    missing = np.flatnonzero(owner < 0)
    if missing.size:
        named = sorted(name for name, cells in subdomains.items() if np.isin(cells, missing).any())
        hint = f" (they belong to {', '.join(repr(n) for n in named)})" if named else " (they are in no volume region)"
        raise MeshInputError("fe.materials", f"[fe.materials]: {missing.size} of {mesh.nelements} tetrahedra have "
                                             f"no material{hint}; give a [fe.materials.<region>] table for each "
                                             "volume region")


def _facet_geometry(mesh, facets: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(centroids (F, 3) [m], areas (F,) [m^2]) of facets, from their corners."""
    p = mesh.p[:, mesh.facets[:, facets]]  # (3, 3 corners, F)
    centroids = p.mean(axis=1).T
    areas = 0.5 * np.linalg.norm(np.cross((p[:, 1] - p[:, 0]).T, (p[:, 2] - p[:, 0]).T), axis=1)
    return centroids, areas


def _check_seat(mesh, facets, key, config, ring, radii, meaning, warnings) -> tuple[dict, np.ndarray]:
    name = getattr(config, key.split(".")[1])
    centroids, areas = _facet_geometry(mesh, facets)
    centre = (centroids * areas[:, None]).sum(axis=0) / areas.sum()
    r = np.hypot(centroids[:, 0] - centre[0], centroids[:, 1] - centre[1])
    r_mean = float((r * areas).sum() / areas.sum())
    roundness = float(np.ptp(r) / r_mean) if r_mean > 0.0 else np.inf
    length = float(np.ptp(mesh.p[2, mesh.facets[:, facets]]))
    unit = config.mesh_unit
    if not roundness <= SEAT_ROUNDNESS:
        raise MeshInputError(key, f"{key} = {name!r} is not a cylinder round an axis parallel to z (its faces lie "
                                  f"at {r.min():.4g} to {r.max():.4g} m from the axis through its centroid); the "
                                  "mesh's axes must be the scene's, z along the bearing axis, and the seat a full "
                                  "cylinder round it")
    lo, hi = (1.0 - SEAT_RADIUS_MARGIN) * radii[0], (1.0 + SEAT_RADIUS_MARGIN) * radii[1]
    if not lo <= r_mean <= hi:
        from .config import MESH_UNITS

        fits = [u for u, f in MESH_UNITS.items() if lo <= r_mean / MESH_UNITS[unit] * f <= hi]
        hint = (f"with fe.mesh_unit = {fits[0]!r} it would be {r_mean / MESH_UNITS[unit] * MESH_UNITS[fits[0]]:.4g} m, "
                "on the ring" if fits else "no length unit puts it on the ring: is it the right region?")
        raise MeshInputError(key, f"{key} = {name!r} has radius {r_mean:.4g} m (coordinates read in "
                                  f"fe.mesh_unit = {unit!r}), but the ring sits at {radii[0]:.4g} to {radii[1]:.4g} m "
                                  f"({meaning}): the ring is not on this seat; {hint}")
    if not ring.width / SEAT_LENGTH_RATIO <= length <= SEAT_LENGTH_RATIO * ring.width:
        warnings.append((key, f"{name!r} is {length:.4g} m long, the ring {ring.width:.4g} m wide "
                              "(bearing.width): check that the region is the seat of the ring"))
    pieces = _pieces(mesh, facets)
    if pieces > 1:
        warnings.append((key, f"{name!r} is in {pieces} separate pieces: the coupling spreads the loads over "
                              "all of them; check that the region is the seat alone"))
    return {"region": name, "radius_m": r_mean, "length_m": length, "area_m2": float(areas.sum()),
            "centroid_m": centre.tolist(), "pieces": pieces}, centre


def _pieces(mesh, facets: np.ndarray) -> int:
    """Connected pieces of a set of facets (facets sharing a corner are connected)."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    corners = mesh.facets[:, facets]
    n = facets.size
    incidence = coo_matrix((np.ones(corners.size), (np.tile(np.arange(n), 3), corners.ravel())),
                           shape=(n, mesh.nvertices)).tocsr()
    return int(connected_components(incidence @ incidence.T, directed=False)[0])


def _check_clamp(mesh, fixed: np.ndarray, config) -> None:
    """Each connected body must touch the clamp at >= 3 points not on one line."""
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    t = mesh.t[:4]
    rows = np.repeat(t, 4, axis=0).ravel()
    cols = np.tile(t, (4, 1)).ravel()
    graph = coo_matrix((np.ones(rows.size, dtype=np.int8), (rows, cols)), shape=(mesh.nvertices,) * 2)
    n_bodies, body_of_vertex = connected_components(graph, directed=False)
    clamped = np.unique(mesh.facets[:, fixed])
    for body in range(n_bodies):
        vertices = np.flatnonzero(body_of_vertex == body)
        if vertices.size == 0:
            continue
        points = mesh.p[:, np.intersect1d(vertices, clamped)]
        if points.shape[1] >= 3:
            spread = points - points.mean(axis=1, keepdims=True)
            s = np.linalg.svd(spread, compute_uv=False)
            if s[1] > 1e-6 * s[0]:
                continue
        cells = np.flatnonzero(body_of_vertex[t[0]] == body)
        regions = sorted(name for name, c in (mesh.subdomains or {}).items() if np.isin(c, cells).any())
        named = ", ".join(repr(r) for r in regions) or "no named region"
        raise MeshInputError("fe.fixed", f"fe.fixed = {config.fixed!r}: the body made of {named} ({cells.size} "
                                         f"tetrahedra) touches the clamped region at {points.shape[1]} nodes, too few "
                                         "to hold it (three or more not on one line): it is free, with rigid-body "
                                         "modes. Clamp a face of it in that region, or bond it to its neighbour (a "
                                         "mesh that shares the nodes on the interface: Gmsh 'fragment', Abaqus merged "
                                         "nodes)")
