"""The renderers the conformance tests compare vgxsim's software batch with.

``"mesa"``: :class:`vgxsim.reference.mesa.MesaPeer`, llvmpipe driven directly from
the window-space commands.  ``"opengl_backend"``: vgxsim's own OpenGL backend
(:class:`vgxsim.backends.opengl.batch.OpenGLBatch`) fed the same commands through
the batch interface the pipeline uses, so that the backend -- its vertex, depth
and colour conversions, its framebuffer object, upload and readback -- must agree
with the software batch as closely as Mesa does, under the same tolerances.
"""

from __future__ import annotations

import numpy as np

from vgxsim.batch import CLEAR_COLOUR, CLEAR_STENCIL, CLEAR_Z
from vgxsim.reference import mesa
from vgxsim.state.planes import ZMAX, Framebuffer, PlaneConfig

PEERS = ("mesa", "opengl_backend")
_BITS = {"color": CLEAR_COLOUR, "z": CLEAR_Z, "stencil": CLEAR_STENCIL}


class BackendPeer:
    """The MesaPeer calls the conformance tests use (render, color, depth_iris,
    stencil, close), drawn by the OpenGL backend's batch on one framebuffer that
    persists between :meth:`render` calls, as a peer's GL buffers do.

    Parameters
    ----------
    width, height : int
    """

    def __init__(self, width: int, height: int):
        from vgxsim.backends.opengl.batch import OpenGLBatch

        self.fb = Framebuffer(PlaneConfig(width, height, double=False, zbits=24, stencil=8))
        self.batch = OpenGLBatch(self.fb)

    def render(self, commands) -> None:
        """Draw naive-format commands (``("triangle", verts, state)``, vertices
        ``(x, y, z, rgba[, (s/w, t/w, 1/w)])``, and ``("clear", planes, values,
        state)``)."""
        for cmd in commands:
            if cmd[0] == "clear":
                _, planes, values, rs = cmd
                self.batch.add_clear(sum(_BITS[p] for p in planes), values.get("color", 0),
                                     values.get("z", ZMAX), values.get("stencil", 0), rs)
                continue
            _, verts, rs = cmd
            xyz = np.array([v[:3] for v in verts], np.float64)
            col = np.array([v[3] for v in verts], np.float64)
            tex = np.array([v[4] for v in verts], np.float64) if len(verts[0]) > 4 else None
            self.batch.add_window_triangles(xyz[:, 0], xyz[:, 1], xyz[:, 2], col,
                                            np.array([[0, 1, 2]]), rs, flat_col=col[2:3],
                                            tex=tex)
        self.batch.flush()

    def color(self) -> np.ndarray:
        """(H, W) uint32 0xAABBGGRR, row 0 at the bottom."""
        return self.fb.front.copy()

    def depth_iris(self) -> np.ndarray:
        """(H, W) int32 IRIS window z."""
        return self.fb.z.copy()

    def stencil(self) -> np.ndarray:
        """(H, W) uint8."""
        return self.fb.stencil.copy()

    def close(self) -> None:
        self.batch.close()


def open_peer(kind: str, width: int, height: int):
    """A renderer of :data:`PEERS` of the given size."""
    if kind == "mesa":
        return mesa.MesaPeer(width, height)
    return BackendPeer(width, height)
