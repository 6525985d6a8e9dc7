"""The float32 table lookup of the traction's residual passes (dynamics/_speed/table_lookup.py)
against exact arithmetic."""

from __future__ import annotations

import numpy as np
import pytest

from bearingsim.dynamics._speed.table_lookup import lerp_rows32

from .simd_reference import lerp_fma_reference


@pytest.mark.parametrize("n", [0, 1, 7, 8, 9, 16, 237, 320])
def test_lookup_gives_the_exact_fused_interpolation(n):
    """Rows picked as 8-byte words, interpolated by one fused multiply-add, against exact
    rational arithmetic rounded once (the fma) and then by the scale: the same bits, for every
    remainder of n modulo 8, indices past the table's end clamped to its last interval, and an
    index on a node exactly; nothing is written past n."""
    rng = np.random.default_rng(n + 3)
    flat = rng.uniform(1e-3, 3.0, 2 * 300).astype(np.float32)
    f_index = rng.uniform(0.0, 310.0, max(n, 1)).astype(np.float32)
    f_index[0] = 299.5 if n else f_index[0]  # beyond last = 298.999999: clamped
    if n > 2:
        f_index[2] = 17.0  # on a node: frac = 0
    inv_scale = 4.2e5
    ref = lerp_fma_reference(f_index[:n], flat, inv_scale)
    m = max(n, 1)
    out = np.full(m, np.nan, dtype=np.float32)
    scratch = (np.zeros(m, dtype=np.uint32), np.zeros(m, dtype=np.float32), np.zeros(m, dtype=np.int64))
    lerp_rows32(f_index, n, flat, inv_scale, out, *scratch)
    assert np.array_equal(out[:n], ref)
    if n == 0:
        assert np.isnan(out[0])


def test_the_fma_differs_from_a_separate_multiply_and_add():
    """The reference's single rounding is what the test above checks, not a coincidence of
    both roundings: on these inputs a separately rounded product and sum differ somewhere."""
    rng = np.random.default_rng(5)
    flat = rng.uniform(1e-3, 3.0, 2 * 300).astype(np.float32)
    f_index = rng.uniform(0.0, 298.0, 2000).astype(np.float32)
    i = f_index.astype(np.int64)
    frac = f_index - i.astype(np.float32)
    separate = (flat[2 * i] + frac * flat[2 * i + 1]) * np.float32(1.0)
    assert not np.array_equal(separate, lerp_fma_reference(f_index, flat, 1.0))
