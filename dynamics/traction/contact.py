"""The traction of one ball–race contact, whatever its law: `contact_traction` sends a film law
to the fast engine (`fast.traction_fast`) and a law without film to its own kernel
(`laws.operations.dry_traction`), chosen by numba from the class of the rule's law bundle, so
that a model compiles the path of its own law only."""

from __future__ import annotations

from numba.extending import overload

from .._speed.compile_policy import NO_REFCOUNT
from .fast import FLAG_OK, traction_fast
from .laws import LAWS, operations


def contact_traction(tr, F_n, a, b, p_h, h, du0, dv0, w_s, u, out, jacobian):
    """Traction on the ball into out[0:3] = (F_x, F_y, M_z) and out[3:12] = their Jacobian in
    (du0, dv0, w_s) (units as `traction_fast`, u [m/s] the mean surface speed); returns the engine's flag bits (FLAG_OK for a law
    without film). tr: the `fast.TractionRule`, whose `law` is the law's bundle; F_n [N] the
    normal load (laws without film scale with it)."""
    if LAWS.law_of(type(tr.law)).film:
        return traction_fast(a, b, p_h, h, du0, dv0, w_s, u, tr, out, jacobian)
    operations.dry_traction(tr.law, F_n, a, b, du0, dv0, w_s, out)
    return FLAG_OK


@overload(contact_traction, jit_options=NO_REFCOUNT, inline="always")
def _contact_traction(tr, F_n, a, b, p_h, h, du0, dv0, w_s, u, out, jacobian):
    law = tr.types[tr.fields.index("law")]
    if LAWS.law_of(law.instance_class).film:
        def film(tr, F_n, a, b, p_h, h, du0, dv0, w_s, u, out, jacobian):
            return traction_fast(a, b, p_h, h, du0, dv0, w_s, u, tr, out, jacobian)
        return film

    def dry(tr, F_n, a, b, p_h, h, du0, dv0, w_s, u, out, jacobian):
        operations.dry_traction(tr.law, F_n, a, b, du0, dv0, w_s, out)
        return FLAG_OK
    return dry
