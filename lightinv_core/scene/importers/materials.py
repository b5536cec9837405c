"""Reflectances: the user's materials mapping (by lighting group and by material name)
and, failing that, a material's colour from the file (MTL Kd, glTF baseColor) as a guess,
else the default. Every problem with the mapping is an ``ObjImportError``.
"""

from __future__ import annotations

import json
import numbers
import os
from dataclasses import dataclass, field
from pathlib import Path

from lightinv_core.errors import ObjImportError, SceneError
from lightinv_core.scene.importers.faces import LISTED, Places, clip
from lightinv_core.scene.importers.files import read_text, reason
from lightinv_core.scene.model import check_reflectance

DEFAULT_REFLECTANCE = 0.5
KD_CAP = 0.95  # exporters write Kd 1 1 1 for white; a reflectance of 1 makes radiosity diverge
MATERIALS_KEYS = ("default", "groups", "materials")


@dataclass(frozen=True)
class MaterialMap:
    """Explicit reflectances by lighting group and by material name, and the default."""

    default: float = DEFAULT_REFLECTANCE
    groups: dict[str, float] = field(default_factory=dict)
    materials: dict[str, float] = field(default_factory=dict)
    source: str = "materials mapping"


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
        raise ObjImportError(f"{src} is not valid JSON: {reason(exc)}; fix the file") from None
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


class Reflectances:
    """Reflectance of a (group, material): mapping by group, by material, the material's
    colour (MTL Kd, glTF baseColor), default."""

    def __init__(self, mats: MaterialMap, kd: dict[str, float], places: Places):
        self.mats, self.kd, self.places = mats, kd, places
        self.capped: dict[str, float] = {}
        self.defaulted: set[str] = set()
        self.bare: set[str] = set()  # groups with faces of no material, not mapped
        self.groups: set[str] = set()
        self.materials: set[str | None] = set()

    def __call__(self, group: str, material: str | None) -> float:
        self.groups.add(group)
        self.materials.add(material)
        if group in self.mats.groups:
            return self.mats.groups[group]
        if material in self.mats.materials:
            return self.mats.materials[material]
        if material in self.kd:
            lum = self.kd[material]
            if lum > KD_CAP:
                self.capped[material] = lum
            return min(lum, KD_CAP)
        if material is not None:
            self.defaulted.add(material)
        else:
            self.bare.add(group)
        return self.mats.default

    def defaults_used(self) -> list[str]:
        """Where the default reflectance stood in for one the file or the mapping did
        not give: materials without a colour, and groups whose faces name no material
        (an OBJ without MTL); each line says which default and where to give one."""
        out = []
        if self.defaulted:
            where = self.places.colour_file or f"its {self.places.colour}"
            out.append(
                f"no reflectance for material(s) {_names(self.defaulted)} (not in the materials "
                f"mapping or {where}); they use the default {self.mats.default:g}"
            )
        if self.bare:
            given = self.mats.default != DEFAULT_REFLECTANCE
            source = f"the {self.mats.source}'s default" if given else "the built-in default"
            every = " (every surface)" if self.bare == self.groups else ""
            out.append(
                f"no {self.places.colour} for group(s) {_names(self.bare)}{every}, and the "
                f"materials mapping does not name them: they use {source} reflectance "
                f"{self.mats.default:g}; give reflectances in a materials JSON file (the "
                "import dialog's Materials JSON) or change them after import"
            )
        return out

    def warnings(self) -> list[str]:
        """One warning per capped material, materials without a colour and unused
        mapping names (groups without any material are the import report's notes)."""
        colour = self.places.colour
        out = [
            f"material {clip(m)}: {colour} luminance {lum:.3g} capped at {KD_CAP} (exporters "
            f"write {self.places.white or colour + ' 1 1 1'} for white, and a reflectance of 1 "
            "makes radiosity diverge); give its reflectance in the materials mapping to "
            "silence this"
            for m, lum in self.capped.items()
        ]
        if self.defaulted:
            out.append(self.defaults_used()[0])
        for key, seen in (("groups", self.groups), ("materials", self.materials)):
            unused = set(getattr(self.mats, key)) - seen
            if unused:
                out.append(
                    f"{self.mats.source}: {key} {_names(unused)} do not occur in the "
                    f"{self.places.what} and are ignored; check the spelling"
                )
        return out


def _names(names) -> str:
    shown = sorted(names)
    return ", ".join(clip(n) for n in shown[:LISTED]) + (", ..." if len(shown) > LISTED else "")
