"""The export formats LightInv writes a design in, each an ``Exporter`` found by name
or by a file's suffix (the import side is ``scene.importers.registry``).

``lightinv-cli export`` and the window's File > Export design menu list them from here.
Adding a format is one module with a write function plus its ``Exporter`` in
``BUILTIN`` below; a plug-in or a test may ``register`` one at run time and
``unregister`` it again.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from lightinv_core.export import gltf_export, ifc_export, radiance_scene
from lightinv_core.export.design import ExportedFile


@dataclass(frozen=True)
class Exporter:
    """One export format.

    name : its command-line name and option (``"ifc"`` -> ``--ifc``).
    suffixes : the file name endings it writes, lower case with the dot; the first is
        the default the window's save dialog offers.
    label : its name for people and in the save dialog's filter ("IFC4 building model").
    write : ``write(exported, path) -> ExportedFile``, ``exported`` an
        ``export.design.ExportDesign`` (the design, its solution, scene and light),
        raising ``LightInvError`` for a design it cannot write or a missing extra.
    needs : the optional extra it needs ("ifc"), "" when none.
    """

    name: str
    suffixes: tuple[str, ...]
    label: str
    write: Callable[..., ExportedFile]
    needs: str = ""

    def __post_init__(self) -> None:
        if not self.name or not self.name.isidentifier() or self.name != self.name.lower():
            raise ValueError(f"exporter name {self.name!r} must be a lower-case identifier")
        if not self.suffixes or any(
            not s.startswith(".") or s != s.lower() or len(s) < 2 for s in self.suffixes
        ):
            raise ValueError(
                f"exporter {self.name!r}: suffixes {self.suffixes!r} must be lower-case "
                "file name endings with the dot, e.g. ('.ifc',)"
            )
        if not self.label or "(" in self.label or ")" in self.label:
            # Qt reads a filter's patterns from between parentheses: "IFC (BIM) (*.ifc)"
            # left the save dialog's button disabled.
            raise ValueError(f"exporter {self.name!r}: a label without parentheses, please")

    @property
    def filter(self) -> str:
        """Its entry in a save dialog's filter: ``"IFC4 building model (*.ifc)"``."""
        return f"{self.label} ({' '.join('*' + s for s in self.suffixes)})"

    def default_path(self, path: str | Path) -> Path:
        """``path`` with this format's first suffix unless it already ends with one."""
        p = Path(path)
        return p if p.suffix.lower() in self.suffixes else p.with_suffix(self.suffixes[0])


_EXPORTERS: dict[str, Exporter] = {}


def register(exporter: Exporter) -> Exporter:
    """Add ``exporter``; ValueError if its name is taken."""
    if exporter.name in _EXPORTERS:
        raise ValueError(f"an exporter named {exporter.name!r} is already registered")
    _EXPORTERS[exporter.name] = exporter
    return exporter


def unregister(name: str) -> Exporter:
    """Remove the exporter called ``name`` and return it; ValueError if there is none."""
    try:
        return _EXPORTERS.pop(name)
    except KeyError:
        raise ValueError(f"no exporter named {name!r} is registered") from None


def exporters() -> tuple[Exporter, ...]:
    """The registered exporters, in the order they were registered."""
    return tuple(_EXPORTERS.values())


def exporter(name: str) -> Exporter:
    """The exporter called ``name``; ValueError naming the known ones if there is none."""
    try:
        return _EXPORTERS[name]
    except KeyError:
        known = ", ".join(_EXPORTERS)
        raise ValueError(f"no exporter named {name!r} (known: {known})") from None


def exporter_for(path: str | Path) -> Exporter | None:
    """The first exporter writing files with ``path``'s suffix (any case), or None."""
    suffix = Path(path).suffix.lower()
    return next((e for e in _EXPORTERS.values() if suffix in e.suffixes), None)


BUILTIN = (
    Exporter("ifc", ifc_export.SUFFIXES, "IFC4 building model", ifc_export.write_ifc, needs="ifc"),
    Exporter("radiance", radiance_scene.SUFFIXES, "Radiance scene", radiance_scene.write_radiance),
    Exporter("gltf", gltf_export.SUFFIXES, "Lit glTF binary", gltf_export.write_gltf),
)
"""The formats LightInv writes out of the box (docs/export.md), in the menu's order."""
for _exporter in BUILTIN:
    register(_exporter)
