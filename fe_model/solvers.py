"""One factorisation of the SPD stiffness matrix, reused for every load case.

Two direct solvers: scipy's SuperLU, always there, and MKL PARDISO (matrix declared SPD),
installed with the optional extra `bearingsim[pardiso]` (x86-64 only, about 1 GB of MKL,
OpenMP and TBB). At the default mesh SuperLU is as fast; PARDISO pays for much finer meshes
(docs/performance.md, benchmarks/fe.py). `auto` takes PARDISO when it is installed.
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
