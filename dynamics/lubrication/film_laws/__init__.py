"""The EHD central-film laws and their registry (docs/model.md §6.3; docs/contact_laws.md).

`LAWS` is the registry (`dynamics.registry`): plain Python, so that a scene's
choices and checks read it without importing the law modules. Each entry names the module that states the law; the module defines the parameter bundle
`Params`, `pack(options, lubricant)` and `central_film(law, F, Rx, Ry, E_eff, eta0, alpha_p, u_s)`
[m] (see `hamrock_dowson`). The force kernel reaches a law through `operations.central_film`, by
the class of its bundle, contact by contact; the NVM law's bundle makes the time loop take the
film of every contact at once instead (`lubrication.film.film_central_nvm_batch`, the engine's
own path for that law).

A new law is one module and one `LAWS.register(...)` line.
"""

from __future__ import annotations

from ...registry import Law, Registry

LAWS = Registry("film", __name__, operations=("central_film",))

LAWS.register(Law("nvm", ".nvm", film=True,
                  doc="Nijenbanning-Venner-Moes (1994): the four Moes asymptotes blended"))
LAWS.register(Law("hamrock-dowson", ".hamrock_dowson", film=True,
                  doc="Hamrock-Dowson (1977) central film"))
