"""IRIS GL calls: oldstyle."""

__all__: list[str] = []
