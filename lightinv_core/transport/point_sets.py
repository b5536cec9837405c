"""Receiver point sets: where and facing which way light is read, and how the samples
make the values a designer asks for.

A ``PointSet`` holds ``q`` sample points with their unit normals and, when a value is
not the illuminance of one sample, a ``reduce`` matrix (r, q): value = reduce @
(illuminance at the samples). Cylindrical illuminance Ez is the mean of the vertical
illuminance over N horizontal directions around a point (``design/model/calc_kinds.py``)
and semi-cylindrical illuminance Esc = Ez + (Ev(facing) - Ev(behind)) / pi; both are
fixed rows of ``reduce``. Light is linear, so every path that lights samples (zone
basis, luminaire responses, clear glazing) lights the values by one sparse product.

``read_points_csv`` reads a free point set: ``x,y,z`` or ``x,y,z,nx,ny,nz`` per line
(m; a header line and blank lines allowed), every bad row named by its line number.
"""

from __future__ import annotations

import csv
import io
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import scipy.sparse as sp

from lightinv_core.errors import LightInvError

UP = np.array([0.0, 0.0, 1.0])
MAX_POINTS = 1_000_000
"""Most points a CSV may hold (each costs a row of form factors)."""


@dataclass(frozen=True, eq=False)
class PointSet:
    """Samples ``points`` (q, 3) m facing unit ``normals`` (q, 3), read as r values by
    ``reduce`` (r, q) (None: each sample is a value, r = q); ``at`` (r, 3) m: where each
    value is shown (a cylinder's axis point; default the samples)."""

    points: np.ndarray
    normals: np.ndarray
    reduce: sp.csr_matrix | None = None
    at: np.ndarray | None = None

    def __post_init__(self) -> None:
        pts = np.asarray(self.points, dtype=float).reshape(-1, 3)
        nrm = np.broadcast_to(np.asarray(self.normals, dtype=float), pts.shape).copy()
        length = np.linalg.norm(nrm, axis=1)
        if np.any(length == 0) or not np.all(np.isfinite(pts)):
            raise LightInvError("a point set needs finite points and non-zero normals")
        object.__setattr__(self, "points", pts)
        object.__setattr__(self, "normals", nrm / length[:, None])
        if self.reduce is not None:
            object.__setattr__(self, "reduce", sp.csr_matrix(self.reduce))
        at = pts if self.at is None else np.asarray(self.at, dtype=float).reshape(-1, 3)
        object.__setattr__(self, "at", at)

    @property
    def size(self) -> int:
        """Number of values r."""
        return len(self.at)

    def values(self, at_samples: np.ndarray) -> np.ndarray:
        """The values (r, ...) from the illuminance at the samples (q, ...)."""
        a = np.asarray(at_samples)
        if self.reduce is None:
            return a
        return (
            np.asarray(self.reduce @ a.reshape(len(self.points), -1))
            .reshape((self.size, *a.shape[1:]))
            .astype(a.dtype, copy=False)
        )

    def key(self) -> bytes:
        """Bytes that tell two point sets apart (caches)."""
        parts = [self.points.tobytes(), self.normals.tobytes()]
        if self.reduce is not None:
            r = self.reduce
            parts += [r.indptr.tobytes(), r.indices.tobytes(), r.data.tobytes()]
        return b"|".join(parts)


def as_point_set(points: np.ndarray | PointSet | None) -> PointSet:
    """``points`` as a ``PointSet``: an array (q, 3) is q samples facing up (a work
    plane's grid), None is no point."""
    if isinstance(points, PointSet):
        return points
    pts = np.zeros((0, 3)) if points is None else np.asarray(points, float).reshape(-1, 3)
    return PointSet(pts, np.broadcast_to(UP, pts.shape))


def stack(sets: list[PointSet]) -> PointSet:
    """One point set of several, in order (their reduce matrices block-diagonal)."""
    if not sets:
        return as_point_set(None)
    pts = np.vstack([s.points for s in sets])
    nrm = np.vstack([s.normals for s in sets])
    at = np.vstack([s.at for s in sets])
    if all(s.reduce is None for s in sets):
        return PointSet(pts, nrm, None, at)
    blocks = [s.reduce if s.reduce is not None else sp.identity(len(s.points)) for s in sets]
    return PointSet(pts, nrm, sp.block_diag(blocks, format="csr"), at)


def read_points_csv(path: str | Path) -> tuple[np.ndarray, np.ndarray | None]:
    """Points (q, 3) m and their normals (q, 3) (None when no row gives one) from a CSV
    file of ``x,y,z[,nx,ny,nz]`` rows (comma, semicolon or tab separated; a first line
    that is not numbers is a header). LightInvError naming the line of a bad row."""
    p = Path(path)
    try:
        text = p.read_text(encoding="utf-8-sig")
    except OSError as exc:
        raise LightInvError(f"cannot read the points file {p}: {exc.strerror or exc}") from None
    except UnicodeDecodeError:
        raise LightInvError(f"the points file {p} is not text (UTF-8)") from None
    return parse_points_csv(text, p.name)


def parse_points_csv(text: str, name: str = "points") -> tuple[np.ndarray, np.ndarray | None]:
    """``read_points_csv`` of the text of a file called ``name`` (for messages)."""
    sample = text[:4096]
    delim = max((",", ";", "\t"), key=sample.count) if sample.strip() else ","
    rows, normals, widths = [], [], set()
    for line_no, row in enumerate(csv.reader(io.StringIO(text), delimiter=delim), 1):
        cells = [c.strip() for c in row]
        if not any(cells):
            continue
        while cells and not cells[-1]:
            cells.pop()
        try:
            values = [float(c) for c in cells]
        except ValueError:
            if not rows and line_no == _first_line(text):
                continue  # a header
            raise LightInvError(
                f"{name}, line {line_no}: expected numbers x,y,z[,nx,ny,nz], "
                f"got {','.join(cells)!r}"
            ) from None
        if len(values) not in (3, 6):
            raise LightInvError(
                f"{name}, line {line_no}: expected 3 values (x,y,z) or 6 (x,y,z,nx,ny,nz), "
                f"got {len(values)}"
            )
        if not all(math.isfinite(v) for v in values):
            raise LightInvError(f"{name}, line {line_no}: a value is not a finite number")
        if len(values) == 6 and math.hypot(*values[3:]) == 0:
            raise LightInvError(f"{name}, line {line_no}: the normal (0, 0, 0) has no direction")
        widths.add(len(values))
        rows.append(values[:3])
        normals.append(values[3:] if len(values) == 6 else [0.0, 0.0, 1.0])
        if len(rows) > MAX_POINTS:
            raise LightInvError(f"{name}: more than {MAX_POINTS:,} points")
    if not rows:
        raise LightInvError(f"{name}: no point (rows of x,y,z[,nx,ny,nz] in metres)")
    if widths == {3, 6}:
        raise LightInvError(
            f"{name}: some rows give a normal and some do not; give all six values on every "
            "row, or three on every row (facing up)"
        )
    pts = np.array(rows, dtype=float)
    if widths == {3}:
        return pts, None
    nrm = np.array(normals, dtype=float)
    return pts, nrm / np.linalg.norm(nrm, axis=1)[:, None]


def _first_line(text: str) -> int:
    """The number of the first non-blank line of ``text``."""
    for i, line in enumerate(text.splitlines(), 1):
        if line.strip():
            return i
    return 1
