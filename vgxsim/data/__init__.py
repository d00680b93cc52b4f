"""Scenes, models and textures shipped with vgxsim (made by scripts/make_shipped_data.py).

* ``scenes/``   -- ``.scn`` files: ``cubes`` (the default scene), ``balls``,
  ``textured_floor``, ``dense`` (a 51,200-triangle torus) and ``teapot``;
* ``models/``   -- ``.glo`` geometry they name, and the teapot's Bezier patches;
* ``textures/`` -- SGI ``.rgb`` images.
"""

from __future__ import annotations

from importlib import resources
from pathlib import Path

SCENES = ("cubes", "balls", "textured_floor", "dense", "teapot")


def data_path(*parts: str) -> Path:
    """Filesystem path of a shipped file, e.g. ``data_path("scenes", "balls.scn")``."""
    return Path(str(resources.files(__name__).joinpath(*parts)))


def scene_path(name: str) -> Path:
    """Path of a shipped scene by name (``"balls"``) or file name (``"balls.scn"``).

    Raises
    ------
    KeyError
        If no such scene is shipped.
    """
    stem = name[:-4] if name.endswith(".scn") else name
    if stem not in SCENES:
        raise KeyError(f"no shipped scene {name!r} (shipped: {', '.join(SCENES)})")
    return data_path("scenes", stem + ".scn")
