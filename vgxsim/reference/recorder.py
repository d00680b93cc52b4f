"""Record what vgxsim draws, as window-space commands another renderer can replay.

:func:`record_window_triangles` is a context manager that, while it is active,
captures every triangle and every clear that reaches a :class:`~vgxsim.batch.CommandBatch`,
in drawing order:

* triangles *after* clipping, projection and snapping, in IRIS window coordinates
  (``xw = xf / 256``, ``yw = yf / 256``, ``zw`` as the pipeline computed it), with
  their colours per vertex after lighting (or the flat colour on all three vertices
  under ``shademodel(FLAT)``) and their :class:`~vgxsim.state.raster.RasterState`;
* clears, with their planes, values and state.

The capture wraps :meth:`CommandBatch.add_triangles`, the single entry point through
which :func:`vgxsim.geometry.pipeline.draw_triangles` (and
:meth:`CommandBatch.add_window_triangles`) queue triangles once they are clipped,
projected to the window and snapped to fixed point, and
:meth:`CommandBatch.add_clear`.  Rendering itself is unchanged: the wrapped methods
call the originals.  Points, lines and text (fragments) are not recorded; their
count is kept in :attr:`Recording.skipped_fragment_runs`.

The result feeds :class:`vgxsim.reference.mesa.MesaPeer`: :meth:`Recording.commands`
gives its immediate-mode command list, :meth:`Recording.runs` groups consecutive
triangles of the same state for the vertex-array path, and :class:`MesaReplay`
uploads everything once and replays it with one ``glDrawArrays`` per run.

Examples
--------
>>> from vgxsim.examples import heidmann1991                       # doctest: +SKIP
>>> with record_window_triangles() as rec:                         # doctest: +SKIP
...     heidmann1991.render(320, 256)
>>> rec.n_triangles, len(rec.runs())                               # doctest: +SKIP
"""

from __future__ import annotations

import contextlib
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

import numpy as np

from vgxsim.batch import CLEAR_COLOUR, CLEAR_STENCIL, CLEAR_Z, CommandBatch
from vgxsim.state.raster import FLAT, RasterState

__all__ = ["ClearRecord", "MesaReplay", "Recording", "TriangleRecord",
           "record_window_triangles"]

SUBPIXEL_ONE = 256


@dataclass(frozen=True)
class TriangleRecord:
    """Triangles of one ``add_triangles`` call, in window coordinates.

    Attributes
    ----------
    positions : ndarray, shape (n, 3, 3), float64
        ``(xw, yw, zw)`` of each triangle's three vertices, in the vertex order the
        pipeline queued them (not yet culled: culling is part of the state).
    colours : ndarray, shape (n, 3, 4), float64
        RGBA in [0, 1] per vertex; under flat shading all three are the flat colour.
    state : RasterState
    """

    positions: np.ndarray
    colours: np.ndarray
    state: RasterState


@dataclass(frozen=True)
class ClearRecord:
    """One clear: planes as MesaPeer names it (``"color"``, ``"z"``, ``"stencil"``).

    Attributes
    ----------
    planes : frozenset of str
    values : dict
        ``{"color": 0xAABBGGRR, "z": int, "stencil": int}``.
    state : RasterState
    """

    planes: frozenset
    values: dict
    state: RasterState

    def command(self) -> tuple:
        """The ``("clear", planes, values, state)`` command of MesaPeer and the naive
        reference."""
        return ("clear", set(self.planes), dict(self.values), self.state)


