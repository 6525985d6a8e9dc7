"""Quasi-static equilibrium of a ball bearing (docs/model.md §10): the solver (`solver`),
its numba kernels (`kernels`) and its result with the dynamic start state (`result`)."""
