import warnings

import pytest

from vgxsim.shadow import api


@pytest.fixture(autouse=True)
def _private_model_cache(tmp_path_factory, monkeypatch):
    """Keep the adjacency cache of these tests out of the user's home."""
    monkeypatch.setenv("VGXSIM_CACHE_DIR", str(tmp_path_factory.getbasetemp() / "model-cache"))


@pytest.fixture(scope="session")
def cubes():
    """The default three cubes: both lights have JITTER 0.6, so soft shadows vary."""
    return api.load_scene("cubes")


@pytest.fixture(scope="session")
def reference():
    """The in-process program, without the farm: api.render as the CLI calls it."""
    def render(scene, **kw):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", api.ViewpointInShadowWarning)
            return api.render(scene, **kw)
    return render


@pytest.fixture(scope="module")
def threads_cluster():
    """Two single-threaded Dask workers as threads of this process (fast to start)."""
    pytest.importorskip("distributed")
    from vgxsim.farm import DaskExecutor

    with DaskExecutor(n_workers=2, processes=False) as ex:
        yield ex
