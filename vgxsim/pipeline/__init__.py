"""The pipeline between the gl layer and the kernels.

:mod:`.records` holds the interned draw-state records, :mod:`.decode` turns a
window's command stream into geometry passes at a flush.
"""
