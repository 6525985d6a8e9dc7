"""gmsh geometry and mesh transfer: groups, measures, determinism, caching."""

import math

import numpy as np
import pytest
from skfem import Basis, ElementTetP1, FacetBasis, Functional

from bearingsim.fe_model import FEConfig, RingSeat
from bearingsim.meshes import MeshData, build_housing_mesh, cached_housing_mesh

SIZE = 0.03  # coarse: these tests are about topology and groups, not accuracy


@pytest.fixture(scope="module")
def housing() -> MeshData:
    return build_housing_mesh(FEConfig().housing_geometry(RingSeat()), SIZE)


def _area(mesh, group):
    fb = FacetBasis(mesh, ElementTetP1(), facets=mesh.boundaries[group])
    return Functional(lambda w: 1.0 + 0 * w.x[0]).assemble(fb)


def _volume(mesh, group):
    b = Basis(mesh, ElementTetP1(), elements=mesh.subdomains[group])
    return Functional(lambda w: 1.0 + 0 * w.x[0]).assemble(b)


def test_all_physical_groups_exist_and_volumes_partition_the_mesh(housing):
    assert set(housing.volumes) == {"shaft", "inner_ring", "support_a", "support_b", "housing"}
    assert set(housing.surfaces) == {"inner_ring_bore", "inner_ring_seat", "inner_ring_race", "outer_ring_seat",
                                     "support_a", "support_b", "housing_flange"}
    all_elements = np.sort(np.concatenate(list(housing.volumes.values())))
    np.testing.assert_array_equal(all_elements, np.arange(housing.n_elements))


def test_group_measures_match_the_drawn_dimensions(housing):
    """Areas/volumes of cylinders meshed with flat facets: the inscribed polygon loses
    about (pi h / (2 pi r))^2 / 6 of the perimeter (< 1 % here), hence the tolerance."""
    mesh = housing.to_skfem()
    ring, cfg = RingSeat(), FEConfig()
    r_b, r_o, B = 0.5 * ring.inner_bore_diameter, 0.5 * ring.inner_outer_diameter, ring.width
    assert _area(mesh, "inner_ring_race") == pytest.approx(2 * math.pi * r_o * B, rel=0.01)
    assert _area(mesh, "inner_ring_bore") == pytest.approx(2 * math.pi * r_b * B, rel=0.01)
    assert _area(mesh, "outer_ring_seat") == pytest.approx(math.pi * ring.outer_outside_diameter * B, rel=0.01)
    assert _area(mesh, "support_a") == pytest.approx(2 * math.pi * r_b * cfg.support_width, rel=0.01)
    flange = math.pi * (0.25 * cfg.housing_flange_diameter**2 - 0.25 * ring.outer_outside_diameter**2)
    assert _area(mesh, "housing_flange") == pytest.approx(flange, rel=0.01)
    assert _volume(mesh, "inner_ring") == pytest.approx(math.pi * (r_o**2 - r_b**2) * B, rel=0.02)


def test_interior_interface_survives_the_transfer(housing):
    """inner_ring_bore lies between ring and shaft: each of its facets has two elements."""
    mesh = housing.to_skfem()
    facets = mesh.boundaries["inner_ring_bore"]
    assert facets.size > 0
    assert np.all(mesh.f2t[1, facets] >= 0)
    ring_elements = set(mesh.subdomains["inner_ring"].tolist())
    shaft_elements = set(mesh.subdomains["shaft"].tolist())
    for f in facets[:20]:
        pair = set(mesh.f2t[:, f].tolist())
        assert pair & ring_elements and pair & shaft_elements


def test_meshing_is_deterministic(housing):
    again = build_housing_mesh(FEConfig().housing_geometry(RingSeat()), SIZE)
    np.testing.assert_array_equal(again.points, housing.points)
    np.testing.assert_array_equal(again.tets, housing.tets)
    for name in housing.surfaces:
        np.testing.assert_array_equal(again.surfaces[name], housing.surfaces[name])


def test_mesh_cache_round_trip(tmp_path):
    geometry = FEConfig().housing_geometry(RingSeat())
    first, path, reused = cached_housing_mesh(geometry, 0.04, tmp_path)
    second, path2, reused2 = cached_housing_mesh(geometry, 0.04, tmp_path)
    assert (reused, reused2) == (False, True) and path == path2
    np.testing.assert_array_equal(first.tets, second.tets)
    assert set(first.volumes) == set(second.volumes)
    _, path3, _ = cached_housing_mesh(geometry, 0.045, tmp_path)
    assert path3 != path  # a different size is a different artefact


# --- meridian section (the axisymmetric model's mesh) ------------------------------------------

@pytest.fixture(scope="module")
def section():
    from bearingsim.meshes.housing import build_section_mesh

    return build_section_mesh(FEConfig().housing_geometry(RingSeat()), 0.01, 0.05)


