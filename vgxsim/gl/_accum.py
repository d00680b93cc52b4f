"""IRIS GL calls: accum."""

__all__: list[str] = []
