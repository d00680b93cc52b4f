"""File formats of the ``shadows`` program (README of Heidmann's 1991 demo, "File Formats").

* :mod:`.errors`  -- :class:`FormatError`, naming the file, the line and what was expected;
* :mod:`.glo`     -- ``.glo`` polygon geometry, reader and writer;
* :mod:`.cache`   -- the precomputed adjacency cache (the role of the original ``.pdat``);
* :mod:`.scn`     -- ``.scn`` scene descriptions;
* :mod:`.convert` -- meshes trimesh reads to ``.glo`` (the role of ``bintoglo``);
* :mod:`.sgi`     -- SGI ``.rgb`` images (textures).
"""

from .errors import FormatError

__all__ = ["FormatError"]
