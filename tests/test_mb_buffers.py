"""Output buffers of the compiled loop (dynamics/multibody/buffers.py)."""

import pickle

import numpy as np
import pytest

from bearingsim.dynamics.multibody.buffers import zeroed


@pytest.mark.parametrize("shape", [7, (3, 5), (0, 4), (2, 0)])
def test_zeroed_is_a_writable_zero_array_like_np_zeros(shape):
    a = zeroed(shape)
    ref = np.zeros(shape)
    assert a.shape == ref.shape and a.dtype == np.float64
    assert a.flags.c_contiguous and a.flags.writeable
    assert not a.any()
    a[...] = 2.5
    assert (a == 2.5).all()


def test_zeroed_views_keep_the_map_alive_and_pickle_by_value():
    rows = zeroed((1000, 3))
    rows[:, 1] = np.arange(1000)
    head = rows[:10]  # the records a run keeps are views like this one
    del rows
    assert head[9, 1] == 9.0
    back = pickle.loads(pickle.dumps(head))
    np.testing.assert_array_equal(back, head)


def test_zeroed_large_array_is_zero_everywhere():
    # 8 MB: past numpy's 4 MB huge-page threshold, the case the helper exists for
    a = zeroed((1024, 1024), dtype=np.float64)
    assert a.nbytes == 8 * 1024 * 1024
    assert float(np.abs(a).max()) == 0.0
