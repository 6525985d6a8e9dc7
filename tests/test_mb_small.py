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
