"""IRIS GL calls: window."""

__all__: list[str] = []
