"""General multibody core: CRV rigid bodies, joints, viscoelastic hinge, HHT-α integrator.

Knows nothing about bearings (docs/contributing.md rule 1): models implement the residual protocol of
`problem.py`; `integrate` advances them. docs/model.md §4, §5, §9.
"""

from .hinge import HingeStiffness, hinge_energy, hinge_forces, hinge_strains
from .integrate import initial_acceleration, integrate
from .linear_solvers import BlockArrowMatrix, BlockArrowSolver, DenseSolver
from .problem import MultibodyProblem, check_problem
from .results import IntegrationError, Result, Solution, SolverStats
from .sampling import FixedIntervalSampler
from .settings import HHTSettings, JacobianReuse

__all__ = [
    "BlockArrowMatrix", "BlockArrowSolver", "DenseSolver", "FixedIntervalSampler",
    "HHTSettings", "HingeStiffness", "IntegrationError", "JacobianReuse", "MultibodyProblem",
    "Result", "Solution", "SolverStats", "check_problem", "hinge_energy", "hinge_forces",
    "hinge_strains", "initial_acceleration", "integrate",
]
