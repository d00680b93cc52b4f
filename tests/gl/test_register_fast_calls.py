"""zbuffer, zfunction, swritemask, backface, frontface, shademodel and linewidth's
valid paths (gl/_raster.py register_call, FAST_CALLS) store the register values
their general paths store (ints and GL tokens), so the raster snapshot keys and the
planes are the same with the switch on and off; values they do not take reach the
general path, which raises the GLError naming the call."""

from __future__ import annotations

import numpy as np
import pytest

from vgxsim import GL, gl
from vgxsim.gl import _core
from vgxsim.gl._core import session

CALLS = [("zbuffer", (0, 1, 5, GL.TRUE if hasattr(GL, "TRUE") else 1)),
         ("zfunction", (GL.ZF_LEQUAL, GL.ZF_ALWAYS, 1, 4)),
         ("swritemask", (0xFF, -1, 1 << 40, 3)),
         ("backface", (0, 1, 2)), ("frontface", (0, 1)),
         ("shademodel", (GL.FLAT, GL.GOURAUD, 0, 1)), ("linewidth", (1, 2, 3))]


def _render(seed: int, fast: bool, monkeypatch):
    monkeypatch.setattr(_core, "FAST_CALLS", fast)
    session.reset()
    rng = np.random.default_rng(seed)
    try:
        gl.prefsize(24, 20)
        gl.winopen("regs")
        gl.RGBmode()
        gl.stensize(8)
        gl.gconfig()
        ctx = session.windows[session.current]
        keys = []
        for _ in range(40):
            name, values = CALLS[int(rng.integers(0, len(CALLS)))]
            getattr(gl, name)(values[int(rng.integers(0, len(values)))])
            keys.append(repr(ctx.raster._key()))
            gl.cpack(int(rng.integers(0, 1 << 32)))
            gl.bgnpolygon()
            x, y = (float(v) for v in rng.uniform(0, 16, 2))
            for p in ((x, y, 0.0), (x + 6.0, y + 1.0, 0.0), (x + 2.0, y + 7.0, 0.0)):
                gl.v3f(p)
            gl.endpolygon()
        return keys, ctx.read_rgba().copy()
    finally:
        session.reset()
        monkeypatch.setattr(_core, "FAST_CALLS", True)
        session.refresh()


@pytest.mark.parametrize("seed", range(4))
def test_register_calls_valid_paths_store_what_the_general_paths_store(seed, monkeypatch):
    fast_keys, fast_rgba = _render(seed, True, monkeypatch)
    slow_keys, slow_rgba = _render(seed, False, monkeypatch)
    assert fast_keys == slow_keys
    assert np.array_equal(fast_rgba, slow_rgba)


@pytest.mark.parametrize("call, args, error, pattern", [
    ("zfunction", (8,), gl.GLValueError, r"zfunction\(8\): func 8 is not a valid token"),
    ("zbuffer", (1.0,), gl.GLTypeError, r"zbuffer\(1.0\)"),
    ("zbuffer", (1 << 40,), gl.GLValueError, r"does not fit in 32"),
    ("shademodel", (2,), gl.GLValueError, r"shademodel\(2\): mode 2 is not a valid"),
    ("linewidth", (0,), gl.GLValueError, r"linewidth\(0\): n 0 is outside"),
    ("backface", (1, 2), gl.GLTypeError, r"backface\(1, 2\): expected 1 argument"),
])
def test_bad_register_arguments_raise_naming_the_call(gl_window, call, args, error, pattern):
    gl_window(8, 6)
    with pytest.raises(error, match=pattern):
        getattr(gl, call)(*args)
