"""The ball–pocket normal-force laws and their registry (docs/model.md §7; docs/contact_laws.md).

A pocket law gives the normal force of a ball on its pocket wall from the penetration delta,
its rate and the remembered impact speed: `normal_force(law, delta, delta_dot, impact_speed)`
returns (F_n, dF_n/d delta, dF_n/d delta_dot) (see `hertz_hysteresis`). The pocket geometry,
the friction and the wrenches are the contact's (`contact.pocket`), which reaches the law
through `operations.normal_force`, by the class of its bundle.

`LAWS` is the registry (`dynamics.registry`): plain Python, so that a scene's
choices and checks read it without importing the law modules. Each module defines `Params`, `normal_force` and
`pack(hertz_constant, restitution, damping_model, reference_impact_speed)`: the Hertz constant
k_h of the ball in its pocket [N/m^1.5] and the scene's impact options
(`physics.pocket_restitution`, the damping model, the floor of the impact speed [m/s]).

A new law is one module and one `LAWS.register(...)` line.
"""

from __future__ import annotations

from ...registry import Law, Registry

LAWS = Registry("pocket", __name__, operations=("normal_force",))

LAWS.register(Law("hertz-hysteresis", ".hertz_hysteresis",
                  doc="Hertz with hysteresis damping (Hunt-Crossley family, Flores et al. 2011 factor)"))
