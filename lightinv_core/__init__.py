"""LightInv engine: scenes, radiosity transport, low-rank operator, inverse design.

This package is GUI-free: it never imports Qt, VTK or pyvista, so it works from a
script, a notebook or the ``lightinv-cli`` command line.
"""

from lightinv_core.errors import LightInvError, SceneError

__all__ = ["LightInvError", "SceneError"]
__version__ = "0.1.0"
