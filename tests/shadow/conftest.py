import pytest


@pytest.fixture(autouse=True)
def _private_model_cache(tmp_path_factory, monkeypatch):
    """Keep the adjacency cache of these tests out of the user's home."""
    monkeypatch.setenv("VGXSIM_CACHE_DIR", str(tmp_path_factory.getbasetemp() / "model-cache"))
