"""Refuse an OBJ file too big to import before parsing it, with the numbers.

Parsing builds Python objects per vertex and per face, so a 500 MB file would grow
past the machine's memory and be killed with no message after a minute or more. A
streaming count of its ``v`` and ``f`` lines (about 1 s per GB) tells, before any
parsing, whether its faces alone exceed the patch limit and whether the import
would fit in the memory this process may use (the container's limit included).
"""

from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

from lightinv_core.errors import ObjImportError
from lightinv_core.memory import available_memory_bytes, format_bytes
from lightinv_core.scene.patches import MAX_PATCHES

CHUNK = 1 << 24
# Peak import memory per face and per vertex (bytes), measured (bench/scene_build.py)
# with headroom: a rectangular face becomes a Surface and a Rect (about 1.6 kB), a
# triangle a row of an array; the text itself is held about three times while decoded.
BYTES_PER_FACE = 2000
BYTES_PER_VERTEX = 250
BYTES_PER_FILE_BYTE = 3
MEMORY_SHARE = 0.8


@dataclass(frozen=True)
class ObjCounts:
    """Lines of an OBJ file: vertices (``v``), faces (``f``) and its size in bytes."""

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


def count_obj_lines(path: str | os.PathLike) -> ObjCounts:
    """Count the ``v`` and ``f`` lines of an OBJ file by streaming it in 16 MB blocks.

    UTF-16 files are counted with their zero bytes dropped; a statement split by a
    trailing backslash counts where it starts, as in the parser.
    """
    vertices = faces = 0
    tail = b"\n"
    with open(path, "rb") as fh:
        first = fh.read(3)
        for bom in (b"\xef\xbb\xbf", b"\xff\xfe", b"\xfe\xff"):
            if first.startswith(bom):
                first = first[len(bom) :]
                break
        tail += first.replace(b"\x00", b"")
        while block := fh.read(CHUNK):
            text = tail + block.replace(b"\x00", b"")
            # Count a line at the newline that starts it; keep the last (maybe partial)
            # line for the next block.
            cut = text.rfind(b"\n")
            head, tail = text[:cut], text[cut:]
            for lead in (b"\n", b"\r"):
                vertices += head.count(lead + b"v ") + head.count(lead + b"v\t")
                faces += head.count(lead + b"f ") + head.count(lead + b"f\t")
        for lead in (b"\n", b"\r"):
            vertices += tail.count(lead + b"v ") + tail.count(lead + b"v\t")
            faces += tail.count(lead + b"f ") + tail.count(lead + b"f\t")
    return ObjCounts(vertices, faces, os.path.getsize(path))


def check_obj_size(path: Path, fname: str) -> ObjCounts:
    """Raise ObjImportError if the OBJ file has more faces than patches allowed, or if
    importing it would take more than 80% of the memory available; else its counts."""
    return check_counts(count_obj_lines(path), fname)


def check_counts(counts: ObjCounts, fname: str) -> ObjCounts:
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
