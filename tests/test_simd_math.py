"""The array exp and logs of dynamics/_speed/simd_math.py against libm (math.exp, math.log) and
against their plain-Python twins (py_func)."""

import math

import numpy as np

from bearingsim.dynamics._speed.simd_math import EXP_MAX, EXP_MIN, exp_array, log_array, log_array32


def test_exp_array_matches_math_exp_and_its_range_ends():
    rng = np.random.default_rng(3)
    x = np.concatenate([rng.uniform(EXP_MIN, EXP_MAX, 4000), rng.uniform(-1, 1, 1000), [0.0, EXP_MIN, EXP_MAX, -1e-300]])
    n = x.size
    out = np.empty(n)
    exp_array(x, n, np.empty(n), np.empty(n, dtype=np.int64), out)
    exact = np.array([math.exp(v) for v in x])
    assert np.all(np.abs(out / exact - 1.0) < 1e-15)
    # below the range: 0 (as libm, which underflows there); above: held at exp(EXP_MAX)
    ends = np.array([EXP_MIN - 1e-9, -745.5, -1e300, EXP_MAX + 5.0, 1e300])
    exp_array(ends, 5, np.empty(5), np.empty(5, dtype=np.int64), ends)  # in place: x and out may alias
    assert ends[:3].tolist() == [0.0, 0.0, 0.0] and ends[3] == ends[4] == math.exp(EXP_MAX)


def test_log_array_matches_math_log_below_and_above_one():
    rng = np.random.default_rng(5)
    z = np.concatenate([np.exp(rng.uniform(-700, 700, 4000)), 1.0 + rng.uniform(-1e-9, 1e-9, 200),
                        [1.0, 0.5, 2.0, math.sqrt(2.0), math.sqrt(0.5), 2.2250738585072014e-308]])
    n = z.size
    out = np.empty(n)
    log_array(z, n, np.empty(n), np.empty(n, dtype=np.int64), out)
    exact = np.log(z)
    assert np.all(np.abs(out - exact) <= 1e-13 * np.maximum(np.abs(exact), 1.0))


def test_log_array_above_one_matches_math_log_and_its_py_func():
    rng = np.random.default_rng(3)
    z = np.concatenate([1.0 + rng.uniform(0, 1e-9, 50), np.exp(rng.uniform(0, 700, 200)), [1.0, 2.0, math.sqrt(2.0)]])
    n = z.size
    out, slow = np.empty(n), np.empty(n)
    log_array(z, n, np.empty(n), np.empty(n, dtype=np.int64), out)
    log_array.py_func(z, n, np.empty(n), np.empty(n, dtype=np.int64), slow)
    exact = np.log(z)
    assert np.all(np.abs(out - exact) <= 1e-13 * np.maximum(exact, 1.0))
    assert np.allclose(out, slow, rtol=1e-14, atol=1e-15)  # FMA contraction: last-bit differences


def test_log_array32_matches_math_log():
    rng = np.random.default_rng(5)
    z = np.concatenate([1.0 + rng.uniform(0, 1e-3, 50), np.exp(rng.uniform(0, 43, 500)),  # z <= 2 x 1e18 + 1
                        [1.0, 2.0, math.sqrt(2.0), 4e18]]).astype(np.float32)
    n = z.size
    out, slow = np.empty(n), np.empty(n)
    scratch = (np.empty(n, dtype=np.float32), np.empty(n, dtype=np.int32))
    log_array32(z, n, *scratch, out)
    log_array32.py_func(z, n, *scratch, slow)
    exact = np.log(z.astype(np.float64))  # of the float32 argument: the kernel's own error only
    assert np.all(np.abs(out - exact) <= 3e-7 * np.maximum(exact, 1.0))
    assert np.allclose(out, slow, rtol=1e-6, atol=1e-7)
