"""The OpenGL backend: window-space primitives drawn by OpenGL 1.x (OSMesa headless).

:mod:`.surface` owns the GL context and its framebuffer object (front, back and
depth-stencil attachments, uploaded from and read back into the numpy planes);
:mod:`.batch` is the :class:`~vgxsim.batch.CommandBatch` subclass the pipeline
queues on.  PyOpenGL is imported only when a window of this backend is made
(``pip install vgxsim[opengl]``).  docs/opengl_backend.md lists where the planes
may differ from the software backend's, and by how much.
"""
