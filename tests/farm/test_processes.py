"""Process workers (the default LocalCluster): a worker killed mid-sweep loses nothing,
and ``vgxsim shadows --soft/--spin`` on a cluster writes what ``--local`` writes."""

import os
import signal

import numpy as np
import pytest

from vgxsim.cli import main
from vgxsim.farm.tasks import render_task
from vgxsim.shadow import api

distributed = pytest.importorskip("distributed")

SIZE = (40, 32)


@pytest.mark.slow
def test_worker_killed_mid_sweep_loses_nothing(cubes, reference):
    from vgxsim.farm import DaskExecutor

    views = [api.orbit(cubes.camera, rotate=(30.0 * k, 0.0)) for k in range(10)]
    from dataclasses import replace

    scenes = [replace(cubes, camera=c) for c in views]
    with DaskExecutor(n_workers=2, processes=True) as ex:
        ex.warm_up([{"size": SIZE}])
        before = set(ex.workers)
        jobs = [(render_task, ex.put(s), {"size": SIZE}) for s in scenes]
        results, killed = [], None
        for r in ex.map(jobs):
            results.append(r)
            if killed is None:  # kill the busiest worker while it renders
                busy = ex.client.processing()
                killed = max(before, key=lambda w: len(busy.get(w, ())))
                pid = ex.client.run(os.getpid, workers=[killed])[killed]
                os.kill(pid, signal.SIGKILL)
        assert killed is not None and killed not in ex.workers  # it really died
    assert sorted(r.index for r in results) == list(range(10))
    assert all(r.error is None for r in results)
    for r in results:
        ref = reference(scenes[r.index], size=SIZE)
        assert np.array_equal(r.value["colour"], ref.colour)


@pytest.mark.slow
def test_cli_soft_and_spin_on_a_cluster_equal_local(tmp_path):
    import imageio.v3 as iio

    common = ["shadows", "--size", "24x20", "--workers", "2"]
    assert main([*common, "--soft", "4", "-o", str(tmp_path / "farm.png")]) == 0
    assert main([*common, "--soft", "4", "--local", "-o", str(tmp_path / "local.png")]) == 0
    farm, local = iio.imread(tmp_path / "farm.png"), iio.imread(tmp_path / "local.png")
    assert np.array_equal(farm, local)
    hard = api.render(None, size=(24, 20)).colour[..., :3]
    assert hard.shape == farm.shape and not np.array_equal(farm, hard)
    assert main([*common, "--spin", "3", "--mode", "objects", "-o",
                 str(tmp_path / "farm.gif")]) == 0
    assert main([*common, "--spin", "3", "--mode", "objects", "--local", "-o",
                 str(tmp_path / "local.gif")]) == 0
    assert (tmp_path / "farm.gif").read_bytes() == (tmp_path / "local.gif").read_bytes()
