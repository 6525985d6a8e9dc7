"""Linear interpolation in a float32 table, for the float32 traction passes (docs/model.md §6.4).

The table holds rows (v_i, v_(i+1) - v_i), flattened; a lookup at position f computes, per node m,

    f = min(f_index[m], last),   i = floor(f),   out[m] = fma(f - i, v_(i+1) - v_i, v_i) * scale

in float32. Reading a row at a data-dependent position is a gather, which LLVM leaves scalar, so
the lookup is split into three passes: the row and fraction (vectorised, and fused by the
traction into its slip pass), the rows picked as one 8-byte word each in a pass of nothing but
loads (`pick_rows`), and the interpolation (vectorised, fused into the Eyring pass). LLVM
contracts the multiply and add into one fused multiply-add on a CPU with FMA, which is what the
tests check against exact arithmetic. docs/performance.md gives the cost.
"""

from __future__ import annotations

import numba
import numpy as np

from .compile_policy import VEC


@numba.njit(cache=True, inline="always")
def last_position32(flat):
    """The largest table position a lookup takes, in float32: just short of the last row of
    flat, so that its row is the last full interval."""
    return np.float32(flat.size // 2 - 1.000001)


@numba.njit(cache=True, inline="always")
def split_position32(f_index, last):
    """(i, f - i) of f = min(f_index, last): the row (uint32) and the fraction within it (float32)."""
    f = min(f_index, last)
    i = np.uint32(f)
    return i, f - np.float32(i)


@numba.njit(cache=True, inline="always")
def lerp_picked32(pair, m, frac, scale):
    """fma(frac, v_(i+1) - v_i, v_i) * scale from node m's picked row, `pair` being the picked
    rows viewed as float32 (v_i, v_(i+1) - v_i) pairs."""
    return (pair[2 * m] + frac * pair[2 * m + 1]) * scale


@numba.njit(**VEC)
def pick_rows(row, n, rows, picked):
    """picked[m] = rows[row[m]] for m < n: the table's rows read as one 8-byte word each
    (`flat.view(np.int64)`), row uint32, picked int64. The index arithmetic lives in the
    vectorised passes around this one, which is left only its loads."""
    for m in range(n):
        picked[m] = rows[np.uint64(row[m])]


@numba.njit(**VEC)
def lerp_rows32(f_index, n, flat, inv_scale, out, row, frac, picked):
    """out[m] = the lookup of the module docstring at f_index[m], m < n, with scale = inv_scale
    as float32, in its three passes. row (uint32), frac (float32), picked (int64): scratch of
    length >= n. The float32 traction passes fuse the first and last pass into their
    neighbours (`traction.fast`); this is the lookup on its own, for tests and benchmarks."""
    last = last_position32(flat)
    scale = np.float32(inv_scale)
    for m in range(n):
        row[m], frac[m] = split_position32(f_index[m], last)
    pick_rows(row, n, flat.view(np.int64), picked)
    pair = picked.view(np.float32)
    for m in range(n):
        out[m] = lerp_picked32(pair, m, frac[m], scale)
