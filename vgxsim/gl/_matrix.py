"""IRIS GL calls: matrix."""

__all__: list[str] = []
