"""kernels/options.py: helpers compile once per argument types and refuse Python calls."""

from __future__ import annotations

import pytest

from vgxsim.kernels.options import callee, inline, jit


@inline
def _scaled(a, k):
    return a * k + k


@callee
def _out_of_line(a, flag):
    return _scaled(a, 3) if flag else -a


@jit(cache=False)
def _caller(a):
    # constants 0, 1, 2 would each be a Literal[int] specialisation in plain numba.njit
    return _scaled(a, 0) + _scaled(a, 1) + _scaled(a, 2) + _out_of_line(a, True)


def test_constant_arguments_share_one_compile():
    # 5*0+0 + 5*1+1 + 5*2+2 + (5*3+3) = 0 + 6 + 12 + 18
    assert _caller(5) == 36
    assert len(_scaled.signatures) == 1
    assert len(_out_of_line.signatures) == 1


@pytest.mark.parametrize("helper", [_scaled, _out_of_line])
def test_python_call_is_a_clear_error_not_a_crash(helper):
    with pytest.raises(TypeError, match="kernel helper"):
        helper(1, 2)
