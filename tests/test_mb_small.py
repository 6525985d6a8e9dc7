"""Loop-written small products (dynamics/multibody/small.py) against numpy's."""

import numpy as np

from bearingsim.dynamics.multibody.small import mm, mtv, mv


def test_small_products_equal_numpy_for_any_layout():
    rng = np.random.default_rng(5)
    for n, k, m in [(3, 3, 3), (2, 3, 3), (3, 2, 3), (6, 6, 6), (2, 3, 2)]:
        A, B = rng.normal(size=(n, k)), rng.normal(size=(k, m))
        x, y = rng.normal(size=k), rng.normal(size=n)
        np.testing.assert_allclose(mm(A, B), A @ B, rtol=1e-13, atol=1e-14)
        np.testing.assert_allclose(mv(A, x), A @ x, rtol=1e-13, atol=1e-14)
        np.testing.assert_allclose(mtv(A, y), A.T @ y, rtol=1e-13, atol=1e-14)
        # transposed and strided views, as the kernels pass them (R.T, R[:, 2])
        At = np.ascontiguousarray(A.T).T
        np.testing.assert_allclose(mm(At, B), A @ B, rtol=1e-13, atol=1e-14)
        np.testing.assert_allclose(mv(A, np.vstack([x, x])[0]), A @ x, rtol=1e-13, atol=1e-14)
        np.testing.assert_allclose(mm.py_func(A, B), mm(A, B), rtol=1e-13, atol=1e-14)


def test_small_builders_equal_numpy_bit_for_bit():
    """outer, eye3, add_into and copy_into replace np.outer, np.eye and slice assignments in the
    kernels; each entry is one product or one sum, so they must agree exactly."""
    from bearingsim.dynamics.multibody.small import add_into, copy_into, eye3, outer

    rng = np.random.default_rng(7)
    a, b = rng.normal(size=3), rng.normal(size=6)
    assert np.array_equal(outer(a, b), np.outer(a, b))
    assert np.array_equal(eye3(), np.eye(3))
    K, A = rng.normal(size=(6, 6)), rng.normal(size=(3, 3))
    expected = K.copy()
    expected[3:, :3] += A
    add_into(K[3:, :3], A)  # a strided view, as the tangents pass their blocks
    assert np.array_equal(K, expected)
    expected[:3, 3:] = A
    copy_into(K[:3, 3:], A)
    assert np.array_equal(K, expected)
