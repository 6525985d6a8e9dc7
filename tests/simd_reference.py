"""Exact references for the float32 table lookup (tests only)."""

from __future__ import annotations

from fractions import Fraction

import numpy as np


def round_to_float32(x: Fraction) -> np.float32:
    """x correctly rounded to float32 (nearest, ties to even): the float64 nearest to x, then
    the nearest of the three float32 values around it, compared exactly."""
    c = np.float32(float(x))
    candidates = [np.nextafter(c, np.float32(-np.inf)), c, np.nextafter(c, np.float32(np.inf))]
    best = min(candidates, key=lambda v: (abs(Fraction(float(v)) - x), int(np.float32(v).view(np.uint32)) & 1))
    return np.float32(best)


def lerp_fma_reference(f_index: np.ndarray, flat: np.ndarray, inv_scale: float) -> np.ndarray:
    """What `table_lookup.lerp_rows32` must give, in float32: f = min(f_index, last), i = floor f,
    fma(f - i, flat[2i + 1], flat[2i]) (one rounding of the exact value) times the float32 scale."""
    last = np.float32(flat.size // 2 - 1.000001)
    scale = np.float32(inv_scale)
    out = np.empty(f_index.size, dtype=np.float32)
    for m, f in enumerate(np.asarray(f_index, dtype=np.float32)):
        f = f if f < last else last
        i = int(f)
        frac = np.float32(f - np.float32(i))  # exact: f and i share the exponent range
        exact = Fraction(float(frac)) * Fraction(float(flat[2 * i + 1])) + Fraction(float(flat[2 * i]))
        out[m] = np.float32(round_to_float32(exact) * scale)
    return out
