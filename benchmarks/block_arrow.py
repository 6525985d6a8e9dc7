"""Benchmark: block-arrow Schur solver vs dense LU, the solve with and without the block size
known to the compiler, and the integrator's per-step overhead.

Run: taskset -c 1 python -m benchmarks.block_arrow
"""

from __future__ import annotations


import numpy as np
import scipy.linalg as sla

from bearingsim.dynamics.multibody import (BlockArrowMatrix, BlockArrowSolver, DenseSolver, HHTSettings,
                                integrate)
from bearingsim.dynamics.multibody.example_problems import ArrowSprings, Pendulum
from benchmarks import best_time


def random_arrow(Z: int, m: int, nb: int, rng) -> BlockArrowMatrix:
    A = BlockArrowMatrix.zeros(Z, m, nb)
    A.D[:] = rng.normal(size=A.D.shape) + 4 * np.eye(m)
    A.E[:] = rng.normal(size=A.E.shape)
    A.F[:] = rng.normal(size=A.F.shape)
    A.B[:] = rng.normal(size=A.B.shape) + (4 * np.sqrt(Z) + 2) * np.eye(nb)
    return A


def solver_table(m: int = 6, nb: int = 12) -> None:
    rng = np.random.default_rng(0)
    print(f"block-arrow (m = {m}, border nb = {nb}) vs dense; times per factor+solve [us]")
    print(f"{'Z':>5} {'n':>6} {'block':>10} {'block/Z':>9} {'dense(numba)':>13} "
          f"{'scipy LU':>10} {'max|x-x_ref|':>13}")
    for Z in (10, 22, 44, 88, 176):
        A = random_arrow(Z, m, nb, rng)
        n = Z * m + nb
        b = rng.normal(size=n)
        x = np.empty(n)
        blk = BlockArrowSolver(Z, m, nb)
        dense = A.to_dense()
        dns = DenseSolver()

        def run_block():
            blk.factor(A)
            blk.solve(b, x)

        def run_dense():
            dns.factor(dense)
            dns.solve(b, x)

        def run_scipy():
            sla.lu_solve(sla.lu_factor(dense, check_finite=False), b, check_finite=False)

        run_block()
        run_dense()
        t_blk, t_dns = best_time(run_block), best_time(run_dense, number=3)
        t_sp = best_time(run_scipy, number=5)
        run_block()
        err = np.abs(x - np.linalg.solve(dense, b)).max()
        print(f"{Z:5d} {n:6d} {t_blk * 1e6:10.1f} {t_blk * 1e6 / Z:9.2f} {t_dns * 1e6:13.1f} "
              f"{t_sp * 1e6:10.1f} {err:13.2e}")


def solve_paths(Z: int = 22, m: int = 6, nb: int = 12, rounds: int = 3) -> None:
    """One solve of the reference bearing's size (22 balls of 6 unknowns, a border of 12) by
    `block_arrow_solve`, whose rigid-body blocks (m = 6) run loops compiled with m known, and by
    the same loops with m read at run time (the route of any other m), alternated; and whether
    the two give the same bits."""
    import numba

    from bearingsim.dynamics.multibody.linear_solvers import _block_arrow_solve_m, block_arrow_solve

    @numba.njit
    def known(Dinv_T, F_T, DinvE_T, S, piv_S, rhs, x, reps):
        for _ in range(reps):
            block_arrow_solve(Dinv_T, F_T, DinvE_T, S, piv_S, rhs, x)

    @numba.njit
    def at_run_time(Dinv_T, F_T, DinvE_T, S, piv_S, rhs, x, reps):
        for _ in range(reps):
            _block_arrow_solve_m(Dinv_T, F_T, DinvE_T, S, piv_S, rhs, x, Dinv_T.shape[1])

    rng = np.random.default_rng(1)
    blk = BlockArrowSolver(Z, m, nb)
    blk.factor(random_arrow(Z, m, nb, rng))
    args = (blk._Dinv_T, blk._F_T, blk._DinvE_T, blk._S, blk._piv_S, rng.normal(size=Z * m + nb))
    x_known, x_run = np.empty(Z * m + nb), np.empty(Z * m + nb)
    known(*args, x_known, 1)
    at_run_time(*args, x_run, 1)
    print(f"\nsolve, Z = {Z}, m = {m}, nb = {nb} [us]; same bits: {np.array_equal(x_known, x_run)}")
    reps = 20000
    for _ in range(rounds):
        t = {name: best_time(lambda f=f, x=x: f(*args, x, reps), repeat=5, number=1) / reps * 1e6
             for name, f, x in (("m known", known, x_known), ("m at run time", at_run_time, x_run))}
        print("  " + "   ".join(f"{k} {v:.3f}" for k, v in t.items()))


def overhead_table() -> None:
    print("\nintegrator cost per accepted step (Python loop + numba kernels) [us]")
    print(f"{'problem':>28} {'n':>4} {'steps':>7} {'Newton/step':>12} {'us/step':>9} "
          f"{'us/iter':>8} {'factor/step':>12}")
    cases = [
        ("pendulum (dense)", Pendulum(2.0), None, np.array([1.0]), np.zeros(1),
         HHTSettings(alpha=0.1, first_step=1e-3, min_step=1e-8, max_step=1e-3, rtol=0.0,
                     atol=1e-7), 20.0),
        ("arrow Z=22 (block-arrow)", ArrowSprings(22), BlockArrowSolver(22, 3, 3),
         np.full(69, 1e-4), np.zeros(69),
         HHTSettings(alpha=0.1, first_step=1e-6, min_step=1e-9, max_step=2e-6, rtol=0.0,
                     atol=1e-9), 0.02),
        ("arrow Z=22 (dense)", ArrowSprings(22, "dense"), DenseSolver(), np.full(69, 1e-4),
         np.zeros(69), HHTSettings(alpha=0.1, first_step=1e-6, min_step=1e-9, max_step=2e-6,
                                   rtol=0.0, atol=1e-9), 0.02),
    ]
    for name, problem, solver, q0, v0, settings, T in cases:
        integrate(problem, 0.0, T / 100, q0, v0, settings, linear_solver=solver)  # warm up
        sol = integrate(problem, 0.0, T, q0, v0, settings, linear_solver=solver)
        st = sol.stats
        print(f"{name:>28} {problem.n_dof:4d} {st.steps:7d} "
              f"{st.newton_iterations / st.steps:12.2f} {st.wall_time / st.steps * 1e6:9.1f} "
              f"{st.wall_time / st.newton_iterations * 1e6:8.1f} "
              f"{st.factorizations / st.steps:12.3f}")


if __name__ == "__main__":
    solver_table()
    solve_paths()
    overhead_table()
