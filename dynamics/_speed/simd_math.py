"""exp and log over arrays, in loops LLVM vectorises (docs/model.md §6.3, §6.4).

numba compiles `math.exp` and `math.log` to scalar libm calls, which no loop around them can
vectorise (this llvmlite has no SVML). The residual takes several thousand logarithms (the
Eyring stress at every traction node) and ~700 exp/log (the film formula at 2Z contacts) per
evaluation, so these kernels take them in branch-free passes over contiguous arrays instead:
the float's exponent and mantissa are taken apart (and put together) through an int64 view of
the bits, and the rest is a polynomial. Callers pass their own scratch; nothing allocates.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from .compile_policy import VEC

LN2 = math.log(2.0)
_INV_LN2 = 1.0 / LN2
# ln 2 split for Cody-Waite reduction: LN2_HI has trailing zero bits, so k LN2_HI is exact for |k| < 2^11
_LN2_HI = 6.93147180369123816490e-01
_LN2_LO = 1.90821492927058770002e-10
_MANTISSA = 0x000FFFFFFFFFFFFF
_EXP_ONE = 0x3FF0000000000000
_SQRT2_MANTISSA = 0x6A09E667F3BCD  # mantissa bits of sqrt(2)
# the same for float32 (23 mantissa bits, exponent bias 127)
_MANTISSA32 = np.int32(0x007FFFFF)
_EXP_ONE32 = np.int32(0x3F800000)
_SQRT2_MANTISSA32 = np.int32(0x3504F3)
# exp_array's range: below EXP_MIN the result is 0 (exp(-708.4) is the smallest normal float),
# above EXP_MAX it is held at exp(EXP_MAX) (~8e307) instead of overflowing
EXP_MIN, EXP_MAX = -708.0, 709.0
# exp_array without "reassoc": it would fold (x - k LN2_HI) - k LN2_LO into x - k ln 2 and lose
# the reduction's exactness (2e-14 relative at |x| ~ 700 where it did); the loop has no
# reduction, so it vectorises without it
_VEC_EXACT = {**VEC, "fastmath": {"nsz", "arcp", "contract", "afn"}}


@numba.njit(**VEC)
def log_array(z, n, exponent, mantissa_bits, out):
    """out[m] = ln z[m] for positive normal z (not subnormal, finite), m < n; |error| < 1e-13
    max(1, |ln z|) (tested against math.log).

    z = 2^e m with m in [sqrt(1/2), sqrt(2)) taken apart through an int64 view of the bits;
    ln m = 2 atanh(s), s = (m - 1)/(m + 1), |s| <= 0.172, series to s^15 (next term
    2 s^17/17 < 1.2e-14). exponent (float64) and mantissa_bits (int64): scratch of length >= n.
    """
    zi = z.view(np.int64)
    for m in range(n):
        bits = zi[m]
        mant = bits & _MANTISSA
        up = np.int64(mant > _SQRT2_MANTISSA)
        exponent[m] = float((bits >> 52) - 1023 + up)
        mantissa_bits[m] = mant | (_EXP_ONE - (up << 52))
    mf = mantissa_bits.view(np.float64)
    for m in range(n):
        x = mf[m]
        s = (x - 1.0) / (x + 1.0)
        s2 = s * s
        p = 1.0 / 15.0
        p = p * s2 + 1.0 / 13.0
        p = p * s2 + 1.0 / 11.0
        p = p * s2 + 1.0 / 9.0
        p = p * s2 + 1.0 / 7.0
        p = p * s2 + 1.0 / 5.0
        p = p * s2 + 1.0 / 3.0
        p = p * s2 + 1.0
        out[m] = exponent[m] * LN2 + 2.0 * s * p


@numba.njit(**VEC)
def log_array32(z, n, exponent, mantissa_bits, out):
    """out[m] = ln z[m] for float32 z >= 1, m < n, computed in float32 (out is float32 in the
    traction's residual-only passes, traction/fast.py); |error| < 3e-7 max(1, ln z).

    `log_array` in float32: z = 2^e m, m in [sqrt(1/2), sqrt(2)), ln m = 2 atanh(s) to s^9 (next
    term 2 s^11/11 < 7e-10); e ln 2 with ln 2 rounded to float32 (relative 3e-8). exponent
    (float32) and mantissa_bits (int32): scratch of length >= n."""
    zi = z.view(np.int32)
    for m in range(n):
        bits = zi[m]
        mant = bits & _MANTISSA32
        up = np.int32(mant > _SQRT2_MANTISSA32)
        exponent[m] = np.float32((bits >> np.int32(23)) - np.int32(127) + up)
        mantissa_bits[m] = mant | (_EXP_ONE32 - (up << np.int32(23)))
    mf = mantissa_bits.view(np.float32)
    one = np.float32(1.0)
    ln2 = np.float32(LN2)
    for m in range(n):
        x = mf[m]
        s = (x - one) / (x + one)
        s2 = s * s
        p = np.float32(1.0 / 9.0)
        p = p * s2 + np.float32(1.0 / 7.0)
        p = p * s2 + np.float32(1.0 / 5.0)
        p = p * s2 + np.float32(1.0 / 3.0)
        p = p * s2 + one
        out[m] = exponent[m] * ln2 + np.float32(2.0) * s * p


@numba.njit(**_VEC_EXACT)
def exp_array(x, n, mantissa, exponent_bits, out):
    """out[m] = exp(x[m]), m < n; relative error < 1e-15 for x in [EXP_MIN, EXP_MAX] (tested
    against math.exp), 0 below EXP_MIN, exp(EXP_MAX) above. x and out may be the same array.

    x = k ln 2 + r with k = round(x / ln 2), |r| <= ln(2)/2 (Cody-Waite: ln 2 in two parts, so
    r carries no rounding of k ln 2); e^r by its Taylor series to r^13 (next term
    0.347^14/14! < 4e-18); 2^k built in the exponent bits through an int64 view.
    mantissa (float64: e^r) and exponent_bits (int64: 2^k): scratch of length >= n.
    """
    for m in range(n):
        xm = min(max(x[m], EXP_MIN), EXP_MAX)
        k = math.floor(xm * _INV_LN2 + 0.5)
        r = (xm - k * _LN2_HI) - k * _LN2_LO
        p = 1.0 / 6227020800.0
        p = p * r + 1.0 / 479001600.0
        p = p * r + 1.0 / 39916800.0
        p = p * r + 1.0 / 3628800.0
        p = p * r + 1.0 / 362880.0
        p = p * r + 1.0 / 40320.0
        p = p * r + 1.0 / 5040.0
        p = p * r + 1.0 / 720.0
        p = p * r + 1.0 / 120.0
        p = p * r + 1.0 / 24.0
        p = p * r + 1.0 / 6.0
        p = p * r + 0.5
        p = p * r + 1.0
        p = p * r + 1.0
        # the underflow test reads x before out overwrites it (they may alias)
        mantissa[m] = p if x[m] >= EXP_MIN else 0.0
        exponent_bits[m] = (np.int64(k) + 1023) << 52
    scale = exponent_bits.view(np.float64)
    for m in range(n):
        out[m] = mantissa[m] * scale[m]
