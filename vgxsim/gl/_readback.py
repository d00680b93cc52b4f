"""IRIS GL calls: readback."""

__all__: list[str] = []
