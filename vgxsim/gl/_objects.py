"""IRIS GL calls: objects."""

__all__: list[str] = []
