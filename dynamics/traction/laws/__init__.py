"""The ball–race traction laws and their registry (docs/model.md §6.4; docs/contact_laws.md).

`LAWS` is the registry (`dynamics.registry`): plain Python, so that a scene's
choices and checks read it without importing the law modules. Each entry names the module that states the law. A film law's module defines
`stress_scale(law, p_h)` and `response(law, k, r)` (see `eyring`); a law without film defines
`dry_traction(law, F_n, a, b, du0, dv0, w_s, out)` (see `coulomb`). Every module defines its
parameter bundle `Params` and `pack(options, lubricant)`. The reference quadrature and the fast
engine reach a law through `operations`, by the class of its bundle. The entries' flags:
`load_exponent`, |T| ~ F_n^e at fixed slip (the Newton tangent's load coupling).

A new law is one module and one `LAWS.register(...)` line.
"""

from __future__ import annotations

from ...registry import Law, Registry

LAWS = Registry("traction", __name__, operations=("stress_scale", "response"),
                dry_operations=("dry_traction",))

LAWS.register(Law(
    "eyring", ".eyring", film=True, flags={"load_exponent": 2.0 / 3.0},
    doc="Eyring shear thinning, tau = tau0 asinh(eta |s|/(tau0 h)) (the plateau grows like the contact area, "
        "F_n^(2/3))"))
LAWS.register(Law(
    "limiting-shear", ".limiting_shear", film=True, flags={"load_exponent": 1.0},
    doc="Bair-Winer limiting shear, tau = tau_L (1 - exp(-eta |s|/(tau_L h))), "
        "tau_L = physics.limiting_shear_coefficient x mean Hertz pressure"))
LAWS.register(Law("coulomb", ".coulomb", flags={"load_exponent": 1.0}, doc="regularised Coulomb friction (dry)"))
LAWS.register(Law("none", ".no_traction", flags={"load_exponent": 0.0}, doc="no traction"))
