"""IRIS GL calls: lighting."""

__all__: list[str] = []