def test_section_groups_partition_and_measure_the_drawn_body(section):
    """Straight-sided triangles draw the rectangles of the section exactly, so the measures of
    revolution 2 pi int r are exact to round-off."""
    from skfem import Basis, ElementTriP1, FacetBasis, Functional

    assert set(section.volumes) == {"shaft", "inner_ring", "support_a", "support_b", "housing"}
    assert set(section.surfaces) == {"inner_ring_bore", "inner_ring_seat", "inner_ring_race", "outer_ring_seat",
                                     "support_a", "support_b", "housing_flange"}
    np.testing.assert_array_equal(np.sort(np.concatenate(list(section.volumes.values()))),
                                  np.arange(section.n_elements))
    mesh, ring, cfg = section.to_skfem(), RingSeat(), FEConfig()
    revolve = Functional(lambda w: 2 * math.pi * w.x[0])
    r_b, r_o, B = 0.5 * ring.inner_bore_diameter, 0.5 * ring.inner_outer_diameter, ring.width
    area = {g: revolve.assemble(FacetBasis(mesh, ElementTriP1(), facets=mesh.boundaries[g])) for g in mesh.boundaries}
    assert area["inner_ring_race"] == pytest.approx(2 * math.pi * r_o * B, rel=1e-12)
    assert area["inner_ring_bore"] == pytest.approx(2 * math.pi * r_b * B, rel=1e-12)
    assert area["outer_ring_seat"] == pytest.approx(math.pi * ring.outer_outside_diameter * B, rel=1e-12)
    assert area["support_b"] == pytest.approx(2 * math.pi * r_b * cfg.support_width, rel=1e-12)
    flange = math.pi * (0.25 * cfg.housing_flange_diameter**2 - 0.25 * ring.outer_outside_diameter**2)
    assert area["housing_flange"] == pytest.approx(flange, rel=1e-12)
    ring_volume = revolve.assemble(Basis(mesh, ElementTriP1(), elements=mesh.subdomains["inner_ring"]))
    assert ring_volume == pytest.approx(math.pi * (r_o**2 - r_b**2) * B, rel=1e-12)
    d1, d2 = (section.points[section.triangles[:, k]] - section.points[section.triangles[:, 0]] for k in (1, 2))
    assert np.all(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0] > 0)  # counter-clockwise in (r, z)


def test_section_meshing_is_deterministic_and_cached(section, tmp_path):
    from bearingsim.meshes.cache import cached_section_mesh
    from bearingsim.meshes.housing import build_section_mesh

    geometry = FEConfig().housing_geometry(RingSeat())
    again = build_section_mesh(geometry, 0.01, 0.05)
    np.testing.assert_array_equal(again.points, section.points)
    np.testing.assert_array_equal(again.triangles, section.triangles)
    first, path, reused = cached_section_mesh(geometry, 0.01, tmp_path, 0.05)
    second, path2, reused2 = cached_section_mesh(geometry, 0.01, tmp_path, 0.05)
    assert (reused, reused2) == (False, True) and path == path2 and path.name.startswith("section-")
    np.testing.assert_array_equal(second.triangles, section.triangles)
    for name in section.surfaces:
        np.testing.assert_array_equal(second.surfaces[name], section.surfaces[name])
    assert cached_section_mesh(geometry, 0.01, tmp_path, 0.1)[1] != path  # other grading, other artefact
    _, tets_path, _ = cached_housing_mesh(geometry, 0.04, tmp_path)
    assert tets_path.name.startswith("mesh-")


def test_revolved_tetrahedra_are_conforming_and_keep_the_groups(section):
    """Sweeping the section through 16 sectors: every group survives, the mesh is conforming
    (to_skfem matches each surface triangle to a facet) and measures are those of the
    inscribed polygons, sin(2 pi / n) / (2 pi / n) for areas of the section swept round."""
    from skfem import Basis, ElementTetP1, Functional

    from bearingsim.meshes.section import revolve_to_tets

    sectors = 16
    tets = revolve_to_tets(section, sectors)
    mesh = tets.to_skfem()
    assert set(mesh.boundaries) == set(section.surfaces) and set(mesh.subdomains) == set(section.volumes)
    ring = RingSeat()
    r_b, r_o, B = 0.5 * ring.inner_bore_diameter, 0.5 * ring.inner_outer_diameter, ring.width
    volume = Functional(lambda w: 1.0 + 0 * w.x[0]).assemble(
        Basis(mesh, ElementTetP1(), elements=mesh.subdomains["inner_ring"]))
    polygon = math.sin(2 * math.pi / sectors) / (2 * math.pi / sectors)
    assert volume == pytest.approx(math.pi * (r_o**2 - r_b**2) * B * polygon, rel=1e-10)
    interface = mesh.boundaries["inner_ring_bore"]
    assert np.all(mesh.f2t[1, interface] >= 0)  # interior: two tetrahedra each


def test_revolved_wedges_have_positive_vtk_volume(section):
    """VTK's wedge: base (0, 1, 2) with its right-hand normal pointing away from (3, 4, 5)."""
    from bearingsim.meshes.section import revolved_points, revolved_wedges

    points = revolved_points(section.points, 8)
    wedges = revolved_wedges(section.triangles, section.n_nodes, 8)
    p = points[wedges]
    normal = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    towards_top = p[:, 3:].mean(axis=1) - p[:, :3].mean(axis=1)
    assert np.all(np.einsum("ij,ij->i", normal, towards_top) < 0)
