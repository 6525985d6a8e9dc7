"""The cage–land laws and their registry (docs/model.md §8; docs/contact_laws.md).

A land law says how the film and the metal share the load of the guiding land as the cage's
eccentricity ratio eps = e/C grows: `weights(law, eps)` returns the weights of the film force
and torque and their slopes, the film clearance over C, whether metal can touch and whether the
film terms are clipped (see `hybrid`). The short journal bearing (`journal.short_bearing`)
evaluates the film and the metal contact and blends them by these weights, reaching the law
through `operations.weights`, by the class of its bundle.

`LAWS` is the registry (`dynamics.registry`): plain Python, so that a scene's
choices and checks read it without importing the law modules. Each module defines `Params`, `pack(eps0)` (eps0: `physics.cage_race_boundary`) and
`weights`. An entry's `film`: the law needs the lubricant's viscosity; its flag `boundary`: the
film clearance is C (1 + eps0), so eps0 C is the film at first metal contact (outputs, the
crush screen and the land-film check read it).

A new law is one module and one `LAWS.register(...)` line.
"""

from __future__ import annotations

from ...registry import Law, Registry

LAWS = Registry("land", __name__, operations=("weights",))

LAWS.register(Law("hybrid", ".hybrid", film=True, flags={"boundary": True},
                  doc="hybrid film/metal (paper eqs. 25-31)"))
LAWS.register(Law("hydrodynamic", ".hydrodynamic", film=True, flags={"boundary": False},
                  doc="film only"))
LAWS.register(Law("dry", ".dry", flags={"boundary": False}, doc="metal only"))
LAWS.register(Law("none", ".no_land", flags={"boundary": False}, doc="no contact"))
