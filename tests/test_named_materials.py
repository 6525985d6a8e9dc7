"""Built-in materials (dynamics/materials/data; docs/model.md §2.2): the values against their cited
sources, the scene forms that name them, and that a named material is used in every model exactly
as the same numbers written out (Hertz contacts of pocket and land, mass and inertia, thermal growth).

Reference numbers (the data files give the same, number by number):
- silicon bronze C65500: 15 000 ksi, 0.308 lb/in^3 = 8.53 g/cm^3, 18.0e-6 1/K (CDA-style data sheet);
- PA66-GF25: interpolated in glass mass fraction between unfilled PA66 (2.83 GPa, Cerobear; 1140 kg/m^3
  and 90e-6 1/K, Crawford, Plastics Engineering, Table 1.8) and glass-filled grades (9.5 GPa at 30 %,
  Encycl. Phys. Sci. Technol.; 1380 kg/m^3 and 30e-6 1/K at 33 %, Crawford);
- silicon nitride GPS-Si3N4: 3.27 g/cm^3, 310 GPa, 0.24, 3.3e-6 1/K (Lily Bearing ceramic table).
"""

from __future__ import annotations

import copy

import numpy as np
import pytest
from typer.testing import CliRunner

from bearingsim.dynamics.geometry import Material, effective_modulus
from bearingsim.dynamics.materials.library import builtin_material_names, load_builtin_material
from bearingsim.pipeline.cli.commands import app
from bearingsim.pipeline.scene.load import apply_overrides, read_scene_table, resolve
from bearingsim.pipeline.scene.schema import SceneError
from bearingsim.pipeline.stages.simulate import model_params

KSI = 6.894757e6  # Pa


def _interpolate(w: float, w0: float, v0: float, w1: float, v1: float) -> float:
    return v0 + (v1 - v0) * (w - w0) / (w1 - w0)


@pytest.mark.parametrize("name, E, nu, rho, alpha, t_max", [
    ("bronze", 15_000 * KSI, 0.34, 8530.0, 18.0e-6, 200.0),
    ("pa66-gf25", _interpolate(25, 0, 2.83e9, 30, 9.5e9), 0.41, _interpolate(25, 0, 1140.0, 33, 1380.0),
     _interpolate(25, 0, 90e-6, 33, 30e-6), 100.0),
    ("peek", 4.1e9, 0.40, 1320.0, 47e-6, 204.0),
    ("phenolic", 0.5 * (11.0e9 + 8.3e9), 0.30, 1350.0, 0.5 * (18.0e-6 + 19.0e-6), 125.0),
    ("steel", 205e9, 0.29, 7870.0, 12.2e-6, 300.0),
    ("silicon-nitride", 310e9, 0.24, 3270.0, 3.3e-6, 1000.0),
])
def test_named_materials_hold_their_cited_values(name, E, nu, rho, alpha, t_max):
    m = load_builtin_material(name)
    assert m.material.youngs_modulus == pytest.approx(E, rel=2e-3)  # the files round to 3-4 digits
    assert (m.material.poisson_ratio, m.material.density) == (pytest.approx(nu), pytest.approx(rho, rel=2e-3))
    assert m.material.thermal_expansion == pytest.approx(alpha, rel=2e-3)
    assert m.max_temperature_degC == t_max and m.source


def test_every_file_is_a_valid_material_for_its_roles():
    assert {"bronze", "steel", "peek", "pa66-gf25", "phenolic"} <= set(builtin_material_names("cage"))
    assert {"aisi-52100", "m50", "silicon-nitride"} <= set(builtin_material_names("ball"))
    for name in builtin_material_names():
        table = read_scene_table("helicopter-b-given-hinge")[0]
        for role in load_builtin_material(name).roles:
            table = copy.deepcopy(table)
            table["materials"][role] = name
            resolve(table)  # through the scene validator: every value in range


def _scene(**materials):
    table = copy.deepcopy(read_scene_table("helicopter-b-given-hinge")[0])
    table["materials"].update(materials)
    return resolve(table)


