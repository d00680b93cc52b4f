"""``--record-events FILE``: the input of a window session as an events script.

Every step the live queue delivers is written, as it is delivered, as one statement
of :mod:`vgxsim.events.script` with ``after FRAME`` set to the frame count at that
moment (``after 12 press MIDDLEMOUSE``, ``after 12 move 301 244``, ``after 40 menu
4``).  Played back headless (``vgxsim run PROGRAM --events FILE``), the queue delivers
each step at the first delivery point of that frame, so the program reads the same
input between the same frames and draws the same frames.  The match is per frame: a
step the user made in the middle of a frame (while the program was already blocked in
``qread``, say) is replayed at that frame's first ``qtest`` or ``qread``, which a
program that draws only at frame ends cannot tell apart.  Lines are flushed as they
are written: a killed session keeps the input up to its end.
"""

from __future__ import annotations

import os
import time

from vgxsim.sinks import SinkError

__all__ = ["EventScriptWriter"]


class EventScriptWriter:
    """Writes delivered steps as script statements.

    Parameters
    ----------
    path : str or path-like
    overwrite : bool
        Replace an existing file (else it is refused before the run).

    Raises
    ------
    SinkError
        If the file exists (without ``overwrite``) or cannot be created.
    """

    def __init__(self, path, overwrite: bool = False):
        self.path = os.fspath(path)
        if os.path.exists(self.path) and not overwrite:
            raise SinkError(f"{self.path} exists; give --overwrite to replace it")
        try:
            self._fh = open(self.path, "w", encoding="utf-8")
        except OSError as exc:
            raise SinkError(f"cannot write the events script {self.path}: {exc}") from exc
        self._fh.write(f"# vgxsim window session, recorded {time.strftime('%Y-%m-%d %H:%M:%S')}"
                       "\n# replay headless: vgxsim run PROGRAM --events THIS_FILE\n")
        self._fh.flush()
        self.lines = 0

    def statement(self, frame: int, text: str) -> None:
        """Write ``after FRAME TEXT`` (a comment when ``text`` starts with ``#``)."""
        line = text if text.startswith("#") else f"after {frame} {text}"
        self._fh.write(line + "\n")
        self._fh.flush()
        self.lines += 1

    def close(self) -> None:
        if not self._fh.closed:
            self._fh.close()
