"""The tangent assembly's small products (dynamics/bearing/tangents.py) against numpy."""

from __future__ import annotations

import numpy as np
import pytest

from bearingsim.dynamics.bearing.tangents import add_congruent, point_map


@pytest.mark.parametrize("na, nb", [(6, 6), (6, 3), (3, 6)])
def test_add_congruent_is_a_transposed_j_b_on_any_layout(na, nb):
    rng = np.random.default_rng(na * 10 + nb)
    A, J, B = rng.normal(size=(3, na)), rng.normal(size=(3, 3)), rng.normal(size=(3, nb))
    big = rng.normal(size=(8, 14))
    expected = big.copy()
    expected[1:1 + na, 5:5 + nb] -= 0.5 * (A.T @ J @ B)
    add_congruent(big[1:1 + na, 5:5 + nb], A, J, B, -0.5)  # a strided view, as the blocks are
    assert np.allclose(big, expected, rtol=1e-14, atol=1e-14)


def test_point_map_is_identity_and_minus_r_cross_r():
    rng = np.random.default_rng(3)
    r, (R, _) = rng.normal(size=3), np.linalg.qr(rng.normal(size=(3, 3)))
    out = np.full((3, 6), np.nan)
    point_map(r, R, out)
    skew = np.array([[0.0, -r[2], r[1]], [r[2], 0.0, -r[0]], [-r[1], r[0], 0.0]])
    assert np.array_equal(out[:, :3], np.eye(3))
    assert np.allclose(out[:, 3:], -skew @ R, rtol=1e-14, atol=1e-15)
