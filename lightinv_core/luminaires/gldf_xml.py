"""GLDF product.xml: its definitions by id, and a variant's light emitters read from them.

``gldf.py`` opens the file and walks the variants; this module knows the elements
(GLDF 1.0, gldf.io's XSD 1.0.0-rc.3): Files, Photometries, Fixed and Changeable
LightSources, Equipments, Emitters, maintenance and product size. Numbers are the
units the XSD gives: lm, W, K, mm (converted to m here), hours, years.
"""

from __future__ import annotations

import math
import zipfile
from dataclasses import dataclass
from xml.etree import ElementTree as ET

from lightinv_core.luminaires.photometry import fail

PHOTOMETRY_TYPES = {"ldc/eulumdat": "ldt", "ldc/ies": "ies"}
"""GLDF content types read, and the reader each goes to."""


@dataclass(frozen=True)
class Maintenance:
    """Maintenance data a GLDF states (empty tuples where it states none).

    ``lamp``: (hours, LLMF, LSF) of the light source (CIE lamp factors by burning time,
    or LED factors with LSF 1); ``luminaire``: (years, room condition, LMF);
    ``lifetime_h``: the light source's expected life, h; ``useful_life``: texts such as
    "L80B50 70000h 25°C"."""

    lamp: tuple[tuple[float, float, float], ...] = ()
    luminaire: tuple[tuple[float, str, float], ...] = ()
    lifetime_h: float | None = None
    useful_life: tuple[str, ...] = ()

    def empty(self) -> bool:
        """Whether nothing is stated."""
        return not (self.lamp or self.luminaire or self.lifetime_h or self.useful_life)


@dataclass(frozen=True)
class GldfEmitter:
    """One light emitter of a variant: its photometry file in the zip (``member``, read
    as ``kind`` 'ldt' or 'ies'), rated flux (lm) and power (W) as the GLDF states them
    (None where it does not), light source colour and maintenance."""

    emitter_id: str
    member: str
    kind: str
    lumens: float | None
    watts: float | None
    cct_k: float | None = None
    cri_ra: float | None = None
    lamp: str = ""
    rotated: str = ""
    maintenance: Maintenance = Maintenance()


def text(e: ET.Element | None, path: str = "") -> str:
    """The text at ``path`` under ``e`` (``e``'s own without a path), whitespace joined."""
    if e is None:
        return ""
    node = e.find(path) if path else e
    return " ".join((node.text or "").split()) if node is not None else ""


def locale(e: ET.Element | None, path: str) -> str:
    """A translatable text: English if given, else the first language."""
    node = e.find(path) if e is not None else None
    if node is None:
        return ""
    locales = node.findall("Locale")
    chosen = next((x for x in locales if (x.get("language") or "").startswith("en")), None)
    return text(chosen if chosen is not None else (locales[0] if locales else node))


def number(source: str, e: ET.Element | None, path: str, signed: bool = False) -> float | None:
    """The number at ``path`` under ``e`` (None if absent); >= 0 unless ``signed``."""
    return _checked(source, text(e, path), path or (e.tag if e is not None else ""), signed)


def attribute(source: str, e: ET.Element, name: str, default: float | None = None) -> float | None:
    """The number in attribute ``name`` of ``e`` (``default`` if absent), >= 0."""
    value = _checked(source, (e.get(name) or "").strip(), f"{e.tag} {name}", False)
    return default if value is None else value


def _checked(source: str, shown: str, what: str, signed: bool) -> float | None:
    if not shown:
        return None
    try:
        value = float(shown.replace(",", "."))
    except ValueError:
        raise fail(source, None, f"{what} is {shown[:24]!r}", "it must be a number") from None
    if not math.isfinite(value) or (value < 0 and not signed):
        raise fail(source, None, f"{what} is {shown[:24]}", "it must be a finite number >= 0")
    return value


def member(source: str, archive: zipfile.ZipFile, name: str) -> str:
    """The zip member of a file named in product.xml: in the folder of its content
    type (``ldc/``) per the container rules, else wherever a member of that name is."""
    names = archive.namelist()
    for candidate in (f"ldc/{name}", name):
        if candidate in names:
            return candidate
    tail = name.rsplit("/", 1)[-1]
    found = [n for n in names if n.rsplit("/", 1)[-1] == tail]
    if found:
        return found[0]
    raise fail(
        source,
        None,
        f"the photometry file {name!r} named in product.xml is not in the GLDF",
        "the file is incomplete: export it again",
    )


