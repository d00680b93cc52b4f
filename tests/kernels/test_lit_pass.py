"""The lit pass's vectorized span loop (MODE_COLOUR: z test, optional stencil test,
blend replace / ONE+ONE / SA+MSA) against the naive reference, bit for bit, over
random destination colours, stencil values and depths: every 8-bit blend rounding
case occurs many times in a window of a few thousand pixels."""

import numpy as np
import pytest
from kernel_helpers import (
    assert_planes_equal,
    full_state,
    random_planes,
    render_kernels,
    render_naive,
)

from vgxsim.state.codes import (
    BF_MSA,
    BF_ONE,
    BF_SA,
    BF_ZERO,
    CMP_ALWAYS,
    CMP_EQUAL,
    CMP_LEQUAL,
    D_CBLEND,
    D_MODE,
    MODE_COLOUR,
)
from vgxsim.state.derive import derive_states

W, H = 64, 48


@pytest.mark.parametrize("blend", [(BF_ONE, BF_ZERO), (BF_ONE, BF_ONE), (BF_SA, BF_MSA)])
@pytest.mark.parametrize("stencil", [False, True])
def test_lit_pass_matches_naive(blend, stencil):
    rng = np.random.default_rng(hash((blend, stencil)) % 2**32)
    cfg = dict(double=False, zbits=24, stencil=8 if stencil else 0)
    init = random_planes(rng, W, H, **cfg)
    init["z"][...] = rng.integers(-3, 4, size=(H, W)) * 1000  # ties for the EQUAL/LEQUAL tests
    if stencil:
        init["stencil"][...] = rng.integers(0, 3, size=(H, W))
    rs = full_state(W, H, zbuffer=True, zfunc=int(rng.choice([CMP_EQUAL, CMP_LEQUAL])),
                    stencil=stencil, sfunc=CMP_EQUAL if stencil else CMP_ALWAYS, sref=1,
                    blend_sf=blend[0], blend_df=blend[1],
                    zwritemask=int(rng.choice([0, 0xFFFFFF])))
    derived, _ = derive_states(rs.as_row()[None], cfg["stencil"], True, True)
    assert derived[0, D_MODE] == MODE_COLOUR and derived[0, D_CBLEND] < 3  # the fast loop
    cmds = []
    for _ in range(12):
        z = float(rng.integers(-3, 4) * 1000)
        verts = tuple((float(rng.uniform(-20, W + 20)), float(rng.uniform(-20, H + 20)), z,
                       tuple(float(c) for c in rng.uniform(0, 1, 4))) for _ in range(3))
        cmds.append(("triangle", verts, rs))
    want = render_naive(cmds, W, H, init=init, **cfg)
    assert not np.array_equal(want["front"], init["front"])
    for mode in ("span", "general"):
        got = render_kernels(cmds, W, H, init=init, mode=mode, **cfg)
        assert_planes_equal(got, want, f"mode={mode}")
