"""The ball–race traction laws and their registry (docs/model.md §6.4; docs/contact_laws.md).

Each film law is one module with two numba functions, `stress_scale(parameter, p_h)` and
`response(k, r)` (see `eyring`); the reference quadrature and the fast engine take the law as
its integer code and reach it through `dispatch.stress_scale` and `dispatch.response`. `LAWS`
(plain Python, so that loading a scene loads no numba) tells the rest of the package what a
law needs: the scene's choices (`ModelOptions.traction`), the
parameter packing (`bearing.params`), the load exponent of the Newton tangent
(`bearing.race_forces`) and the scene check that a lubricant is given (`pipeline.scene.load`).

A new film law is one module, one entry in `LAWS` and its branch in `dispatch`.
"""

from __future__ import annotations

from dataclasses import dataclass

NONE, COULOMB, EYRING, LIMITING_SHEAR = 0, 1, 2, 3


@dataclass(frozen=True)
class TractionLaw:
    """What the model needs to know of a traction law besides its kernel."""

    code: int               # the integer the kernels dispatch on
    load_exponent: float    # |T| ~ F_n^load_exponent at fixed slip (the Newton tangent's load coupling)
    film: bool              # a film law: needs a [lubricant] and the EHD film, runs in the film engine
    doc: str


LAWS = {
    "eyring": TractionLaw(EYRING, 2.0 / 3.0, True,
                          "Eyring shear thinning, tau = tau0 asinh(eta |s|/(tau0 h)) (the plateau grows like the "
                          "contact area, F_n^(2/3))"),
    "limiting-shear": TractionLaw(LIMITING_SHEAR, 1.0, True,
                                  "Bair-Winer limiting shear, tau = tau_L (1 - exp(-eta |s|/(tau_L h))), "
                                  "tau_L = physics.limiting_shear_coefficient x mean Hertz pressure"),
    "coulomb": TractionLaw(COULOMB, 1.0, False, "regularised Coulomb friction (dry)"),
    "none": TractionLaw(NONE, 0.0, False, "no traction"),
}
