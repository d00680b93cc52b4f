"""IRIS GL calls: raster."""

__all__: list[str] = []
