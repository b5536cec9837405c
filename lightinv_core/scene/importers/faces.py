"""The neutral input of every importer: polygon faces in metres (z up) with their
lighting group and material, and how messages name the file and places in it.

A format's reader turns its file into ``Polygons`` (OBJ ``f`` statements, glTF and PLY
triangles joined into polygons, IFC element faces) and a ``Places`` saying where a face
is in its own terms (a line of an OBJ file, a triangle of a glTF node); ``assembly``
makes the Scene of them. A group named ``zone:NAME:KIND`` is an emitter zone
(``zone_spec``).
"""

from __future__ import annotations

from bisect import bisect_right
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from lightinv_core.errors import ObjImportError
from lightinv_core.kinds import source_kind_names

UP_AXES = ("z", "y")
# Largest coordinate accepted, in metres after scaling: beyond it areas overflow, and no
# building is that large (a bigger number means the scale is wrong).
MAX_COORD = 1e8
LISTED = 5  # names or line numbers listed in a message


@dataclass(frozen=True)
class Face:
    """One polygon face: 0-based vertex indices, where it is (an OBJ line, a face number;
    ``Places`` says which), lighting group and material (None: none)."""

    index: tuple[int, ...]
    line: int
    group: str
    material: str | None


@dataclass
class Polygons:
    """A model read by a format's reader: vertices (n, 3) in metres, z up; faces; the
    reader's warnings (the import adds its own)."""

    vertices: np.ndarray
    faces: list[Face]
    warnings: list[str] = field(default_factory=list)


def clip(text: str, n: int = 40) -> str:
    """``repr`` of ``text`` cut to about ``n`` characters, for error messages."""
    return repr(text if len(text) <= n else text[:n] + "...")


def describe_lines(lines: list[int]) -> str:
    """'line 7' or 'lines 7, 9, 11, 13, 15 and 3 more'."""
    if len(lines) == 1:
        return f"line {lines[0]}"
    shown = ", ".join(str(n) for n in lines[:LISTED])
    return f"lines {shown}" + (f" and {len(lines) - LISTED} more" if len(lines) > LISTED else "")


def zone_spec(group: str, where: str) -> tuple[str, str] | None:
    """(NAME, KIND) of a ``zone:NAME:KIND`` group, None for other groups; errors start
    with ``where`` (the file and line, ``"room.obj line 12"``)."""
    if not group.lower().startswith("zone:"):
        return None
    name, sep, kind = group[5:].rpartition(":")
    if not sep or not name:
        raise ObjImportError(
            f"{where}: group {clip(group)} is not a valid zone group; "
            "name it zone:NAME:skylight or zone:NAME:luminaire"
        )
    if kind.lower() not in source_kind_names():
        raise ObjImportError(
            f"{where}: group {clip(group)}: zone kind {clip(kind)} is not one of "
            f"skylight, window, luminaire; name the group zone:{name}:skylight, "
            f"zone:{name}:window or zone:{name}:luminaire"
        )
    return name, kind.lower()


class Places:
    """How messages name the model file and places in it: by default, line numbers.

    ``Face.line`` is a line of the file here; readers that number their faces instead
    say where a face is in their own terms (``FacePlaces``). A format sets the class
    attributes to its words (``obj.ObjPlaces``).
    """

    what = "model"  # "... do not occur in the model"
    colour = "material colour"  # where a material's colour comes from
    item_kind = "group"  # what a lighting group is in the import report
    white: str | None = None  # how white is written in ``colour`` (None: "<colour> 1 1 1")
    colour_file: str | None = None  # where colours are given ("an MTL file"; None: the model)

    def __init__(self, path: Path):
        self.path = path
        self.fname = path.name

    def at(self, line: int) -> str:
        """Where face ``line`` is, after the file name: ``" line 12"``."""
        return f" line {line}"

    def within(self, line: int) -> str:
        """The same in brackets, after a group name: ``" (line 12)"``."""
        return f" (line {line})"

    def many(self, lines: list[int]) -> str:
        """Where several faces are: ``"lines 7, 9"``."""
        return describe_lines(lines)


class FacePlaces(Places):
    """Messages about faces numbered within their part (a glTF node or PLY colour, an IFC
    element) rather than by line."""

    def __init__(
        self, path: Path, starts: list[int], labels: list[str], colour: str, noun="triangle"
    ):
        super().__init__(path)
        self.starts, self.labels, self.colour, self.noun = starts, labels, colour, noun

    def at(self, line: int) -> str:
        return ""

    def within(self, line: int) -> str:
        return ""

    def many(self, lines: list[int]) -> str:
        by_part: dict[int, list[int]] = {}
        for n in lines:
            k = bisect_right(self.starts, n) - 1
            by_part.setdefault(k, []).append(n - self.starts[k] + 1)
        out = []
        for k, nums in list(by_part.items())[:LISTED]:
            shown = ", ".join(str(n) for n in nums[:LISTED])
            more = f" and {len(nums) - LISTED} more" if len(nums) > LISTED else ""
            noun = self.noun if len(nums) == 1 else self.noun + "s"
            out.append(f"{noun} {shown}{more} of {self.labels[k]}")
        if len(by_part) > LISTED:
            out.append(f"{len(by_part) - LISTED} more parts")
        return "; ".join(out)
