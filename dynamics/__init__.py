"""Contact kernels, bodies, hinge joint, HHT-α integrator, bearing model, quasi-static
solver (docs/model.md §4–§10). Stands alone: never imports fe_model or pipeline.

Layout: `contact/` (Hertz, ball–race and ball–pocket contact), `lubrication/` (film,
rheology, lubricant data), `traction/` (Eyring traction: reference quadrature and the fast
rule), `journal/` (cage–guiding-race contact), `multibody/` (the integrator, which knows
nothing of bearings), `bearing/` (the bearing model), `quasistatic/` (the equilibrium solver).
"""
