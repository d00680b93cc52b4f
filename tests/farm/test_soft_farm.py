"""Soft shadows on the farm equal api.render(soft=N) (the program's sequential acbuf
loop) bit for bit, whatever the number of workers and the cut into tasks."""

import numpy as np
import pytest

from vgxsim.farm import LocalExecutor, soft_shadows, spin
from vgxsim.farm.jobs import FarmTaskError, sample_chunks
from vgxsim.shadow import api

SIZE = (20, 16)


def test_sample_chunks_cover_every_sample_once():
    assert sample_chunks(7, 3) == [(0, 2), (2, 5), (5, 7)]
    assert sample_chunks(2, 5) == [(0, 1), (1, 2)]


@pytest.mark.parametrize("chunks", [1, 3, 8])
def test_in_process_soft_shadow_equals_the_program(cubes, reference, chunks):
    ref = reference(cubes, soft=8, size=SIZE, seed=7)
    with LocalExecutor() as ex:
        got = soft_shadows(ex, cubes, 8, chunks=chunks, size=SIZE, seed=7)
    assert np.array_equal(got.colour, ref.colour)
    assert np.array_equal(got.depth, ref.depth)
    assert got.stencil.shape == (0, SIZE[1], SIZE[0]) and got.stencil_zero == ref.stencil_zero
    # jitter matters here: the soft image is not the hard one
    assert not np.array_equal(ref.colour, reference(cubes, size=SIZE).colour)


def test_32_sample_soft_shadow_identical_on_1_2_3_workers_and_in_process(cubes, reference):
    pytest.importorskip("distributed")
    from vgxsim.farm import DaskExecutor

    ref = reference(cubes, soft=32, size=SIZE)
    images = {}
    with LocalExecutor() as ex:
        images["in-process"] = soft_shadows(ex, cubes, 32, chunks=5, size=SIZE)
    for n in (1, 2, 3):
        with DaskExecutor(n_workers=n, processes=False) as ex:
            images[n] = soft_shadows(ex, cubes, 32, size=SIZE)
    for name, frame in images.items():
        assert np.array_equal(frame.colour, ref.colour), name
        assert np.array_equal(frame.depth, ref.depth), name


def test_spin_on_two_workers_equals_render_spin(cubes, threads_cluster):
    ref = api.render_spin(cubes, 3, size=SIZE, mode="objects")
    got = spin(threads_cluster, cubes, 3, size=SIZE, mode="objects")
    assert len(got) == 3
    for a, b in zip(got, ref, strict=True):
        assert np.array_equal(a, b)
    assert not np.array_equal(got[0], got[1])  # the camera did turn


def test_a_failing_sample_names_its_job(cubes, threads_cluster):
    with pytest.raises(FarmTaskError, match=r"samples 0\.\.1 of 2.*mode.*bogus"):
        soft_shadows(threads_cluster, cubes, 2, chunks=1, size=SIZE, mode="bogus")
