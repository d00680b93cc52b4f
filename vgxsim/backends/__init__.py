"""Backends: what renders the window-space primitives the pipeline sets up.

The software backend is :class:`vgxsim.batch.CommandBatch` (band kernels into the
numpy planes).  The OpenGL backend (:mod:`vgxsim.backends.opengl`) takes the same
snapped, lit, clipped window-space triangles, line and point fragments and clears
and draws them with OpenGL 1.x fixed-function state, reading the planes back at
every flush, so readback calls and sinks see the planes unchanged.

The backend is a process-wide setting, like the thread count
(:mod:`vgxsim.threads`): :func:`set_backend`, or the environment variable
``VGXSIM_BACKEND`` (``software`` or ``opengl``); ``vgxsim run --backend`` sets it.
It applies to windows configured (winopen/gconfig) after the change.
"""

from __future__ import annotations

import os

BACKENDS = ("software", "opengl")
_override: str | None = None


class BackendError(RuntimeError):
    """A backend was asked for that does not exist or cannot start here."""


def set_backend(name: str | None) -> str | None:
    """Use backend ``name`` for windows configured from now on (None: follow
    ``VGXSIM_BACKEND``, else software).

    Returns
    -------
    str or None
        The previous setting (to restore it with another call).
    """
    global _override
    if name is not None and name not in BACKENDS:
        raise BackendError(f"unknown backend {name!r}; choose one of {', '.join(BACKENDS)}")
    previous, _override = _override, name
    return previous


def get_backend() -> str:
    """The backend new windows get."""
    if _override is not None:
        return _override
    name = os.environ.get("VGXSIM_BACKEND", "software").strip().lower() or "software"
    if name not in BACKENDS:
        raise BackendError(f"VGXSIM_BACKEND={name!r} is not one of {', '.join(BACKENDS)}")
    return name


def make_batch(framebuffer):
    """The batch a window's pipeline queues its primitives on.

    Parameters
    ----------
    framebuffer : vgxsim.state.planes.Framebuffer

    Returns
    -------
    vgxsim.batch.CommandBatch
        A software batch, or its OpenGL subclass.
    """
    if get_backend() == "opengl":
        from vgxsim.backends.opengl.batch import OpenGLBatch

        return OpenGLBatch(framebuffer)
    from vgxsim.batch import CommandBatch

    return CommandBatch(framebuffer)


__all__ = ["BACKENDS", "BackendError", "set_backend", "get_backend", "make_batch"]
