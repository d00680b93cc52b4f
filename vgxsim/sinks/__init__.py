"""Frame sinks for headless runs: PNG sequences, memory, GIF/MP4 video.

See :mod:`vgxsim.sinks.frames`.  Sinks take IRIS-convention images (row 0 at
the bottom) and store them top row first.
"""

from vgxsim.sinks.frames import (
    FrameSink,
    MemorySink,
    PNGSequenceSink,
    SinkError,
    VideoSink,
    open_sink,
    to_top_down,
    write_png,
)
from vgxsim.sinks.images import write_image

__all__ = [
    "FrameSink",
    "MemorySink",
    "PNGSequenceSink",
    "SinkError",
    "VideoSink",
    "open_sink",
    "to_top_down",
    "write_image",
    "write_png",
]
