"""The one error type of the file readers: file, line and what was expected."""

from __future__ import annotations


class FormatError(ValueError):
    """A scene, model or texture file that cannot be read.

    The message is ``FILE:LINE: what was found, and what was expected`` (LINE is
    omitted when the problem is the whole file, e.g. it does not exist).

    Attributes
    ----------
    path : str
    line : int or None
        One-based line number.
    reason : str
    """

    def __init__(self, path: str, line: int | None, reason: str):
        self.path = str(path)
        self.line = line
        self.reason = reason
        where = f"{self.path}:{line}" if line is not None else self.path
        super().__init__(f"{where}: {reason}")
