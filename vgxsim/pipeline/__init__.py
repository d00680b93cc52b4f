"""The pipeline between the gl layer and the kernels.

:mod:`.context` holds one window (its state data, command stream and batch);
:mod:`.records` the interned draw-state records; :mod:`.decode` turns a window's
command stream into geometry passes at a flush; :mod:`.draw` lights vertices and
defers triangles to shared geometry passes.
"""
