"""The import formats LightInv reads, each an ``Importer`` found by a file's suffix.

``scene.loading.load_scene`` looks a model file's format up here, and the window's
file dialog and the project's checks list the suffixes from here. Adding a format is
one module (a load function that reads the file into ``faces.Polygons`` and hands
them to ``assembly.assemble_scene``) plus its ``Importer`` in ``BUILTIN`` below; a
plug-in or a test may ``register`` one at run time and ``unregister`` it again.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from lightinv_core.scene.importers import gltf, ifc, obj, ply
from lightinv_core.scene.importers.faces import UP_AXES
from lightinv_core.scene.model import Scene

COMMON_OPTIONS = ("materials", "resolution", "scale", "up", "skip_degenerate")
"""The keyword arguments every load function takes (``load_obj``'s meaning)."""


@dataclass(frozen=True)
class Importer:
    """One import format.

    name : what it is called in messages ("glTF").
    suffixes : the file name endings it reads, lower case with the dot (".gltf", ".glb").
    load : ``load(path, materials=, resolution=, scale=, up=, skip_degenerate=,
        **options) -> Scene``, raising ``ObjImportError`` for a bad file or option.
    up : the format's up axis, "z" or "y", used when the user gives none.
    options : the keyword options it takes beyond ``COMMON_OPTIONS`` ("group_by").
    label : its name in the file dialog's filter ("Wavefront OBJ"; default ``name``).
    """

    name: str
    suffixes: tuple[str, ...]
    load: Callable[..., Scene]
    up: str = "z"
    options: tuple[str, ...] = ()
    label: str = ""

    def __post_init__(self) -> None:
        if not self.name:
            raise ValueError("an importer needs a name")
        if not self.suffixes or any(
            not s.startswith(".") or s != s.lower() or len(s) < 2 for s in self.suffixes
        ):
            raise ValueError(
                f"importer {self.name!r}: suffixes {self.suffixes!r} must be lower-case "
                "file name endings with the dot, e.g. ('.obj',)"
            )
        if self.up not in UP_AXES:
            raise ValueError(f"importer {self.name!r}: up must be 'z' or 'y', not {self.up!r}")
        clash = set(self.options) & set(COMMON_OPTIONS)
        if clash:
            raise ValueError(
                f"importer {self.name!r}: {sorted(clash)[0]!r} is a common option; list "
                "only the options it takes beyond them"
            )

    @property
    def filter(self) -> str:
        """Its entry in a file dialog's filter: ``"glTF (*.gltf *.glb)"``."""
        return f"{self.label or self.name} ({' '.join('*' + s for s in self.suffixes)})"


_IMPORTERS: dict[str, Importer] = {}


def register(importer: Importer) -> Importer:
    """Add ``importer``; ValueError if its name or one of its suffixes is taken."""
    if importer.name in _IMPORTERS:
        raise ValueError(f"an importer named {importer.name!r} is already registered")
    for other in _IMPORTERS.values():
        taken = set(importer.suffixes) & set(other.suffixes)
        if taken:
            raise ValueError(
                f"importer {importer.name!r}: {sorted(taken)[0]} is already read by {other.name!r}"
            )
    _IMPORTERS[importer.name] = importer
    return importer


def unregister(name: str) -> Importer:
    """Remove the importer called ``name`` and return it; ValueError if there is none."""
    try:
        return _IMPORTERS.pop(name)
    except KeyError:
        raise ValueError(f"no importer named {name!r} is registered") from None


def importers() -> tuple[Importer, ...]:
    """The registered importers, in the order they were registered."""
    return tuple(_IMPORTERS.values())


def importer_for(path: str | Path) -> Importer | None:
    """The importer of the file ``path`` by its suffix (any case), None if none reads it."""
    suffix = Path(path).suffix.lower()
    return next((i for i in _IMPORTERS.values() if suffix in i.suffixes), None)


def model_suffixes() -> tuple[str, ...]:
    """Every suffix a model file may have, in registration order."""
    return tuple(s for i in _IMPORTERS.values() for s in i.suffixes)


def option_names() -> frozenset[str]:
    """The format options some registered importer takes (beyond ``COMMON_OPTIONS``)."""
    return frozenset(o for i in _IMPORTERS.values() for o in i.options)


def is_model_file(path: str | Path) -> bool:
    """Whether ``path`` names a model file LightInv imports (by its suffix)."""
    return importer_for(path) is not None


def default_up(path: str | Path) -> str:
    """A model's up axis by its format's convention ("y" for glTF by its specification,
    "z" for OBJ, PLY and IFC; "z" for a file no importer reads)."""
    importer = importer_for(path)
    return importer.up if importer is not None else "z"


BUILTIN = (
    Importer("OBJ", obj.SUFFIXES, obj.load_obj, label="Wavefront OBJ"),
    Importer("glTF", gltf.SUFFIXES, gltf.load_gltf, up="y", options=("group_by",)),
    Importer("PLY", ply.SUFFIXES, ply.load_ply),
    Importer("IFC", ifc.SUFFIXES, ifc.load_ifc),
)
"""The formats LightInv reads out of the box (docs/obj-import.md), in the file dialog's
order."""
for _importer in BUILTIN:
    register(_importer)
