"""The bearing model's named outputs: each diagnostic channel is declared once (name, width,
unit, description) and read back by name (dynamics/bearing/channels.py); a run hands back
named series (`BearingRun.channels()`). Checked here against the raw layouts written out by
hand: a swapped slot, a wrong width or a misplaced body would show."""

from __future__ import annotations

import numpy as np
import pytest

from bearingsim.dynamics.bearing import channels, layout
from bearingsim.dynamics.bearing.run import BearingRun
from bearingsim.dynamics.multibody.crv import crv_from_rotation_vector, crv_to_matrix


def test_slots_follow_the_declaration_and_cover_the_row():
    for table in (channels.GLOBAL, channels.PER_BALL):
        covered = [s for c in table for s in range(c.slot, c.slot + c.width)]
        assert covered == list(range(table.size))
        assert all(c.unit and c.description for c in table)
    # the kernel writes the outer contact of a ball next to the inner one
    for quantity in ("load", "contact_angle", "film", "slide_roll", "max_pressure"):
        inner = channels.PER_BALL[f"contacts/inner_{quantity}"].slot
        assert channels.PER_BALL[f"contacts/outer_{quantity}"].slot == inner + 1


def test_a_name_cannot_be_declared_twice():
    c = channels.Channel("x", 1, "m", "one")
    with pytest.raises(ValueError, match="declared twice"):
        channels.RowLayout(c, c)


def test_read_picks_the_declared_slot_of_each_ball():
    Z, n = 4, 3
    diag = np.arange(n * channels.diag_size(Z), dtype=float).reshape(n, -1)
    s = channels.PER_BALL["contacts/outer_film"].slot
    for k in range(Z):  # per ball: after the global block, DB slots a ball
        np.testing.assert_array_equal(channels.read(diag, Z, "contacts/outer_film")[:, k],
                                      diag[:, channels.N_DG + channels.DB * k + s])
    g = channels.GLOBAL["cage_race/force"].slot
    np.testing.assert_array_equal(channels.read(diag, Z, "cage_race/force"), diag[:, g:g + 2])
    np.testing.assert_array_equal(channels.read(diag[1], Z, "energy/hinge"),
                                  diag[1, channels.GLOBAL["energy/hinge"].slot])


def synthetic_run(has_cage: bool, Z: int = 3, n: int = 5) -> BearingRun:
    rng = np.random.default_rng(7)
    n_dof = layout.n_dof(Z, has_cage)
    q, v = rng.normal(size=(n, n_dof)), rng.normal(size=(n, n_dof))
    for o in ([layout.inner_offset(Z)] + ([layout.cage_offset(Z, True)] if has_cage else [])):
        q[:, o + 3:o + 6] = [crv_from_rotation_vector(0.2 * rng.normal(size=3)) for _ in range(n)]
    return BearingRun(t=np.linspace(0, 1e-4, n), q=q, v=v, diag=rng.normal(size=(n, channels.diag_size(Z))),
                      impacts=np.zeros((0, 6)), energy={}, kinetic=rng.normal(size=n), stats={},
                      ball_count=Z, has_cage=has_cage, step_history=np.zeros((2, 2)))


def test_run_series_map_the_raw_layouts():
    Z = 3
    run = synthetic_run(True, Z)
    s = run.channels()
    o, c = 6 * Z, 6 * Z + 6  # layout.py: 6 per ball, then inner race (6), then cage (6)
    for k in range(Z):
        np.testing.assert_array_equal(s["balls/position"].data[:, k], run.q[:, 6 * k:6 * k + 3])
        np.testing.assert_array_equal(s["balls/angular_velocity"].data[:, k], run.v[:, 6 * k + 3:6 * k + 6])
        np.testing.assert_array_equal(s["contacts/inner_load"].data[:, k], run.diag[:, channels.N_DG + channels.DB * k])
    np.testing.assert_array_equal(s["inner_race/position"].data, run.q[:, o:o + 3])
    np.testing.assert_array_equal(s["cage/velocity"].data, run.v[:, c:c + 3])
    for i in range(run.t.size):
        np.testing.assert_allclose(s["inner_race/axis"].data[i], crv_to_matrix(run.q[i, o + 3:o + 6])[:, 2])
        spatial = crv_to_matrix(run.q[i, c + 3:c + 6]) @ run.v[i, c + 3:c + 6]
        np.testing.assert_allclose(s["cage/speed"].data[i], spatial[2], rtol=1e-14)
    np.testing.assert_array_equal(s["cage_race/eccentricity_ratio"].data, run.diag[:, 0])
    assert s["contacts/inner_load"].unit == "N" and s["contacts/inner_load"].dims == ("time", "ball")
    assert s["cage_race/force"].dims == ("time", "xy") and s["balls/position"].dims == ("time", "ball", "xyz")
    for name, series in s.items():
        assert series.data.ndim == len(series.dims), name
        assert series.data.shape[0] == (2 if name == "solver/step_size" else run.t.size), name


def test_without_a_cage_no_cage_series_and_no_bookkeeping_channels():
    with_cage, without = synthetic_run(True).channels(), synthetic_run(False).channels()
    cage_names = {n for n in with_cage if n.startswith(("cage", "pocket"))}
    assert cage_names and not cage_names & set(without)
    assert set(with_cage) - cage_names == set(without)
    assert "traction/flagged_contacts" not in with_cage and "pocket/in_contact" not in with_cage
