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
