"""The bearing model as a first-order ODE for scipy's solve_ivp: the baseline of the
work-precision study (and of benchmarks/bearing.py), with the sparsity pattern of its Jacobian
so that Radau and BDF difference only the columns that can couple (a fair baseline: a careful
scipy user passes `jac_sparsity`)."""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp


def ode_rhs(model, rotation_slots, spin_row):
    """y = (q, v) -> (q_dot, v_dot): q_dot = v except CRV slots, c_dot = H(c)^-T Omega (M.4d);
    v_dot = M^-1 g (diagonal M); the prescribed spin has v_dot = 0."""
    from ...dynamics.multibody.crv import crv_H

    n = model.n_dof
    ma, g, zero = np.zeros(n), np.zeros(n), np.zeros(n)
    counter = {"evaluations": 0}

    def rhs(t, y):
        q, v = np.array(y[:n]), np.array(y[n:])  # fresh contiguous arrays: one numba signature
        model.evaluate(float(t), q, v, zero, ma, g)
        counter["evaluations"] += 1
        qd = v.copy()
        for s in rotation_slots:
            qd[s:s + 3] = np.linalg.solve(crv_H(q[s:s + 3]).T, v[s:s + 3])
        vd = g / model.mass
        vd[spin_row] = 0.0
        return np.concatenate([qd, vd])

    return rhs, counter


def jac_sparsity(ball_count: int, has_cage: bool, rotation_slots) -> sp.csr_matrix:
    """Sparsity pattern of d(q_dot, v_dot)/d(q, v) for `ode_rhs` (2n x 2n, n = 6Z + border).

    The forces are block-arrow (docs/model.md §9): a ball's six rows depend on that ball and
    on the border bodies (inner race, cage), the border rows on everything. q_dot = v except
    the rotation slots of the border bodies, whose CRV rate H(c)^-T Omega depends on c and
    Omega (3x3 blocks)."""
    from ...dynamics.bearing import layout

    n = layout.n_dof(ball_count, has_cage)
    border = layout.inner_offset(ball_count)
    block = np.zeros((n, n), dtype=bool)
    for k in range(ball_count):
        o = layout.ball_offset(k)
        block[o:o + layout.BALL_DOF, o:o + layout.BALL_DOF] = True
        block[o:o + layout.BALL_DOF, border:] = True
        block[border:, o:o + layout.BALL_DOF] = True
    block[border:, border:] = True
    dq_dq = np.zeros((n, n), dtype=bool)
    dq_dv = np.eye(n, dtype=bool)
    for s in rotation_slots:
        dq_dq[s:s + 3, s:s + 3] = True
        dq_dv[s:s + 3, s:s + 3] = True
    return sp.csr_matrix(np.block([[dq_dq, dq_dv], [block, block]]))