class Recording:
    """What was drawn while :func:`record_window_triangles` was active.

    Attributes
    ----------
    items : list of TriangleRecord or ClearRecord
        In drawing order.
    sizes : list of tuple
        ``(width, height)`` of every framebuffer drawn to, in order of first use.
    skipped_fragment_runs : int
        Point, line and text runs that were drawn but not recorded.
    """

    def __init__(self) -> None:
        self.items: list[TriangleRecord | ClearRecord] = []
        self.sizes: list[tuple[int, int]] = []
        self.skipped_fragment_runs = 0
        self._fb_ids: list[int] = []

    # -- capture ------------------------------------------------------------------
    def _see(self, batch: CommandBatch) -> None:
        fb_id = id(batch.fb)
        if fb_id not in self._fb_ids:
            self._fb_ids.append(fb_id)
            self.sizes.append((batch.fb.width, batch.fb.height))

    def _add_triangles(self, batch, xf, yf, zw, col, tris, src, flat_col, rs) -> None:
        self._see(batch)
        tris = np.asarray(tris, np.int64).reshape(-1, 3)
        n = tris.shape[0]
        if n == 0:
            return
        pos = np.empty((n, 3, 3), np.float64)
        pos[:, :, 0] = np.asarray(xf, np.float64)[tris] / SUBPIXEL_ONE
        pos[:, :, 1] = np.asarray(yf, np.float64)[tris] / SUBPIXEL_ONE
        pos[:, :, 2] = np.asarray(zw, np.float64)[tris]
        # The batch's rule (CommandBatch.add_triangles): flat when FLAT or no vertex
        # colour; the flat colour is that of the source primitive, black if none.
        if rs.shademodel == FLAT or col is None:
            if flat_col is not None:
                fc = np.asarray(flat_col, np.float64)[np.asarray(src, np.int64)]
            else:
                fc = np.zeros((n, 4))
            cols = np.repeat(fc[:, None, :], 3, axis=1)
        else:
            cols = np.asarray(col, np.float64)[tris]
        self.items.append(TriangleRecord(pos, np.ascontiguousarray(cols), rs))

    def _add_clear(self, batch, planes: int, colour: int, z: int, stencil: int,
                   rs: RasterState) -> None:
        self._see(batch)
        if batch.fb.z is None:  # as CommandBatch.add_clear
            planes &= ~CLEAR_Z
        if batch.fb.stencil is None:
            planes &= ~CLEAR_STENCIL
        names = frozenset(name for bit, name in ((CLEAR_COLOUR, "color"), (CLEAR_Z, "z"),
                                                 (CLEAR_STENCIL, "stencil")) if planes & bit)
        if names:
            values = {"color": int(colour) & 0xFFFFFFFF, "z": int(z), "stencil": int(stencil)}
            self.items.append(ClearRecord(names, values, rs))

    # -- views ----------------------------------------------------------------------
    @property
    def n_triangles(self) -> int:
        """Number of triangles recorded."""
        return sum(it.positions.shape[0] for it in self.items if isinstance(it, TriangleRecord))

    @property
    def n_clears(self) -> int:
        """Number of clears recorded."""
        return sum(isinstance(it, ClearRecord) for it in self.items)

    def commands(self) -> list[tuple]:
        """The recording as a MesaPeer / naive-reference command list.

        Returns
        -------
        list of tuple
            ``("triangle", verts, state)`` with ``verts`` three
            ``(xw, yw, zw, (r, g, b, a))`` tuples, and ``("clear", planes, values,
            state)``, in drawing order.
        """
        out: list[tuple] = []
        for it in self.items:
            if isinstance(it, ClearRecord):
                out.append(it.command())
                continue
            for p, c in zip(it.positions.tolist(), it.colours.tolist(), strict=True):
                verts = [(v[0], v[1], v[2], tuple(k)) for v, k in zip(p, c, strict=True)]
                out.append(("triangle", verts, it.state))
        return out

    def replay(self, batch: CommandBatch, runs: list | None = None) -> None:
        """Queue the recording on a vgxsim CommandBatch (no flush).

        Parameters
        ----------
        batch : CommandBatch
            Its framebuffer should have the recorded size and planes.
        runs : list, optional
            A precomputed :meth:`runs` (default: the items as recorded).

        Notes
        -----
        Replayed through :meth:`CommandBatch.add_window_triangles`, which snaps
        ``xw * 256`` back to the recorded fixed-point values exactly, the frame is
        bit-identical to the recorded one.
        """
        names = {"color": CLEAR_COLOUR, "z": CLEAR_Z, "stencil": CLEAR_STENCIL}
        for it in self.items if runs is None else runs:
            if isinstance(it, ClearRecord):
                bits = sum(names[p] for p in it.planes)
                v = it.values
                batch.add_clear(bits, v["color"], v["z"], v["stencil"], it.state)
                continue
            n = it.positions.shape[0]
            pos = it.positions.reshape(-1, 3)
            batch.add_window_triangles(pos[:, 0], pos[:, 1], pos[:, 2],
                                       it.colours.reshape(-1, 4),
                                       np.arange(3 * n, dtype=np.int64).reshape(n, 3),
                                       it.state, flat_col=it.colours[:, 2, :])

    def runs(self) -> list[TriangleRecord | ClearRecord]:
        """Consecutive triangles of equal state merged into one record each.

        Returns
        -------
        list of TriangleRecord or ClearRecord
            In drawing order; each TriangleRecord is one run for
            :meth:`vgxsim.reference.mesa.MesaPeer.draw_arrays`.
        """
        out: list[TriangleRecord | ClearRecord] = []
        pending: list[TriangleRecord] = []

        def close() -> None:
            if len(pending) == 1:
                out.append(pending[0])
            elif pending:
                out.append(TriangleRecord(np.concatenate([r.positions for r in pending]),
                                          np.concatenate([r.colours for r in pending]),
                                          pending[0].state))
            pending.clear()

        for it in self.items:
            if isinstance(it, ClearRecord):
                close()
                out.append(it)
            elif pending and it.state != pending[0].state:
                close()
                pending.append(it)
            else:
                pending.append(it)
        close()
        return out


