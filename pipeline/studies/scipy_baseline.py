"""The bearing model as a first-order ODE for scipy's solve_ivp: the baseline of the
work-precision study (and of benchmarks/bearing.py)."""

from __future__ import annotations

import numpy as np

def ode_rhs(model, rotation_slots, spin_row):
    """y = (q, v) -> (q_dot, v_dot): q_dot = v except CRV slots, c_dot = H(c)^-T Omega (M.4d);
    v_dot = M^-1 g (diagonal M); the prescribed spin has v_dot = 0."""
    from bearingsim.dynamics.multibody.crv import crv_H

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
