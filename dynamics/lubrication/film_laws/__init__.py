"""The EHD central-film laws and their registry (docs/model.md §6.3; docs/contact_laws.md).

`LAWS` is the registry (`dynamics.registry`): plain Python, so that loading a scene loads no
numba. Each entry names the module that states the law; the module defines the parameter bundle
`Params`, `pack(options, lubricant)` and `central_film(law, F, Rx, Ry, E_eff, eta0, alpha_p, u_s)`
[m] (see `hamrock_dowson`). The force kernel reaches a law through `operations.central_film`, by
the class of its bundle, contact by contact. The entries' flag `batch`: the time loop takes the
law's film of every contact at once (`lubrication.film.film_central_nvm_batch`, the NVM law
only), not contact by contact.

A new law is one module and one `LAWS.register(...)` line.
"""

from __future__ import annotations

from ...registry import Law, Registry

LAWS = Registry("film", __name__, operations=("central_film",))

LAWS.register(Law("nvm", ".nvm", film=True, flags={"batch": True},
                  doc="Nijenbanning-Venner-Moes (1994): the four Moes asymptotes blended"))
LAWS.register(Law("hamrock-dowson", ".hamrock_dowson", film=True, flags={"batch": False},
                  doc="Hamrock-Dowson (1977) central film"))
