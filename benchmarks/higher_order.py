"""Would a higher-order method spend fewer residuals than HHT-α at the accuracy bar? (docs/model.md §9)

    taskset -c 1 python -m benchmarks.higher_order

Over the work-precision window of helicopter-b-given-hinge (15 ms from the quasi-static start,
errors against the fixed-step reference of `pipeline/studies/work_precision.py`):
- the previous default (fixed 2e-6 s steps), whose errors are the accuracy bar;
- HHT-α at the default rtol and at 1.3e-6, 1.5e-6 and 2e-6 (where the bar is crossed);
- scipy's Radau IIA (three stages, order 5) with `jac_sparsity` at rtol 1e-3, as scipy runs it
  and with a fresh finite-difference Jacobian at the start of every step (so that a stale matrix
  cannot inflate its Newton iterations);
- scipy's BDF (variable order 1-5, NDF) with `jac_sparsity` at rtol 1e-4, as scipy runs it, and
  at 5e-5, 1e-4 and 2e-4 with the Newton stopping rule of a production BDF code (`CarriedRateBDF`):
  scipy's own rule needs a contraction rate measured inside the step, so at least two iterations.
scipy counts the residuals of its Newton iterations (three per Radau iteration, one per stage; one
per BDF iteration) in `nfev`, not those of its finite-difference Jacobians; this script also counts
the iterations of every Newton solve and the BDF orders used. A method breaks even with HHT-α when
its residuals per step times its step count reach HHT-α's residuals at the bar.
"""

from __future__ import annotations

import collections
import os
import warnings

import numpy as np
from scipy import integrate
from scipy.integrate._ivp import bdf, radau

COUNT = {"solves": 0, "iterations": 0, "diverged": 0}
ORDERS = collections.Counter()  # accepted BDF steps by order
_solve_collocation = radau.solve_collocation_system
_solve_bdf = bdf.solve_bdf_system
NLSCOEF = 0.1  # CVODE's default nonlinear convergence coefficient (CVodeSetNonlinConvCoef)


def _counted(solve):
    """A scipy Newton solve (returning (converged, n_iter, ...)) that adds to COUNT."""

    def counted(*args, **kwargs):
        out = solve(*args, **kwargs)
        COUNT["solves"] += 1
        COUNT["iterations"] += out[1]
        COUNT["diverged"] += not out[0]
        return out

    return counted


def _carried_rate_solve(fun, t_new, y_predict, c, psi, LU, solve_lu, scale, tol):
    """scipy's simplified Newton for a BDF step (same arguments) with a production code's stopping
    rule: stop when the estimated Newton error, eta times the last correction, is below NLSCOEF of
    the local-error tolerance in the units of the correction (1 / error constant of the order, as
    CVODE's `tq[4]`; Hindmarsh et al., ACM TOMS 31 (2005) 363-396, §2.1). eta = theta / (1 - theta)
    from the contraction theta measured in the step, and at the first iteration the last solve's eta
    carried over as max(eta_old, eps)^0.8 (Hairer & Wanner, Solving ODE II, §IV.8): one iteration
    can then suffice, as it does for HHT-α."""
    solver = CarriedRateBDF.stepping
    eta = max(solver.newton_eta, np.finfo(float).eps) ** 0.8
    tol_newton = NLSCOEF / solver.error_const[solver.order]
    d, y, dy_norm_old = 0, y_predict.copy(), None
    for k in range(bdf.NEWTON_MAXITER):
        f = fun(t_new, y)
        if not np.all(np.isfinite(f)):
            return False, k + 1, y, d
        dy = solve_lu(LU, c * f - psi - d)
        dy_norm = bdf.norm(dy / scale)
        if dy_norm_old is not None:
            rate = dy_norm / dy_norm_old
            if rate >= 1 or rate ** (bdf.NEWTON_MAXITER - k) / (1 - rate) * dy_norm > tol_newton:
                return False, k + 1, y, d
            eta = rate / (1 - rate)
        y += dy
        d += dy
        if dy_norm == 0 or eta * dy_norm < tol_newton:
            solver.newton_eta = eta
            return True, k + 1, y, d
        dy_norm_old = dy_norm
    return False, bdf.NEWTON_MAXITER, y, d


def _bdf_solve(*args, **kwargs):
    """scipy's Newton for a BDF step, or `_carried_rate_solve` while a `CarriedRateBDF` steps."""
    return (_carried_rate_solve if CarriedRateBDF.stepping else _solve_bdf)(*args, **kwargs)


class CountedBDF(integrate.BDF):
    """scipy's BDF, its accepted steps counted by order."""

    def _step_impl(self):
        out = super()._step_impl()
        ORDERS[self.order] += 1
        return out


class CarriedRateBDF(CountedBDF):
    """scipy's BDF with `_carried_rate_solve` as its Newton stopping rule."""

    stepping = None  # the instance inside its _step_impl: scipy calls its module's Newton function

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self.newton_eta = 1.0  # the last converged solve's eta (its first step has none)

    def _step_impl(self):
        CarriedRateBDF.stepping = self
        try:
            return super()._step_impl()
        finally:
            CarriedRateBDF.stepping = None


