"""IRIS GL calls: query."""

__all__: list[str] = []
