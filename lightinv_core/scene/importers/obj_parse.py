"""Wavefront OBJ and MTL text parsed into plain data (``faces.Polygons``).

OBJ coordinates times ``scale`` give metres; a y-up model is turned z-up. Faces keep
their vertex order (counter-clockwise seen from the front). Every problem with the
OBJ file is an ``ObjImportError`` naming the file and line; problems with MTL files
are only warnings (their materials get the default reflectance). Finding the MTL files
is ``obj``'s job, choosing each face's reflectance ``materials``'.
"""

from __future__ import annotations

import math
from collections import Counter
from dataclasses import dataclass, field
from itertools import takewhile

import numpy as np

from lightinv_core.errors import ObjImportError
from lightinv_core.scene.importers.faces import MAX_COORD, Face, Polygons, clip
from lightinv_core.scene.importers.geometry import z_up


@dataclass
class ObjData(Polygons):
    """A parsed OBJ file: its polygons and its ``mtllib`` references (name, line)."""

    mtllibs: list[tuple[str, int]] = field(default_factory=list)


# Statements LightInv does not need and skips silently (texture coordinates, normals,
# smoothing groups, lines, points).
IGNORED = frozenset({"vt", "vn", "s", "l", "p"})


def _statements(text: str):
    """Yield (line number, tokens, text after the keyword); a trailing '\\' continues a line."""
    lines = text.replace("\r\n", "\n").replace("\r", "\n").split("\n")
    pending, start = "", 0
    for no, raw in enumerate([*lines, ""], 1):  # the extra "" ends a pending continuation
        start = start if pending else no
        if raw.endswith("\\"):
            pending += raw[:-1] + " "
            continue
        body, pending = (pending + raw).strip(), ""
        if body and not body.startswith("#"):
            tokens = body.split()
            yield start, tokens, body[len(tokens[0]) :].strip()


def _data(tokens: list[str]) -> list[str]:
    """The arguments of a ``v`` or ``f`` statement, without a trailing '# comment'."""
    return list(takewhile(lambda tok: not tok.startswith("#"), tokens[1:]))


def parse_obj(text: str, fname: str, scale: float, up: str) -> ObjData:
    """Parse OBJ ``text`` (from file ``fname``) into vertices in metres (z up) and faces."""
    coords: list[tuple[float, float, float]] = []
    vlines: list[int] = []
    faces: list[Face] = []
    mtllibs: list[tuple[str, int]] = []
    unknown: Counter[str] = Counter()
    g = o = mtl = None
    for no, tokens, rest in _statements(text):
        kw, where = tokens[0], f"{fname} line {no}"
        if kw == "v":
            coords.append(_vertex(tokens, where))
            vlines.append(no)
        elif kw == "f":
            index = _face(tokens, len(coords), where)
            faces.append(Face(index, no, g or o or mtl or "default", mtl))
        elif kw == "g":
            g = next(iter(_data(tokens)), None)
        elif kw == "o":
            # A new object ends the previous object's groups.
            o, g = rest or None, None
        elif kw == "usemtl":
            mtl = rest or None
        elif kw == "mtllib":
            if rest:
                mtllibs.append((rest, no))
        elif kw not in IGNORED:
            unknown[kw] += 1
    for f in faces:
        top = max(f.index)
        if top >= len(coords):
            raise ObjImportError(
                f"{fname} line {f.line}: the face refers to vertex {top + 1} but the file "
                f"defines only {len(coords)} vertices; the file may be truncated, re-export it"
            )
    vertices = _to_metres(coords, vlines, scale, up, fname)
    warnings = [_unknown_warning(unknown, fname)] if unknown else []
    return ObjData(vertices, faces, warnings, mtllibs)


def _number(tok: str, where: str, what: str) -> float:
    try:
        x = float(tok)
    except ValueError:
        hint = " (use a decimal point, not a comma)" if "," in tok else ""
        raise ObjImportError(
            f"{where}: {what} {clip(tok)} is not a number{hint}; fix or remove the line"
        ) from None
    if not math.isfinite(x):
        raise ObjImportError(f"{where}: {what} {clip(tok)} is not finite; fix or remove the line")
    return x


def _vertex(tokens: list[str], where: str) -> tuple[float, float, float]:
    vals = _data(tokens)
    if len(vals) < 3:
        raise ObjImportError(
            f"{where}: a vertex needs 3 coordinates ('v x y z'), got {len(vals)}; "
            "fix or remove the line"
        )
    # Values after z (w, or vertex colours some exporters write) are checked, then ignored.
    xyz = [_number(tok, where, "vertex coordinate") for tok in vals]
    return xyz[0], xyz[1], xyz[2]


def _face(tokens: list[str], nverts: int, where: str) -> tuple[int, ...]:
    refs = _data(tokens)
    if len(refs) < 3:
        raise ObjImportError(
            f"{where}: a face needs at least 3 vertices, got {len(refs)}; remove the line "
            "(write lines as 'l', not 'f')"
        )
    out = []
    for tok in refs:
        try:
            k = int(tok.split("/", 1)[0])
        except ValueError:
            raise ObjImportError(
                f"{where}: {clip(tok)} is not a vertex reference (v, v/vt, v//vn or v/vt/vn "
                "with whole numbers); fix the face"
            ) from None
        if k == 0:
            raise ObjImportError(
                f"{where}: vertex index 0 is invalid (OBJ indices start at 1; negative ones "
                "count back from the last vertex); fix the face"
            )
        if k < 0 and -k > nverts:
            raise ObjImportError(
                f"{where}: relative vertex index {k} points before the first vertex (only "
                f"{nverts} vertices are defined above this line); fix the face"
            )
        out.append(k + nverts if k < 0 else k - 1)
    return tuple(out)


def _to_metres(coords, vlines: list[int], scale: float, up: str, fname: str) -> np.ndarray:
    with np.errstate(all="ignore"):
        v = np.array(coords, dtype=float).reshape(-1, 3) * scale
    v = z_up(v, up)
    big = np.flatnonzero(~(np.abs(v) <= MAX_COORD).all(axis=1))
    if len(big):
        raise ObjImportError(
            f"{fname} line {vlines[big[0]]}: a coordinate is larger than {MAX_COORD:g} m after "
            f"scaling by {scale:g}; check the model's units and the scale"
        )
    return v


def _unknown_warning(unknown: Counter[str], fname: str) -> str:
    kinds = ", ".join(f"{clip(k, 12)} x{n}" for k, n in unknown.most_common(5))
    more = ", ..." if len(unknown) > 5 else ""
    return (
        f"{fname}: ignored {sum(unknown.values())} unsupported statement(s) ({kinds}{more}); "
        "LightInv reads only vertices and polygon faces"
    )


def parse_mtl(text: str, fname: str, warnings: list[str]) -> dict[str, float]:
    """Kd luminance per ``newmtl`` material of MTL ``text``; unreadable Kd lines are warnings."""
    lum: dict[str, float] = {}
    current = None
    for no, tokens, rest in _statements(text):
        if tokens[0] == "newmtl":
            current = rest or None
        elif tokens[0] == "Kd" and current is not None:
            vals = _data(tokens)
            try:
                rgb = [float(t) for t in vals]
            except ValueError:
                rgb = []
            rgb = rgb * 3 if len(rgb) == 1 else rgb[:3]
            if len(rgb) != 3 or not all(math.isfinite(c) and c >= 0 for c in rgb):
                warnings.append(
                    f"{fname} line {no}: cannot use Kd {clip(rest)} of material "
                    f"{clip(current)}; it gets the default reflectance"
                )
                continue
            lum[current] = 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]
    return lum
