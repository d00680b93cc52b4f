"""The exact soft-shadow reduction against hand-computed acbuf arithmetic."""

import numpy as np
import pytest

from vgxsim.farm.exact import (
    ReductionError,
    accumulate_frames,
    pack_rgba,
    reduce_partials,
    resolve,
    unpack_rgba,
)
from vgxsim.farm.tasks import Partial


def _flat(r, g, b, a, shape=(2, 3)):
    img = np.zeros((*shape, 4), np.uint8)
    img[...] = (r, g, b, a)
    return img


def _partial(start, stop, acc):
    return Partial(start, stop, acc, None, 128)


def test_pack_puts_red_in_the_low_byte():
    img = _flat(1, 2, 3, 4)
    assert pack_rgba(img)[0, 0] == 0x04030201
    assert np.array_equal(unpack_rgba(pack_rgba(img)), img)


def test_accumulate_frames_sums_components():
    acc = accumulate_frames([_flat(10, 20, 30, 255), _flat(1, 2, 3, 255)])
    assert acc.dtype == np.int16
    assert acc[1, 2].tolist() == [11, 22, 33, 510]


def test_acbuf_saturates_at_32767_like_one_saturation_of_the_sum():
    # 129 frames of 255 = 32895 > 32767: acbuf clips; so does one clip of the sum
    frames = [_flat(255, 0, 100, 255)] * 129
    seq = accumulate_frames(frames)
    assert seq[0, 0].tolist() == [32767, 0, 12900, 32767]
    parts = [_partial(0, 50, accumulate_frames(frames[:50])),
             _partial(50, 129, accumulate_frames(frames[50:]))]
    assert np.array_equal(reduce_partials(parts, 129), seq)


def test_partials_that_saturated_on_their_own_still_reduce_exactly():
    frames = [_flat(255, 255, 255, 255)] * 300
    parts = [_partial(a, b, accumulate_frames(frames[a:b])) for a, b in ((0, 140), (140, 300))]
    assert parts[0].acc[0, 0, 0] == 32767  # saturated inside the worker
    assert np.array_equal(reduce_partials(parts[::-1], 300), accumulate_frames(frames))


def test_reduce_refuses_gaps_overlaps_and_negative_sums():
    a = accumulate_frames([_flat(1, 1, 1, 1)])
    with pytest.raises(ReductionError):
        reduce_partials([_partial(0, 1, a), _partial(2, 3, a)], 3)
    with pytest.raises(ReductionError):
        reduce_partials([_partial(0, 2, a), _partial(1, 3, a)], 3)
    with pytest.raises(ReductionError):
        reduce_partials([_partial(0, 1, a)], 2)
    neg = a.copy()
    neg[0, 0, 0] = -1
    with pytest.raises(ReductionError):
        reduce_partials([_partial(0, 1, neg)], 1)


def test_resolve_is_ac_return_rounding_half_up():
    acc = np.zeros((1, 2, 4), np.int16)
    acc[0, 0] = (765, 1, 3, 32767)   # /3 -> 255, 0.333 -> 0, 1, 10922.3 -> 255 (clamped)
    acc[0, 1] = (3, 2, 5, 0)         # /2 (frames=2 below)
    assert resolve(acc[:, :1], 3)[0, 0].tolist() == [255, 0, 1, 255]
    # floor(x + 0.5): 1.5 -> 2, 1.0 -> 1, 2.5 -> 3
    assert resolve(acc[:, 1:], 2)[0, 0].tolist() == [2, 1, 3, 0]
