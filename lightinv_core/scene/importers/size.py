"""Refuse a model too big to import before reading it, with the numbers.

Reading builds Python objects per vertex and per face, so a 500 MB file would grow
past the machine's memory and be killed with no message after a minute or more. Each
format counts its vertices and faces cheaply first (OBJ: a streaming count of its
lines, ``obj_size``; glTF and PLY: their headers) and ``check_counts`` tells whether its
faces alone exceed the patch limit and whether the import would fit in the memory this
process may use (the container's limit included). IFC files are judged by their size
(``check_ifc_size``).
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

from lightinv_core.errors import ObjImportError
from lightinv_core.memory import available_memory_bytes, format_bytes
from lightinv_core.scene.patches import MAX_PATCHES

# Peak import memory per face and per vertex (bytes), measured (bench/scene_build.py)
# with headroom: a rectangular face becomes a Surface and a Rect (about 1.6 kB), a
# triangle a row of an array; the text itself is held about three times while decoded.
BYTES_PER_FACE = 2000
BYTES_PER_VERTEX = 250
BYTES_PER_FILE_BYTE = 3
MEMORY_SHARE = 0.8


@dataclass(frozen=True)
class ModelCounts:
    """A model file's vertices and faces (OBJ: ``v`` and ``f`` lines) and its size in bytes."""

    vertices: int
    faces: int
    nbytes: int

    @property
    def import_bytes(self) -> int:
        """Estimated peak memory of importing the file (bytes)."""
        return (
            BYTES_PER_FACE * self.faces
            + BYTES_PER_VERTEX * self.vertices
            + BYTES_PER_FILE_BYTE * self.nbytes
        )


def check_counts(counts: ModelCounts, fname: str) -> ModelCounts:
    """``counts`` if a model of that many faces and vertices may be imported, else
    ObjImportError (the faces over the patch limit, or the import over 80% of the
    memory available). Other formats count their faces from their headers."""
    if counts.faces > MAX_PATCHES:
        raise ObjImportError(
            f"{fname}: the model has {counts.faces:,} faces and each becomes at least one "
            f"patch (limit {MAX_PATCHES:,}); simplify it in the modeller (merge coplanar "
            "faces, drop furniture detail) or export one floor or room at a time"
        )
    need, have = counts.import_bytes, available_memory_bytes()
    if need > MEMORY_SHARE * have:
        raise ObjImportError(
            f"{fname}: importing {format_bytes(counts.nbytes)} ({counts.vertices:,} vertices, "
            f"{counts.faces:,} faces) needs about {format_bytes(need)} but "
            f"{format_bytes(have)} is available (an import may use at most 80% of it); "
            "simplify the model or free memory"
        )
    return counts


# IFC: ifcopenshell's geometry and the plane polygons took 73 MiB for a 145 kB file and
# 118 MiB for a 590 kB one (generated rooms, bench/model_import.py ``ifc_memory``: about
# 106 bytes per file byte over a 58 MiB base); the per-byte term is doubled for models
# whose bytes hold more geometry.
IFC_BYTES_PER_FILE_BYTE = 200
IFC_BASE_BYTES = 64 << 20


def check_ifc_size(path: Path, fname: str) -> int:
    """The estimated peak memory (bytes) of importing the IFC file ``path``, or
    ObjImportError if it is over 80% of the memory available."""
    nbytes = os.path.getsize(path)
    need, have = IFC_BASE_BYTES + IFC_BYTES_PER_FILE_BYTE * nbytes, available_memory_bytes()
    if need > MEMORY_SHARE * have:
        raise ObjImportError(
            f"{fname}: importing {format_bytes(nbytes)} of IFC needs about "
            f"{format_bytes(need)} but {format_bytes(have)} is available (an import may "
            "use at most 80% of it); export the storeys or rooms to light as a smaller "
            "IFC, or free memory"
        )
    return need
