"""Count an OBJ file's vertices and faces before parsing it, for the size guard
(``size.check_counts``): a streaming count of its ``v`` and ``f`` lines, about 1 s per GB.
"""

from __future__ import annotations

import os
from pathlib import Path

from lightinv_core.scene.importers.size import ModelCounts, check_counts

CHUNK = 1 << 24


def count_obj_lines(path: str | os.PathLike) -> ModelCounts:
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
    return ModelCounts(vertices, faces, os.path.getsize(path))


def check_obj_size(path: Path, fname: str) -> ModelCounts:
    """Raise ObjImportError if the OBJ file has more faces than patches allowed, or if
    importing it would take more than 80% of the memory available; else its counts."""
    return check_counts(count_obj_lines(path), fname)
