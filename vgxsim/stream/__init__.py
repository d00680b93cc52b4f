"""The command stream: what every drawing call of vgxsim.gl appends to.

:mod:`.opcodes` defines the opcodes, :mod:`.recorder` the growable buffers and the
display-object chunks; :mod:`vgxsim.pipeline` decodes a stream at a flush.
"""
