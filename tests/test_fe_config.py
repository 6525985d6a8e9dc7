"""FEConfig: metadata contract with the scene loader, and cross-field validation."""

import dataclasses

import pytest

from bearingsim.fe_model import FEConfig, RingSeat

ALLOWED_METADATA = {"unit", "gt", "ge", "lt", "le", "choices", "doc"}


def test_every_field_has_a_default_unit_and_doc_and_only_allowed_metadata():
    for f in dataclasses.fields(FEConfig):
        assert f.default is not dataclasses.MISSING, f.name
        assert set(f.metadata) <= ALLOWED_METADATA, f.name
        assert "unit" in f.metadata and "doc" in f.metadata, f.name


def test_defaults_satisfy_their_own_ranges_and_validate_for_the_reference_ring():
    config = FEConfig()
    for f in dataclasses.fields(FEConfig):
        value, meta = getattr(config, f.name), f.metadata
        values = value if isinstance(value, tuple) else (value,)
        for v in values:
            if "choices" in meta:
                assert v in meta["choices"], f.name
            assert "gt" not in meta or v > meta["gt"], f.name
            assert "ge" not in meta or v >= meta["ge"], f.name
            assert "lt" not in meta or v < meta["lt"], f.name
            assert "le" not in meta or v <= meta["le"], f.name
    config.validate(RingSeat())  # reference bearing, docs/model.md §2


def test_scene_example_keys_exist():
    # docs/scenes.md's [fe] table shows exactly these two keys
    names = {f.name for f in dataclasses.fields(FEConfig)}
    assert {"mesh_size", "element_order"} <= names


@pytest.mark.parametrize(
    "key, value",
    [
        ("shaft_inner_diameter", 0.14),
        ("support_a_position", -0.02),
        ("support_b_position", 0.02),
        ("support_radial_thickness", 0.04),
        ("housing_flange_position", 0.11),
        ("housing_flange_diameter", 0.2),
        ("mesh_size", 0.5),
        ("perturbation_forces", (0.0, 100.0)),
    ],
)
def test_inconsistent_geometry_names_key_value_and_unit(key, value):
    config = dataclasses.replace(FEConfig(), **{key: value})
    with pytest.raises(ValueError) as err:
        config.validate(RingSeat())
    assert key in str(err.value) and str(value).split(",")[0].strip("(") in str(err.value)


def test_ring_seat_rejects_inverted_diameters():
    with pytest.raises(ValueError, match="inner_bore_diameter < inner_outer_diameter"):
        RingSeat(inner_bore_diameter=0.16)


def test_support_modulus_thin_layer_formula():
    # k_r = 1.5 pi R w E / t (thin elastic layer, nu = 0, see FEConfig.support_modulus)
    config = FEConfig()
    E = config.support_modulus(RingSeat())
    R = 0.065 + 0.5 * config.support_radial_thickness
    assert 1.5 * 3.141592653589793 * R * config.support_width * E / config.support_radial_thickness == \
        pytest.approx(config.support_radial_stiffness, rel=1e-12)
