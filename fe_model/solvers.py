"""One factorisation (or one preconditioner) of the SPD stiffness matrix, reused for every
load case.

Two direct solvers: scipy's SuperLU, always there, and MKL PARDISO (matrix declared SPD),
installed with the optional extra `bearingsim[pardiso]` (x86-64 only, about 1 GB of MKL,
OpenMP and TBB). At the default mesh SuperLU is as fast; PARDISO pays for much finer meshes
(docs/performance.md, benchmarks/fe.py). `auto` takes PARDISO when it is installed.

Beyond what a direct solver holds in memory (a 3-D mesh of a real housing: hundreds of
thousands of dofs, where SuperLU's fill grows past the machine), `AMGSolver`: conjugate
gradients preconditioned by pyamg's smoothed-aggregation multigrid built on the six
rigid-body modes (the near-nullspace of elasticity; Vanek, Mandel & Brezina, Computing 56
(1996) 179), built once and reused for every load case.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from .elasticity import full_from_upper


def pardiso_available() -> bool:
    try:
        import pypardiso  # noqa: F401
    except ImportError:
        return False
    return True


class SPDFactorization:
    """Factor K once (`K_upper`: upper triangle, CSR), then `solve(B)` for many columns."""

    def __init__(self, K_upper: sp.csr_matrix, method: str = "auto"):
        if method == "auto":
            method = "pardiso" if pardiso_available() else "splu"
        if method == "pardiso" and not pardiso_available():
            raise RuntimeError(
                "linear_solver = 'pardiso' but pypardiso is not installed (it needs MKL, x86-64); "
                "use linear_solver = 'splu' or 'auto'"
            )
        self.method = method
        if method == "pardiso":
            import pypardiso

            self._solver = pypardiso.PyPardisoSolver(mtype=2)  # real symmetric positive definite
            self._K = K_upper
            self._solver.factorize(K_upper)
        elif method == "splu":
            from scipy.sparse.linalg import splu

            self._lu = splu(full_from_upper(K_upper).tocsc(), permc_spec="COLAMD")
        else:
            raise ValueError(f"linear_solver = {method!r}: allowed 'auto', 'pardiso', 'splu'")

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        """Solve K X = rhs for a (n,) or (n, m) right-hand side."""
        rhs = np.asarray(rhs, dtype=np.float64)
        if self.method == "pardiso":
            return self._solver.solve(self._K, np.asfortranarray(rhs))
        return self._lu.solve(rhs)

    def free(self) -> None:
        """Release the factor memory (PARDISO keeps it outside Python's heap)."""
        if self.method == "pardiso":
            self._solver.free_memory(everything=True)


class AMGSolver:
    """Smoothed-aggregation AMG (pyamg) + conjugate gradients (scipy) on K X = B.

    `near_nullspace`: (n, 6) rigid-body modes on the free dofs (translations and rotations at
    the dof locations); `tolerance`: relative residual |K x - b| / |b| at which CG stops."""

    method = "amg"

    def __init__(self, K_upper: sp.csr_matrix, near_nullspace: np.ndarray, tolerance: float = 1e-10,
                 max_iterations: int = 2000):
        import pyamg

        self._K = full_from_upper(K_upper)
        self.tolerance = tolerance
        self.max_iterations = max_iterations
        # node blocks (3 x 3: the dofs are 3 node + component, clamps take whole nodes), so that
        # aggregates are sets of nodes; evolution strength and energy-minimising prolongation
        # hold the iterations near 50 on P2 tetrahedra with 1:100 moduli, where the classic
        # settings (symmetric strength, Jacobi smoothing) take 150 (benchmarks/fe_mesh.py)
        blocks = self._K.tobsr(blocksize=(3, 3)) if self._K.shape[0] % 3 == 0 else self._K
        self._hierarchy = pyamg.smoothed_aggregation_solver(
            blocks, B=np.ascontiguousarray(near_nullspace), symmetry="symmetric",
            strength=("evolution", {"k": 2, "proj_type": "D_A", "epsilon": 4.0}),
            smooth=("energy", {"krylov": "cg", "maxiter": 2}), max_coarse=500)
        self._M = self._hierarchy.aspreconditioner(cycle="V")
        self.iterations: list[int] = []
        self.residuals: list[float] = []

    @property
    def levels(self) -> int:
        return len(self._hierarchy.levels)

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        """Solve K X = rhs for a (n,) or (n, m) right-hand side, one CG run per column."""
        from scipy.sparse.linalg import cg

        rhs = np.asarray(rhs, dtype=np.float64)
        columns = rhs.reshape(rhs.shape[0], -1)
        out = np.zeros_like(columns)
        for j in range(columns.shape[1]):
            b = columns[:, j]
            norm = float(np.linalg.norm(b))
            if norm == 0.0:
                self.iterations.append(0)
                self.residuals.append(0.0)
                continue
            count = [0]

            def step(_xk, count=count):
                count[0] += 1

            x, info = cg(self._K, b, rtol=self.tolerance, atol=0.0, maxiter=self.max_iterations, M=self._M,
                         callback=step)
            residual = float(np.linalg.norm(b - self._K @ x) / norm)
            if info != 0 or not np.isfinite(residual):
                raise RuntimeError(
                    f"the FE solve (conjugate gradients with AMG, load case {j + 1} of {columns.shape[1]}) did not "
                    f"reach the relative residual {self.tolerance:g} in {count[0]} iterations (reached {residual:.2e}); "
                    "the mesh may hold badly shaped tetrahedra or materials of very different stiffness. Try a looser "
                    "fe.iterative_tolerance (e.g. 1e-8), or a direct solver (fe.linear_solver = 'splu' or 'pardiso') "
                    "if the mesh fits in memory")
            self.iterations.append(count[0])
            self.residuals.append(residual)
            out[:, j] = x
        return out.reshape(rhs.shape)

    def free(self) -> None:
        self._hierarchy = self._M = None


def spd_solver(K_upper: sp.csr_matrix, method: str, near_nullspace=None, tolerance: float = 1e-10,
               direct_max_dofs: int = 100_000):
    """The solver `method` names ("auto", "pardiso", "splu", "amg") for the upper triangle
    `K_upper`: "auto" is a direct solver up to `direct_max_dofs` unknowns and AMG beyond
    (`near_nullspace` is needed for AMG: a callable giving the (n, 6) rigid-body modes)."""
    if method == "auto":
        method = "amg" if K_upper.shape[0] > direct_max_dofs else "auto"
    if method == "amg":
        if near_nullspace is None:
            raise ValueError("linear_solver = 'amg' is for model = 'mesh'; use 'auto', 'splu' or 'pardiso'")
        return AMGSolver(K_upper, near_nullspace(), tolerance)
    return SPDFactorization(K_upper, method)


def rigid_body_modes(points: np.ndarray) -> np.ndarray:
    """(3 P, 6) rigid-body modes at `points` (P, 3) [m], dofs 3 p + component: three unit
    translations and three rotations about the points' centroid, scaled to unit size."""
    r = points - points.mean(axis=0)
    scale = float(np.sqrt((r**2).sum(axis=1).mean())) or 1.0
    r = r / scale
    B = np.zeros((points.shape[0], 3, 6))
    for c in range(3):
        B[:, c, c] = 1.0
    B[:, 1, 3], B[:, 2, 3] = -r[:, 2], r[:, 1]  # rotation about x: (0, -z, y)
    B[:, 0, 4], B[:, 2, 4] = r[:, 2], -r[:, 0]  # about y: (z, 0, -x)
    B[:, 0, 5], B[:, 1, 5] = -r[:, 1], r[:, 0]  # about z: (-y, x, 0)
    return B.reshape(-1, 6)