def test_a_name_is_the_same_numbers_written_out_in_every_model():
    named = _scene(cage="pa66-gf25")
    m = load_builtin_material("pa66-gf25").material
    written = _scene(cage={"youngs_modulus": m.youngs_modulus, "poisson_ratio": m.poisson_ratio,
                           "density": m.density, "thermal_expansion": m.thermal_expansion})
    assert named.materials == written.materials and named.expansion == written.expansion
    assert named.cage == written.cage  # grown by the cage's own 44.5e-6 1/K
    assert named.expansion.cage == m.thermal_expansion
    static = (np.zeros(3), np.eye(3))
    p_named, p_written = model_params(named, None, *static), model_params(written, None, *static)
    assert p_named.pocket == p_written.pocket and p_named.journal == p_written.journal
    np.testing.assert_array_equal(p_named.fp, p_written.fp)  # cage mass and inertia among them
    # the land contact's effective modulus is the cage's against the ring's (docs/model.md §8)
    grown_cage = named.materials.cage
    assert p_named.journal.e_eff == pytest.approx(effective_modulus(grown_cage, named.materials.race), rel=1e-12)
    bronze = model_params(_scene(), None, *static)
    # a polymer cage: land modulus 2/((1-0.41^2)/8.39e9 + (1-0.3^2)/208e9) ~ 19 GPa against bronze's ~130 GPa
    assert p_named.journal.e_eff < 0.2 * bronze.journal.e_eff
    assert p_named.pocket != bronze.pocket


def test_the_cage_mass_follows_the_named_density():
    bronze, polymer = _scene(cage="bronze"), _scene(cage="pa66-gf25")
    ratio = polymer.cage.mass(polymer.materials.cage, polymer.bearing) / bronze.cage.mass(bronze.materials.cage,
                                                                                        bronze.bearing)
    # the same drawing, grown by 44.5e-6 or 18e-6 1/K over 80 K; growth keeps each part's mass (the operating
    # density falls with the volume, dynamics/thermal.py), so the masses are in the ratio of the named densities
    assert ratio == pytest.approx(1322.0 / 8530.0, rel=1e-9)


def test_a_table_may_refine_a_named_material():
    scene = _scene(cage={"name": "pa66-gf25", "youngs_modulus": 5.5e9})
    assert scene.nominal.materials.cage == Material(5.5e9, 0.41, 1322.0, 44.5e-6)
    # --set (and a sweep's --vary) refines a named entry the same way
    table = copy.deepcopy(read_scene_table("helicopter-b-given-hinge")[0])
    table["materials"]["cage"] = "pa66-gf25"
    overridden = resolve(apply_overrides(table, ["materials.cage.youngs_modulus=5.5e9"]))
    assert overridden.nominal.materials.cage == scene.nominal.materials.cage


@pytest.mark.parametrize("value, key, words", [
    ("nylon", "materials.cage", "'nylon' is not a built-in cage material; built-in cage materials: aisi-4340, brass, "
                                "bronze, pa66-gf25, peek, phenolic, steel"),
    ({"name": "pa66"}, "materials.cage.name", "'pa66' is not a built-in cage material"),
    (12.0, "materials.cage", "expected a built-in material name"),
])
def test_a_wrong_name_lists_the_names(value, key, words):
    with pytest.raises(SceneError) as info:
        _scene(cage=value)
    assert info.value.key == key and words in str(info.value)


def test_a_material_for_another_part_is_refused_with_its_part():
    with pytest.raises(SceneError, match=r"materials.ball: 'pa66-gf25' is not a built-in ball material \(it is one "
                                         r"for the cage\); built-in ball materials: aisi-52100, m50, silicon-nitride"):
        _scene(ball="pa66-gf25")


def test_check_names_the_material_and_warns_past_its_temperature():
    runner = CliRunner()
    result = runner.invoke(app, ["check", "helicopter-b-given-hinge", "--set", 'materials.cage="pa66-gf25"'])
    assert result.exit_code == 0, result.output
    text = " ".join(result.stdout.split())
    assert "cage: built-in 'pa66-gf25'" in text and "up to 100 °C continuous" in text
    # the reference scene's oil is at 100 degC, the cage with it: at the limit, no warning; 110 degC warns
    assert "rated for continuous use" not in result.stderr
    hot = runner.invoke(app, ["check", "helicopter-b-given-hinge", "--set", 'materials.cage="pa66-gf25"',
                              "--set", "thermal.cage_degC=110"])
    assert hot.exit_code == 0
    assert "warning: materials.cage: 'pa66-gf25'" in hot.stderr and "runs at 110 °C" in " ".join(hot.stderr.split())


def test_bearingsim_materials_lists_them():
    result = CliRunner().invoke(app, ["materials"])
    assert result.exit_code == 0
    for name in builtin_material_names():
        assert any(line.split()[:1] == [name] for line in result.stdout.splitlines()), name
