"""IRIS GL calls: events."""

__all__: list[str] = []