class Index:
    """product.xml's definitions by id."""

    def __init__(self, source: str, root: ET.Element, archive: zipfile.ZipFile) -> None:
        self.source, self.archive = source, archive
        defs = root.find("GeneralDefinitions")
        defs = defs if defs is not None else ET.Element("GeneralDefinitions")

        def by_id(path: str) -> dict[str, ET.Element]:
            return {e.get("id", ""): e for e in defs.findall(path)}

        self.files = by_id("Files/File")
        self.photometries = by_id("Photometries/Photometry")
        self.fixed = by_id("LightSources/FixedLightSource")
        self.changeable = by_id("LightSources/ChangeableLightSource")
        self.equipment = by_id("Equipments/Equipment")
        self.emitters = by_id("Emitters/Emitter")

    def get(self, table: dict[str, ET.Element], key: str, what: str) -> ET.Element:
        if key not in table:
            raise fail(self.source, None, f"{what} {key!r} is referenced but not defined", "")
        return table[key]

    def photometry(self, light: ET.Element) -> tuple[str, str]:
        """(zip member, 'ldt' or 'ies') of a light emitter's photometry."""
        ref = light.find("PhotometryReference")
        if ref is None:
            raise fail(self.source, None, "a light emitter has no photometry", "")
        ph = self.get(self.photometries, ref.get("photometryId", ""), "photometry")
        file_ref = ph.find("PhotometryFileReference")
        f = self.get(self.files, file_ref.get("fileId", "") if file_ref is not None else "", "file")
        ctype, name = f.get("contentType", ""), text(f)
        if ctype not in PHOTOMETRY_TYPES:
            raise fail(
                self.source,
                None,
                f"photometry {name!r} is of type {ctype!r}",
                "LightInv reads EULUMDAT (ldc/eulumdat) and IES (ldc/ies) photometry",
            )
        if f.get("type") == "url":
            raise fail(
                self.source,
                None,
                f"the photometry is a link ({name[:80]}), not inside the GLDF",
                "download that file and open it as .ldt/.ies, or use a GLDF that holds it",
            )
        return member(self.source, self.archive, name), PHOTOMETRY_TYPES[ctype]

    def emitter(self, emitter_id: str, notes: list[str]) -> GldfEmitter | None:
        """The normal light of ``Emitter`` ``emitter_id`` (None for a sensor)."""
        e = self.get(self.emitters, emitter_id, "emitter")
        if e.find("LightEmitter") is not None:
            raise fail(self.source, None, "a GLDF 0.9 <LightEmitter>", "export it as GLDF 1.0")
        lights = [x for x in e if x.tag in ("FixedLightEmitter", "ChangeableLightEmitter")]
        if not lights:
            if e.find("MultiChannelLightEmitter") is not None:
                raise fail(self.source, None, f"emitter {emitter_id!r} is multi-channel", "")
            return None
        normal = [x for x in lights if x.get("emergencyBehaviour") != "EmergencyOnly"]
        if not normal:
            notes.append(f"emitter {emitter_id}: emergency lighting only, not counted")
            return None
        if len(lights) > 1:
            notes.append(
                f"emitter {emitter_id}: {len(lights)} alternative modes, the first for "
                "normal lighting is used"
            )
        return self._light(emitter_id, normal[0])

    def _light(self, emitter_id: str, light: ET.Element) -> GldfEmitter:
        member, kind = self.photometry(light)
        rotation = light.find("Rotation")
        turned = []
        for axis in ("X", "Y", "Z", "G0") if rotation is not None else ():
            angle = number(self.source, rotation, axis, signed=True)
            if angle:
                turned.append(f"{axis} {angle:g} deg")
        if light.tag == "FixedLightEmitter":
            ref = light.find("LightSourceReference")
            ls_id = ref.get("fixedLightSourceId", "") if ref is not None else ""
            source = self.get(self.fixed, ls_id, "light source")
            lumens = number(self.source, light, "RatedLuminousFlux")
            watts = number(self.source, source, "RatedInputPower")
        else:
            source, lumens, watts = None, None, None
            eq_ref = light.find("EquipmentReference")
            if eq_ref is not None:
                eq = self.get(self.equipment, eq_ref.get("equipmentId", ""), "equipment")
                watts = number(self.source, eq, "RatedInputPower")
                ls_ref = eq.find("LightSourceReference")
                ls_id = ls_ref.get("changeableLightSourceId", "") if ls_ref is not None else ""
                if ls_id:
                    source = self.get(self.changeable, ls_id, "light source")
                    count = attribute(self.source, ls_ref, "lightSourceCount", 1.0)  # type: ignore[arg-type]
                    each = number(self.source, source, "RatedLuminousFlux")
                    lumens = None if each is None else each * count
        return GldfEmitter(
            emitter_id=emitter_id,
            member=member,
            kind=kind,
            lumens=lumens,
            watts=watts,
            cct_k=number(self.source, source, "ColorInformation/CorrelatedColorTemperature"),
            cri_ra=number(self.source, source, "ColorInformation/ColorRenderingIndex"),
            lamp=locale(source, "Name"),
            rotated=", ".join(turned),
            maintenance=lamp_maintenance(self.source, source),
        )


