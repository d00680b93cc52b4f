"""IRIS GL calls: text."""

__all__: list[str] = []
