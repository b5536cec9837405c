"""Wavefront OBJ and MTL text, and LightInv materials mappings, parsed into plain data.

OBJ coordinates times ``scale`` give metres; a y-up model is turned z-up. Faces keep
their vertex order (counter-clockwise seen from the front). Every problem with the
OBJ file or the materials mapping is an ``ObjImportError`` naming the file and line;
problems with MTL files are only warnings (their materials get the default reflectance).
Finding the MTL files and choosing each face's reflectance is ``obj_import``'s job.
"""

from __future__ import annotations

import json
import math
import numbers
import os
import stat
from collections import Counter
from collections.abc import Callable
from dataclasses import dataclass, field
from itertools import takewhile
from pathlib import Path

import numpy as np

from lightinv_core.errors import ObjImportError, SceneError
from lightinv_core.scene.model import ZONE_KINDS, check_reflectance
from lightinv_core.scene.obj_geometry import z_up
from lightinv_core.textcodec import decode_text

UP_AXES = ("z", "y")
# Statements LightInv does not need and skips silently (texture coordinates, normals,
# smoothing groups, lines, points).
IGNORED = frozenset({"vt", "vn", "s", "l", "p"})
# Largest coordinate accepted, in metres after scaling: beyond it areas overflow, and no
# building is that large (a bigger number means the scale is wrong).
MAX_COORD = 1e8
DEFAULT_REFLECTANCE = 0.5
KD_CAP = 0.95  # exporters write Kd 1 1 1 for white; a reflectance of 1 makes radiosity diverge
LISTED = 5  # names or line numbers listed in a message
MATERIALS_KEYS = ("default", "groups", "materials")


@dataclass(frozen=True)
class ObjFace:
    """One ``f`` statement: 0-based vertex indices, its line, lighting group and material."""

    index: tuple[int, ...]
    line: int
    group: str
    material: str | None


@dataclass
class ObjData:
    """A parsed OBJ file: vertices (n, 3) in metres, z up; faces; ``mtllib`` references."""

    vertices: np.ndarray
    faces: list[ObjFace]
    mtllibs: list[tuple[str, int]]
    warnings: list[str] = field(default_factory=list)


@dataclass(frozen=True)
class MaterialMap:
    """Explicit reflectances by lighting group and by material name, and the default."""

    default: float = DEFAULT_REFLECTANCE
    groups: dict[str, float] = field(default_factory=dict)
    materials: dict[str, float] = field(default_factory=dict)
    source: str = "materials mapping"


def clip(text: str, n: int = 40) -> str:
    """``repr`` of ``text`` cut to about ``n`` characters, for error messages."""
    return repr(text if len(text) <= n else text[:n] + "...")


def describe_lines(lines: list[int]) -> str:
    """'line 7' or 'lines 7, 9, 11, 13, 15 and 3 more'."""
    if len(lines) == 1:
        return f"line {lines[0]}"
    shown = ", ".join(str(n) for n in lines[:LISTED])
    return f"lines {shown}" + (f" and {len(lines) - LISTED} more" if len(lines) > LISTED else "")


def read_text(path: Path, what: str, guard: Callable[[Path, str], object] | None = None) -> str:
    """Read a regular file as text (``decode_text``); ObjImportError if impossible.

    ``guard(path, name)`` runs once the path is known to be a regular file and before
    it is read, to refuse files too big to import.
    """
    try:
        mode = os.stat(path).st_mode
    except FileNotFoundError:
        raise ObjImportError(f"{what} '{path}' does not exist; check the path") from None
    except (OSError, ValueError) as exc:
        raise ObjImportError(f"cannot read {what} '{path}': {_reason(exc)}") from None
    if not stat.S_ISREG(mode):
        raise ObjImportError(
            f"{what} '{path}' is not a file (a folder or device); give the path of the file"
        )
    if guard is not None:
        guard(Path(path), Path(path).name)
    try:
        data = Path(path).read_bytes()
    except OSError as exc:
        raise ObjImportError(
            f"cannot read {what} '{path}': {_reason(exc)}; check that it is readable"
        ) from None
    return decode_text(data)[0]


