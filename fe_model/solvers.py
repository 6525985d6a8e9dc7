"""One factorisation of the SPD stiffness matrix, reused for every load case.

Measured on the 2-core build machine for a ~400k-dof P2 housing model (factor + 6
solves): MKL PARDISO with the matrix declared SPD (mtype 2) ~15 s / 3.1 GB; scipy
SuperLU 250-550 s; AMG-preconditioned CG ~110 s; CHOLMOD/MUMPS need system packages.
So PARDISO is the default and SuperLU the portable fallback (non-x86 machines, where
pypardiso is not installed); see benchmarks/fe.py for the figures of this code.
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp

from bearingsim.fe_model.elasticity import full_from_upper


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
