"""`like(x, value)`: the constant `value` in the floating-point width of `x` (float32 or float64),
so that one law function serves the engine's float32 passes and its float64 ones without a
float32 value meeting a float64 constant (which widens the whole expression)."""

from __future__ import annotations

import numpy as np
from numba import types
from numba.extending import overload


def like(x, value):
    """`value` as x's floating-point type (Python: as float)."""
    return type(x)(value) if isinstance(x, (np.floating, float)) else float(value)


@overload(like, inline="always")
def _like(x, value):
    if isinstance(x, types.Float) and x.bitwidth == 32:
        return lambda x, value: np.float32(value)
    return lambda x, value: np.float64(value)
