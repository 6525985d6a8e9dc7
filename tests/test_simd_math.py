"""The array exp and log of dynamics/simd_math.py against libm (math.exp, math.log)."""

import math

import numpy as np

from bearingsim.dynamics.simd_math import EXP_MAX, EXP_MIN, exp_array, log_array


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
