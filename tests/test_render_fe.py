"""FE deflection renders on a tiny cantilever mesh written like the identify stage's files."""

from __future__ import annotations

import math

import numpy as np
import pytest

from bearingsim.pipeline.render.fe_deflection import FECase, find_cases, nice_scale, render_case, warp_scale

LENGTH, SIDE = 0.1, 0.02  # m


def write_tiny_case(path, tip_deflection: float, stress: float = 1e6) -> None:
    """Quadratic tetrahedra (VTK tetra10, as fe_model/artefacts.py writes them) of a
    0.1 × 0.02 × 0.02 m beam along z with the cantilever shape u_x = w (z/L)^2."""
    import meshio
    from skfem import MeshTet

    mesh = MeshTet.init_tensor(np.linspace(-SIDE / 2, SIDE / 2, 3), np.linspace(-SIDE / 2, SIDE / 2, 3),
                               np.linspace(0.0, LENGTH, 6))
    points = np.vstack([mesh.p.T, 0.5 * (mesh.p[:, mesh.edges[0]] + mesh.p[:, mesh.edges[1]]).T])
    cells = [("tetra10", np.vstack([mesh.t, mesh.nvertices + mesh.t2e]).T)]
    u = np.zeros_like(points)
    u[:, 0] = tip_deflection * (points[:, 2] / LENGTH) ** 2
    centroid_z = points[cells[0][1][:, :4], 2].mean(axis=1)
    vm = stress * (1.0 - centroid_z / LENGTH)  # bending stress largest at the root
    meshio.Mesh(points, cells, point_data={"displacement": u},
                cell_data={"von_mises": [vm], "material": [np.ones(len(vm), dtype=np.int32)]}
                ).write(path, file_format="vtu", compression=None)


def test_nice_scale_and_warp_scale():
    # 1-2-5 series floor: values follow from the definition
    assert nice_scale(3.7e3) == 2e3 and nice_scale(5e3) == 5e3 and nice_scale(0.99) == 0.5
    assert nice_scale(1.0) == 1.0 and nice_scale(0.0) == 1.0 and nice_scale(float("nan")) == 1.0
    for umax in (1e-7, 3.3e-6, 2e-5, 1e-3):
        s = warp_scale(0.5, umax)
        # warped displacement within (0.4, 1] of 6 % of the diagonal (1-2-5 steps <= 2.5x)
        assert 0.4 * 0.06 * 0.5 < s * umax <= 0.06 * 0.5 * (1 + 1e-12)
    assert warp_scale(0.5, 0.0) == 1.0


def test_find_cases_reads_loads_from_hinge_toml(tmp_path):
    write_tiny_case(tmp_path / "case_fx.vtu", 1e-6)
    write_tiny_case(tmp_path / "case_my.vtu", 1e-6)
    (tmp_path / "hinge.toml").write_text(
        '[hinge]\ntranslational = [1.0, 1.0, 1.0]\nbending = [1.0, 1.0]\n'
        '[[cases]]\nname = "fx_-1000"\nload = [-1000.0, 0, 0, 0, 0, 0]\n'
        '[[cases]]\nname = "fx_+500"\nload = [500.0, 0, 0, 0, 0, 0]\n'
        '[[cases]]\nname = "fx_+1000"\nload = [1000.0, 0, 0, 0, 0, 0]\n'
        '[[cases]]\nname = "my_+250"\nload = [0, 0, 0, 0, 250.0, 0]\n')
    cases = find_cases(tmp_path)
    assert [(c.axis, c.load) for c in cases] == [("fx", -1000.0), ("my", 250.0)]  # first of equals
    assert cases[1].label == "load case my = +250 N m"


def _image(path):
    import matplotlib.image as mpimg

    return mpimg.imread(path)[..., :3]


def test_render_case_draws_and_writes_paraview_file(tmp_path):
    import meshio

    write_tiny_case(tmp_path / "case_fx.vtu", 2e-6)
    write_tiny_case(tmp_path / "case_fy.vtu", 0.0, stress=0.0)  # unloaded: no warp, no crash
    a = render_case(FECase(tmp_path / "case_fx.vtu", "fx", 1000.0), tmp_path / "a.png", tmp_path / "a.vtu", "t")
    b = render_case(FECase(tmp_path / "case_fx.vtu", "fx", 1000.0), tmp_path / "b.png", None, "t")
    z = render_case(FECase(tmp_path / "case_fy.vtu", "fy", 0.0), tmp_path / "z.png", None, "t")
    assert a["max_displacement_m"] == pytest.approx(2e-6, rel=1e-12)  # the tip value written
    # warp: 6 % of the diagonal sqrt(0.1² + 2·0.02²), rounded down in the 1-2-5 series
    assert a["warp_scale"] == nice_scale(0.06 * math.sqrt(LENGTH**2 + 2 * SIDE**2) / 2e-6) == 2000.0
    assert z["warp_scale"] == 1.0
    img_a, img_b, img_z = _image(tmp_path / "a.png"), _image(tmp_path / "b.png"), _image(tmp_path / "z.png")
    assert (img_a < 0.9).mean() > 0.02  # something drawn
    assert np.array_equal(img_a, img_b)  # fixed camera: the same case renders identically
    assert np.abs(img_a - img_z).max(axis=2).mean() > 0.01  # other data, other picture
    surface = meshio.read(tmp_path / "a.vtu")
    assert {"displacement", "displacement_magnitude"} <= set(surface.point_data)
    assert "von_mises" in surface.cell_data
    assert np.max(surface.point_data["displacement_magnitude"]) == pytest.approx(2e-6, rel=1e-6)
    assert float(surface.field_data["warp_scale"][0]) == 2000.0


def test_render_case_reads_the_identify_stage_view(tmp_path):
    """The identify stage's own files (the axisymmetric solution on revolved wedges, zlib,
    float32) render like any case: the largest displacement drawn is the file's."""
    import dataclasses

    import meshio

    from bearingsim.fe_model import FEConfig, RingSeat, identify_hinge

    config = dataclasses.replace(FEConfig(), mesh_size=0.03, edge_refinement=1.0)
    identify_hinge(config, RingSeat(), tmp_path)
    case = find_cases(tmp_path)[-1]
    assert case.axis == "my" and case.load == -1000.0  # largest magnitude, first of equals
    record = render_case(case, tmp_path / "my.png", tmp_path / "my_surface.vtu", "t")
    u = meshio.read(case.path).point_data["displacement"].astype(float)
    assert record["max_displacement_m"] == pytest.approx(np.linalg.norm(u, axis=1).max(), rel=1e-6)
    assert record["max_von_mises_Pa"] > 0
    assert (_image(tmp_path / "my.png") < 0.9).mean() > 0.02