@contextlib.contextmanager
def record_window_triangles() -> Iterator[Recording]:
    """Record every triangle and clear queued on any CommandBatch inside the block.

    Yields
    ------
    Recording
        Filled while the block runs; complete when it exits.

    Notes
    -----
    The wrappers are installed on the :class:`~vgxsim.batch.CommandBatch` class and
    removed on exit (also on an exception); blocks may nest (each records
    everything drawn while it is active).  Not thread-safe with respect to other
    threads drawing at the same time.
    """
    rec = Recording()
    orig_tris = CommandBatch.add_triangles
    orig_clear = CommandBatch.add_clear
    orig_frags = CommandBatch.add_fragments

    def add_triangles(self, xf, yf, zw, col, tris, src, flat_col, rs, tex=None):
        # Texture coordinates are drawn but not recorded (replays are untextured).
        rec._add_triangles(self, xf, yf, zw, col, tris, src, flat_col, rs)
        if tex is not None:
            return orig_tris(self, xf, yf, zw, col, tris, src, flat_col, rs, tex=tex)
        return orig_tris(self, xf, yf, zw, col, tris, src, flat_col, rs)

    def add_clear(self, planes, colour, z, stencil, rs):
        rec._add_clear(self, planes, colour, z, stencil, rs)
        return orig_clear(self, planes, colour, z, stencil, rs)

    def add_fragments(self, xy, z, rgba, rs):
        if np.shape(xy)[0]:
            rec.skipped_fragment_runs += 1
        return orig_frags(self, xy, z, rgba, rs)

    CommandBatch.add_triangles = add_triangles
    CommandBatch.add_clear = add_clear
    CommandBatch.add_fragments = add_fragments
    try:
        yield rec
    finally:
        CommandBatch.add_triangles = orig_tris
        CommandBatch.add_clear = orig_clear
        CommandBatch.add_fragments = orig_frags


class MesaReplay:
    """A recording uploaded to one MesaPeer, replayable with one draw per state run.

    All triangles go into one pair of vertex buffers (uploaded once); :meth:`run`
    then issues, in order, each clear and one ``glDrawArrays`` per run of equal
    state.

    Parameters
    ----------
    peer : vgxsim.reference.mesa.MesaPeer
    recording : Recording
    """

    def __init__(self, peer: Any, recording: Recording):
        self.peer = peer
        self.program: list[tuple] = []
        runs = recording.runs()
        tri_runs = [r for r in runs if isinstance(r, TriangleRecord)]
        self.n_triangles = sum(r.positions.shape[0] for r in tri_runs)
        self.arrays = None
        if tri_runs:
            pos = np.concatenate([r.positions for r in tri_runs]).reshape(-1, 3)
            col = np.concatenate([r.colours for r in tri_runs]).reshape(-1, 4)
            # Recorded positions are multiples of 1/256, so either snap is exact.
            self.arrays = peer.upload_arrays(pos, col, subpixel=True)
        first = 0
        for r in runs:
            if isinstance(r, ClearRecord):
                self.program.append(r.command())
            else:
                count = 3 * r.positions.shape[0]
                self.program.append(("arrays", first, count, r.state))
                first += count

    def run(self) -> None:
        """Issue the recording's clears and draws (does not wait: see ``finish``)."""
        peer = self.peer
        for cmd in self.program:
            if cmd[0] == "arrays":
                _, first, count, state = cmd
                peer.draw_arrays(self.arrays, state, first, count)
            else:
                peer.render([cmd])

    def finish(self) -> None:
        """Wait until the peer has finished rendering."""
        self.peer.finish()

    def delete(self) -> None:
        """Free the uploaded buffers."""
        if self.arrays is not None:
            self.arrays.delete()
            self.arrays = None