def lamp_maintenance(source: str, light_source: ET.Element | None) -> Maintenance:
    """A light source's LightSourceMaintenance: CIE lamp factors or LED factors."""
    m = light_source.find("LightSourceMaintenance") if light_source is not None else None
    if m is None:
        return Maintenance()
    rows = []
    for f in m.findall("CieLampMaintenanceFactors/CieLampMaintenanceFactor"):
        hours = attribute(source, f, "burningTime", math.nan)
        llmf = number(source, f, "LampLumenMaintenanceFactor")
        lsf = number(source, f, "LampSurvivalFactor")
        rows.append((hours, llmf if llmf is not None else 1.0, lsf if lsf is not None else 1.0))
    for f in m.findall("LedMaintenanceFactor"):
        value = number(source, f, "")
        hours = attribute(source, f, "hours", math.nan)
        rows.append((hours, value if value is not None else 1.0, 1.0))
    return Maintenance(lamp=tuple(rows), lifetime_h=attribute(source, m, "lifetime"))


def luminaire_maintenance(source: str, meta: ET.Element | None, lamp: Maintenance) -> Maintenance:
    """``lamp`` with the product's luminaire maintenance factors and useful lives."""
    lmf = []
    if meta is not None:
        for f in meta.findall("LuminaireMaintenance/CieLuminaireMaintenanceFactors/*"):
            value = number(source, f, "")
            if value is not None:
                years = attribute(source, f, "years", math.nan)
                lmf.append((years, f.get("roomCondition", ""), value))
    lives = []
    for path in ("UsefulLifeTimes/UsefulLife", "MedianUsefulLifeTimes/MedianUsefulLife"):
        for tree in (meta,) if meta is not None else ():
            lives += [
                text(x)
                for x in tree.findall(f"DescriptiveAttributes/OperationsAndMaintenance/{path}")
            ]
    return Maintenance(lamp.lamp, tuple(lmf), lamp.lifetime_h, tuple(x for x in lives if x))


def size(source: str, *holders: ET.Element | None) -> tuple[float, float, float] | None:
    """ProductSize (length, width, height), m, of the first holder that states it."""
    for h in holders:
        size = h.find("DescriptiveAttributes/Mechanical/ProductSize") if h is not None else None
        if size is not None:
            mm = [number(source, size, k) for k in ("Length", "Width", "Height")]
            return tuple(0.0 if x is None else x / 1000.0 for x in mm)  # type: ignore[return-value]
    return None


def emitter_ids(variant: ET.Element) -> list[str]:
    """The ids of the emitters a variant names (any form of Geometry), once each."""
    geometry = variant.find("Geometry")
    ids: list[str] = []
    for e in geometry.iter() if geometry is not None else ():
        key = e.get("emitterId")
        if key and key not in ids:
            ids.append(key)
    return ids
