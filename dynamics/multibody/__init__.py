"""General multibody core: CRV rigid bodies, joints, viscoelastic hinge, HHT-α integrator.

Knows nothing about bearings (docs/contributing.md rule 1): models implement the residual protocol of
`problem.py`; `integrate` advances them. docs/model.md §4, §5, §9.

The names below load their module on first use, so that the scene loader, which builds the
integrator's `HHTSettings` from `[solver]`, imports neither numba nor the kernels.
"""

from .._lazy import lazy_exports

_EXPORTS = {
    "HingeStiffness": ".hinge", "hinge_energy": ".hinge", "hinge_forces": ".hinge", "hinge_strains": ".hinge",
    "initial_acceleration": ".time_loop", "integrate": ".time_loop",
    "BlockArrowMatrix": ".linear_solvers", "BlockArrowSolver": ".linear_solvers", "DenseSolver": ".linear_solvers",
    "MultibodyProblem": ".problem", "check_problem": ".problem",
    "IntegrationError": ".results", "Result": ".results", "Solution": ".results", "SolverStats": ".results",
    "FixedIntervalSampler": ".sampling", "HHTSettings": ".settings", "JacobianReuse": ".settings",
}
__getattr__, __all__ = lazy_exports(__name__, _EXPORTS)
