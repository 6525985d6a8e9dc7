"""Stage 1 end to end on a coarse mesh: artefacts, round trip, physical sanity."""

import dataclasses

import meshio
import numpy as np
import pytest

from bearingsim.fe_model import FEConfig, RingSeat, identify_hinge, read_hinge


@pytest.fixture(scope="module")
def identified(tmp_path_factory):
    out = tmp_path_factory.mktemp("fe")
    config = dataclasses.replace(FEConfig(), mesh_size=0.025, edge_refinement=1.0, perturbation_forces=(-1000.0, 400.0),
                                 perturbation_moments=(-1000.0, 400.0))
    stages = []
    result = identify_hinge(config, RingSeat(), out, progress=lambda s, f: stages.append((s, f)))
    return config, out, result, stages


def test_artefacts_are_written_and_hinge_toml_round_trips(identified):
    _, out, result, stages = identified
    assert (out / "hinge.toml").exists()
    for axis in ("fx", "fy", "fz", "mx", "my"):
        assert (out / f"case_{axis}.vtu").exists()
    H_u, H_psi, meta = read_hinge(out / "hinge.toml")
    np.testing.assert_array_equal(H_u, result.H_u)
    np.testing.assert_array_equal(H_psi, result.H_psi)
    assert meta["mesh"]["dofs"] == result.mesh_stats["dofs"] > 0
    assert meta["fit"]["condition_number"] == result.condition_number
    assert not list(out.glob("*.tmp*"))  # atomic writes leave nothing behind
    fractions = [f for _, f in stages]
    assert fractions == sorted(fractions) and stages[-1] == ("done", 1.0)


def test_vtu_holds_displacement_and_stress(identified):
    """The axisymmetric solution on its revolved view: wedges of the whole body, compressed."""
    _, out, result, _ = identified
    mesh = meshio.read(out / "case_mx.vtu")
    assert mesh.cells[0].type == "wedge"
    assert mesh.point_data["displacement"].shape == (mesh.points.shape[0], 3)
    vm = mesh.cell_data["von_mises"][0]
    assert np.all(vm >= 0) and vm.max() > 0
    assert set(np.unique(mesh.cell_data["material"][0])) == {1, 2, 3, 4}
    assert b'compressor="vtkZLibDataCompressor"' in (out / "case_mx.vtu").read_bytes()[:2000]
    # M_x tilts the ring about x: the inner race moves along +/-y, symmetric in x
    p, u = mesh.points, mesh.point_data["displacement"]
    race = (np.abs(np.hypot(p[:, 0], p[:, 1]) - 0.075) < 1e-6) & (np.abs(p[:, 2]) < 0.017)
    assert np.abs(u[race, 1]).max() > 10 * np.abs(u[race, 0]).max()


def test_vtu_fields_follow_the_load_direction(identified):
    """F_y is F_x turned by 90 degrees: the displacement fields are the same turned."""
    _, out, _, _ = identified
    fx, fy = meshio.read(out / "case_fx.vtu"), meshio.read(out / "case_fy.vtu")
    p = fx.points.astype(float)
    turned = np.column_stack([-p[:, 1], p[:, 0], p[:, 2]])
    # pair each point with the point a quarter turn further round (the sectors are a multiple of 4)
    key = lambda q: np.round(q / 1e-6).astype(np.int64).tolist()
    index = {tuple(k): i for i, k in enumerate(key(p))}
    j = np.array([index[tuple(k)] for k in key(turned)])
    ux, uy = fx.point_data["displacement"].astype(float), fy.point_data["displacement"].astype(float)
    np.testing.assert_allclose(uy[j], np.column_stack([-ux[:, 1], ux[:, 0], ux[:, 2]]),
                               atol=1e-6 * np.abs(ux).max())


def test_hinge_is_spd_axisymmetric_and_bounded_by_the_supports(identified):
    config, _, result, _ = identified
    H_u, H_psi = result.H_u, result.H_psi
    assert np.all(np.linalg.eigvalsh(H_u) > 0) and np.all(H_psi > 0)
    # the assembly is axisymmetric: x and y must agree (to the mesh's asymmetry)
    assert H_u[0, 0] == pytest.approx(H_u[1, 1], rel=0.02)
    assert H_psi[0] == pytest.approx(H_psi[1], rel=0.02)
    # radial load reaches the seat only through the two supports (springs in parallel),
    # so the radial stiffness cannot exceed their sum
    assert H_u[0, 0] < 2.0 * config.support_radial_stiffness
    # the hinge idealisation holds: fit residual and coupling small
    assert result.residual < 0.05
    assert result.coupling["translation_rotation_max"] < 0.1
    assert result.fit.magnitude_spread < 1e-8  # linear elasticity: only round-off


def test_flange_reaction_is_softer_than_the_bearing_pair(identified, tmp_path):
    """Reacting at the flange adds the housing between seat and flange in series."""
    config, _, pair, _ = identified
    flange = identify_hinge(dataclasses.replace(config, load_reaction="flange"),
                            RingSeat(), tmp_path, write_fields=False)
    assert flange.H_u[0, 0] < pair.H_u[0, 0]


def test_the_hinge_table_pastes_into_a_scene(identified):
    """hinge.toml's header says its [hinge] table pastes into a scene with source = "given":
    the scene then carries the identified values."""
    import tomllib

    from bearingsim.pipeline.scene.load import read_scene_table, resolve

    _, out, result, _ = identified
    with open(out / "hinge.toml", "rb") as fh:
        pasted = tomllib.load(fh)["hinge"]
    pasted["source"] = "given"
    table = read_scene_table("helicopter-b-given-hinge")[0]
    table["hinge"] = pasted
    scene = resolve(table)
    np.testing.assert_array_equal(np.reshape(scene.hinge.translational, (3, 3)), result.H_u)  # kept row by row
    np.testing.assert_array_equal(np.array(scene.hinge.bending), result.H_psi)