def _reason(exc: Exception) -> str:
    return getattr(exc, "strerror", None) or str(exc) or type(exc).__name__


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
    faces: list[ObjFace] = []
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
            faces.append(ObjFace(index, no, g or o or mtl or "default", mtl))
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
    return ObjData(vertices, faces, mtllibs, [_unknown_warning(unknown, fname)] if unknown else [])


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


def load_materials(materials) -> MaterialMap:
    """The materials mapping: None, a dict, or the path of a JSON file of the same form.

    The form is ``{"default": 0.5, "groups": {"floor": 0.2}, "materials": {"paint": 0.8}}``;
    every key is optional and every value is a reflectance in [0, 1).
    """
    if materials is None:
        return MaterialMap()
    if isinstance(materials, dict):
        return _material_map(materials, "materials mapping")
    if not isinstance(materials, str | os.PathLike):
        raise ObjImportError(
            f"materials must be a dict or the path of a JSON file, got {type(materials).__name__}"
        )
    path = Path(materials)
    text = read_text(path, "materials file")
    src = f"materials file '{path.name}'"
    try:
        obj = json.loads(text)
    except json.JSONDecodeError as exc:
        raise ObjImportError(
            f"{src} is not valid JSON: {exc.msg} at line {exc.lineno}, column {exc.colno}; "
            "fix the syntax"
        ) from None
    except (ValueError, RecursionError) as exc:
        raise ObjImportError(f"{src} is not valid JSON: {_reason(exc)}; fix the file") from None
    return _material_map(obj, src)


def _kind(obj) -> str:
    return {dict: "an object", list: "a list", str: "a string"}.get(type(obj), "a value")


def _material_map(obj, src: str) -> MaterialMap:
    if not isinstance(obj, dict):
        raise ObjImportError(
            f'{src}: expected an object like {{"default": 0.5, "groups": {{"floor": 0.2}}, '
            f'"materials": {{"white_paint": 0.8}}}}, got {_kind(obj)}'
        )
    extra = [k for k in obj if k not in MATERIALS_KEYS]
    if extra:
        raise ObjImportError(
            f'{src}: unknown key {clip(str(extra[0]))}; the keys are "default", "groups" '
            'and "materials"'
        )
    default = _rho(obj.get("default", DEFAULT_REFLECTANCE), f'{src}: key "default"')
    tables = []
    for key in ("groups", "materials"):
        table = obj.get(key, {})
        if not isinstance(table, dict):
            raise ObjImportError(
                f'{src}: "{key}" must be an object mapping names to reflectances, '
                f'e.g. {{"floor": 0.2}}, got {_kind(table)}'
            )
        tables.append({str(k): _rho(v, f'{src}: key "{key}"."{k}"') for k, v in table.items()})
    return MaterialMap(default, tables[0], tables[1], src)


def _rho(value, where: str) -> float:
    shown = repr(value) if len(repr(value)) <= 40 else repr(value)[:40] + "..."
    hint = "use a value such as 0.2 (dark floor) to 0.85 (white ceiling)"
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise ObjImportError(f"{where}: reflectance {shown} is not a number; {hint}")
    try:
        return check_reflectance(value, where)
    except SceneError as exc:
        raise ObjImportError(str(exc)) from None
    except OverflowError:
        raise ObjImportError(f"{where}: reflectance {shown} is outside [0, 1); {hint}") from None


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
    if kind.lower() not in ZONE_KINDS:
        raise ObjImportError(
            f"{where}: group {clip(group)}: zone kind {clip(kind)} is not one of "
            f"skylight, luminaire; name the group zone:{name}:skylight or zone:{name}:luminaire"
        )
    return name, kind.lower()
