"""IRIS GL calls: color."""

__all__: list[str] = []