class FreshJacobianRadau(integrate.Radau):
    """scipy's Radau with the Jacobian re-evaluated (and both LU factors redone) before every step."""

    def _step_impl(self):
        self.J = self.jac(self.t, self.y, self.f)
        self.current_jac = True
        self.LU_real = self.LU_complex = None
        return super()._step_impl()


def main() -> None:
    from bearingsim.pipeline.scene import load_scene
    from bearingsim.pipeline.stages.simulate import build_model
    from bearingsim.pipeline.studies import work_precision as wp

    # scipy's num_jac multiplies the difference step of a column tenfold at every Jacobian whose
    # differences vanish (coordinates no force depends on, such as a ball's rotation angles) until it
    # overflows; those columns stay zero, so the overflow warnings say nothing about the comparison
    warnings.filterwarnings("ignore", category=RuntimeWarning, module="scipy.integrate._ivp.common")
    radau.solve_collocation_system = _counted(_solve_collocation)  # count every Newton solve's iterations
    bdf.solve_bdf_system = _counted(_bdf_solve)
    scene = load_scene("helicopter-b-given-hinge")
    params, start = build_model(scene)
    ivp = {"method": "Radau", "rtol": 1e-3, "atol": 1e-8, "sparse": True}
    methods = [wp.fixed_step_method(wp.PREVIOUS_DEFAULT_STEP, "HHT a=0.1 fixed h (previous default: the bar)"),
               wp.Method("HHT a=0.1 adaptive", "rtol = 1e-06", {**wp.ADAPTIVE_DEFAULT, "rtol": 1e-6}),
               *(wp.Method("HHT a=0.1 adaptive", f"rtol = {r:g}", {**wp.ADAPTIVE_DEFAULT, "rtol": r})
                 for r in (1.3e-6, 1.5e-6, 2e-6)),
               wp.Method("Radau, jac_sparsity", "rtol = 0.001", ivp=ivp),
               wp.Method("Radau, jac_sparsity, fresh Jacobian each step", "rtol = 0.001",
                         ivp={**ivp, "solver_class": FreshJacobianRadau}),
               wp.Method("BDF, jac_sparsity", "rtol = 0.0001",
                         ivp={"method": "BDF", "rtol": 1e-4, "atol": 1e-9, "sparse": True, "solver_class": CountedBDF}),
               *(wp.Method("BDF, jac_sparsity, carried-rate Newton test", f"rtol = {r:g}",
                           ivp={"method": "BDF", "rtol": r, "atol": r * 1e-5, "sparse": True,
                                "solver_class": CarriedRateBDF})
                 for r in (5e-5, 1e-4, 2e-4))]
    # atol = rtol x 1e-5, as the work-precision study's solve_ivp rows
    counts = []

    def progress(text):
        counts.append({**COUNT, "orders": dict(ORDERS)})
        print(text, flush=True)

    study = wp.run_study(params, start, scene.solver, False, progress=progress, methods=methods,
                         cfg=wp.StudyConfig(0.015, 5e-6, 1e-7, 1e4))
    counts.append({**COUNT, "orders": dict(ORDERS)})
    print(f"\n{scene.name}, 15 ms window, load average {os.getloadavg()[0]:.2f}")
    print(f"{'method':<64}{'steps':>7}{'residuals':>10}{'per step':>9}{'Newton/step':>12}{'diverged':>9}{'LU':>6}"
          f"{'centre um':>11}{'speed':>9}{'inner nm':>9}{'impacts':>9}  BDF orders 1-5")
    for i, r in enumerate(study["rows"]):
        it = counts[i + 2]["iterations"] - counts[i + 1]["iterations"]
        dv = counts[i + 2]["diverged"] - counts[i + 1]["diverged"]
        newton = f"{it / r['steps']:.2f}" if it else "-"
        orders = [counts[i + 2]["orders"].get(k, 0) - counts[i + 1]["orders"].get(k, 0) for k in range(1, 6)]
        print(f"{r['curve'] + ', ' + r['setting']:<64}{r['steps']:>7}{r['newton_iterations']:>10}"
              f"{r['newton_iterations'] / r['steps']:>9.2f}{newton:>12}{dv if it else '-':>9}{r['factorizations']:>6}"
              f"{r['cage_centre'] * 1e6:>11.2g}{r['cage_speed']:>9.2g}{r['inner_race'] * 1e9:>9.3f}"
              f"{r['impact_force']:>9.3%}  {' '.join(map(str, orders)) if any(orders) else ''}")
    print("residuals: HHT-alpha's Newton iterations (one residual each); scipy's nfev (the residuals of its")
    print("Newton iterations, three per Radau iteration, and one per accepted Radau step; not its")
    print("finite-difference Jacobians).")


if __name__ == "__main__":
    main()
