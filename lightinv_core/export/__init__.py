"""Exports of a solved design back into the building model and other tools: IFC,
a Radiance scene and a lit glTF (docs/export.md).

- ``export_design(project, prepared, solution=None)``: what every format writes
  (``design.py``);
- ``exporters()``, ``exporter(name)``, ``register``/``unregister``: the formats, each
  an ``Exporter`` whose ``write(exported, path)`` writes one file (``registry.py``).
"""

from lightinv_core.export.design import ExportDesign, ExportedFile, export_design
from lightinv_core.export.registry import (
    Exporter,
    exporter,
    exporter_for,
    exporters,
    register,
    unregister,
)

__all__ = [
    "ExportDesign",
    "ExportedFile",
    "Exporter",
    "export_design",
    "exporter",
    "exporter_for",
    "exporters",
    "register",
    "unregister",
]
