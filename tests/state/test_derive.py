"""The numpy state derivation equals the compiled reference in kernels/fragment.py."""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from vgxsim.kernels.fragment import derive_states as derive_compiled
from vgxsim.state.derive import derive_states
from vgxsim.state.raster import RasterState


@settings(max_examples=200, deadline=None)
@given(st.lists(st.tuples(
    st.booleans(), st.integers(0, 7), st.sampled_from([0, 0xFFFFFFFF, 0x00FF00]),
    st.booleans(), st.integers(0, 300), st.integers(0, 7), st.sampled_from([0xFF, 0x0F, 0x81]),
    st.integers(0, 5), st.integers(0, 5), st.integers(0, 5), st.sampled_from([0xFF, 0x3C, 0]),
    st.integers(0, 8), st.integers(0, 7), st.sampled_from([3, 6, 0]),
    st.sampled_from([0, 0xFFFFFFFF, 0xFF]), st.sampled_from([7, 3]),
    st.booleans(), st.booleans()), min_size=1, max_size=6),
    st.integers(0, 8), st.booleans(), st.booleans())
def test_numpy_derivation_equals_compiled(specs, planes, has_colour, has_z):
    rows = []
    for (zb, zf, zwm, sten, ref, sf, sm, fa, pa, zp, swm, bsf, bdf, lo, wm, af, fr, bk) in specs:
        rows.append(RasterState(
            zbuffer=zb, zfunc=zf, zwritemask=zwm, stencil=sten, sref=ref, sfunc=sf, smask=sm,
            sfail=fa, spass=pa, szpass=zp, swritemask=swm, blend_sf=bsf, blend_df=bdf,
            logicop=lo, wmpack=wm, afunc=af, draw_front=fr, draw_back=bk).as_row())
    states = np.stack(rows)
    d1, t1 = derive_states(states, planes, has_colour, has_z)
    d2, t2 = derive_compiled(states, planes, has_colour, has_z)
    np.testing.assert_array_equal(d1, d2)
    np.testing.assert_array_equal(t1, t2)
