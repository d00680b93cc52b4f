"""IRIS GL calls: draw."""

__all__: list[str] = []
