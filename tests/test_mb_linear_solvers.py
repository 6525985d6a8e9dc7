"""Linear solvers of the Newton iteration (docs/model.md §9): the block-arrow Schur-complement
solver against a dense solve (numpy.linalg.solve, LAPACK gesv, as the independent twin)."""

import numpy as np
import pytest

from bearingsim.dynamics.multibody.linear_solvers import (BlockArrowMatrix, BlockArrowSolver,
                                               DenseSolver, lu_factor_inplace)

RNG = np.random.default_rng(7)


def random_block_arrow(Z, m, nb, dominance=4.0):
    A = BlockArrowMatrix.zeros(Z, m, nb)
    A.D[:] = RNG.normal(size=A.D.shape) + dominance * np.eye(m)
    A.E[:] = RNG.normal(size=A.E.shape)
    A.F[:] = RNG.normal(size=A.F.shape)
    A.B[:] = RNG.normal(size=A.B.shape) + (dominance * np.sqrt(Z) + 2.0) * np.eye(nb)
    return A


@pytest.mark.parametrize("Z, m, nb", [(1, 6, 12), (22, 6, 12), (5, 3, 1), (9, 6, 0)])
def test_block_arrow_equals_dense(Z, m, nb):
    A = random_block_arrow(Z, m, nb)
    b = RNG.normal(size=Z * m + nb)
    x = np.empty_like(b)
    solver = BlockArrowSolver(Z, m, nb)
    assert solver.factor(A)
    solver.solve(b, x)
    ref = np.linalg.solve(A.to_dense(), b)
    np.testing.assert_allclose(x, ref, rtol=1e-10, atol=1e-12)


def test_block_arrow_with_pivoting_needed():
    # Zero leading diagonal entries force row exchanges inside the small blocks.
    A = random_block_arrow(4, 6, 5)
    A.D[:, 0, 0] = 0.0
    b = RNG.normal(size=29)
    x = np.empty_like(b)
    s = BlockArrowSolver(4, 6, 5)
    assert s.factor(A)
    s.solve(b, x)
    np.testing.assert_allclose(A.to_dense() @ x, b, atol=1e-10)


def test_dense_solver_matches_numpy_and_flags_singular():
    M = RNG.normal(size=(17, 17))
    b = RNG.normal(size=17)
    x = np.empty(17)
    d = DenseSolver()
    assert d.factor(M)
    d.solve(b, x)
    np.testing.assert_allclose(x, np.linalg.solve(M, b), rtol=1e-10)
    M[:, 3] = 0.0
    assert not d.factor(M)
    M[0, 0] = np.nan
    assert not lu_factor_inplace(M.copy(), np.zeros(17, dtype=np.int64))


def test_singular_small_block_is_reported():
    A = random_block_arrow(3, 6, 2)
    A.D[1] = 0.0
    assert not BlockArrowSolver(3, 6, 2).factor(A)


def test_block_arrow_solve_refuses_the_right_hand_side_as_output():
    # the solve writes the border of out before it has read every small block of rhs
    rng = np.random.default_rng(4)
    A = BlockArrowMatrix.zeros(3, 2, 2)
    A.D[:] = rng.normal(size=A.D.shape) + 4 * np.eye(2)
    A.B[:] = 4 * np.eye(2)
    s = BlockArrowSolver(3, 2, 2)
    assert s.factor(A)
    b = rng.normal(size=8)
    with pytest.raises(ValueError, match="rhs and out must be different arrays"):
        s.solve(b, b)
