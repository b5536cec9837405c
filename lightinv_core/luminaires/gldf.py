"""GLDF (Global Lighting Data Format, ISO 7127) files: a product and its variants.

A ``.gldf`` file is a zip holding ``product.xml`` and the files it names (photometry in
``ldc/``, images, 3D models, ...). This module reads what lighting design needs:

- the **product** (name, number, manufacturer) and each **variant** (name, number), in
  the variants' ``sortOrder``;
- each variant's **light emitters** (``Variant/Geometry`` names ``Emitter`` ids): per
  emitter, its photometry file, rated flux (``FixedLightEmitter/RatedLuminousFlux``, or
  a changeable lamp's ``RatedLuminousFlux`` x ``lightSourceCount``), rated power
  (``FixedLightSource/RatedInputPower``, or the ``Equipment``'s), CCT and CRI (Ra) of
  its light source and the light source's maintenance (LLMF, LSF, LED factors);
- the product's size (``ProductSize``, a variant's own overriding it) and luminaire
  maintenance (CIE LMF by years and room condition, useful lives such as "L80B50").

One ``Emitter`` may hold several light emitters: they are alternatives (modes), not on
together (gldf.io, "Emitters"); the first one not marked ``EmergencyOnly`` is the normal
light, the others are listed in the notes. Several emitters of one variant are on
together (a direct and an indirect part). How they become one photometric table is
``gldf_light.py``.

**Why our own reader and not ``gldf-rs-python``** (MIT, a 7 MB Rust extension, installs
on this Python): it turns product.xml into JSON or XML text and nothing more, so the
walk from a variant to its emitters, light sources, equipment and files, the zip access
and every error message would still be ours. The standard library's ``zipfile`` and
``xml.etree`` do the rest in a few hundred lines without a binary dependency.

Read: GLDF 1.0 (1.0.0-rc.1 to rc.3 and 1.0); 0.9 drafts (``LightEmitter`` with
attributes) are refused. Not read: geometry (L3D/R3D), images, sensors, spectra,
multi-channel emitters, emitter rotations (a rotated emitter is refused), photometry
given as a URL, IES XML.
"""

from __future__ import annotations

import os
import zipfile
from dataclasses import dataclass, field
from pathlib import Path
from xml.etree import ElementTree as ET

from lightinv_core.luminaires.gldf_xml import (
    GldfEmitter,
    Index,
    Maintenance,
    attribute,
    emitter_ids,
    locale,
    luminaire_maintenance,
    size,
    text,
)
from lightinv_core.luminaires.photometry import fail

__all__ = ["GldfEmitter", "GldfProduct", "GldfVariant", "Maintenance", "read_gldf", "read_member"]

MAX_XML_BYTES = 20_000_000
"""Bytes of product.xml (real ones are 5-100 kB); larger ones are refused unread."""
MAX_MEMBER_BYTES = 20_000_000
"""Bytes of one photometry file inside the zip (the photometric readers' own limit)."""


@dataclass(frozen=True)
class GldfVariant:
    """A variant: ``name`` is the product's name and the variant's (one catalogue
    product), ``emitters`` the light emitters that are on together."""

    variant_id: str
    name: str
    variant_name: str
    number: str
    emitters: tuple[GldfEmitter, ...]
    size_m: tuple[float, float, float] | None
    maintenance: Maintenance
    notes: tuple[str, ...] = ()

    @property
    def lumens(self) -> float | None:
        """Rated flux of the emitters together, lm (None unless every one states it)."""
        values = [e.lumens for e in self.emitters]
        return None if None in values else float(sum(values))  # type: ignore[arg-type]

    @property
    def watts(self) -> float | None:
        """Rated input power of the emitters together, W (None unless each states it)."""
        values = [e.watts for e in self.emitters]
        return None if None in values else float(sum(values))  # type: ignore[arg-type]

    def _one(self, attr: str) -> float | None:
        values = {getattr(e, attr) for e in self.emitters} - {None}
        return values.pop() if len(values) == 1 else None

    @property
    def cct_k(self) -> float | None:
        """Correlated colour temperature, K, when its light sources agree on one."""
        return self._one("cct_k")

    @property
    def cri_ra(self) -> float | None:
        """Colour rendering index Ra, when its light sources agree on one."""
        return self._one("cri_ra")


@dataclass(frozen=True)
class GldfProduct:
    """What a GLDF file holds: one product and its variants (at least one)."""

    path: Path
    name: str
    number: str
    manufacturer: str
    format_version: str
    variants: tuple[GldfVariant, ...] = field(default=())

    def variant(self, variant_id: str | None) -> GldfVariant:
        """The variant ``variant_id`` (None: the first), or a PhotometryError."""
        if variant_id is None:
            return self.variants[0]
        for v in self.variants:
            if v.variant_id == variant_id:
                return v
        known = ", ".join(v.variant_id for v in self.variants)
        raise fail(str(self.path), None, f"no variant {variant_id!r}", f"it has: {known}")


def _strip(root: ET.Element) -> ET.Element:
    """Tags without XML namespaces (GLDF uses none, but a writer may add one)."""
    for e in root.iter():
        if isinstance(e.tag, str) and "}" in e.tag:
            e.tag = e.tag.rsplit("}", 1)[1]
    return root


def _version(source: str, header: ET.Element | None) -> str:
    """'major.minor[-rc.N]' from FormatVersion (attributes from rc.2 on, text before)."""
    fv = header.find("FormatVersion") if header is not None else None
    if fv is None:
        return "?"
    if fv.get("major") is not None:
        shown = f"{fv.get('major')}.{fv.get('minor', '0')}"
        pre = fv.get("pre-release")
        shown += f"-rc.{pre}" if pre and pre != "0" else ""
    else:
        shown = text(fv)
    if not shown.startswith("1"):
        raise fail(
            source,
            None,
            f"GLDF format version {shown!r}; this reader takes GLDF 1.0",
            "export the product again as GLDF 1.0 (DIALux, Relux or the maker's site)",
        )
    return shown


def _open(path: Path) -> tuple[zipfile.ZipFile, ET.Element]:
    """The zip, open, and product.xml's root; a PhotometryError if either is not right."""
    source = str(path)
    try:
        archive = zipfile.ZipFile(path)
    except FileNotFoundError:
        raise fail(source, None, "no such file", "check the path") from None
    except (zipfile.BadZipFile, OSError, ValueError) as exc:
        what = f"not a GLDF file (not a zip archive: {exc})"
        raise fail(source, None, what, "give a .gldf file as exported") from None
    try:
        return archive, _product_xml(source, archive)
    except BaseException:
        archive.close()
        raise


def _product_xml(source: str, archive: zipfile.ZipFile) -> ET.Element:
    try:
        info = archive.getinfo("product.xml")
    except KeyError:
        raise fail(source, None, "no product.xml in the zip", "a GLDF holds one") from None
    if info.file_size > MAX_XML_BYTES:
        raise fail(source, None, "product.xml is too large", "check the file")
    try:
        data = archive.read(info)
    except (zipfile.BadZipFile, OSError, ValueError, EOFError) as exc:
        what = f"product.xml cannot be unpacked ({exc})"
        raise fail(source, None, what, "the file is damaged: download it again") from None
    if b"<!ENTITY" in data:  # entity expansion is how a small XML asks for gigabytes
        raise fail(source, None, "product.xml defines XML entities", "GLDF uses none")
    try:
        root = _strip(ET.fromstring(data))
    except ET.ParseError as exc:
        what = f"product.xml is not valid XML ({exc})"
        raise fail(source, None, what, "export the GLDF again") from None
    if root.tag != "Root" or root.find("ProductDefinitions") is None:
        raise fail(source, None, f"product.xml's root is <{root.tag}>", "not a GLDF product")
    return root


def _variant_name(product: str, variant: str) -> str:
    """Product and variant as one catalogue name, without saying a name twice."""
    if not variant or variant.strip("-_ ") == "" or variant in product:
        return product
    if product in variant:
        return variant
    return f"{product} {variant}"


def read_gldf(path: str | os.PathLike) -> GldfProduct:
    """Read a GLDF file's product and variants (not their photometry: see
    ``gldf_light.variant_photometry``); every problem is a one-line PhotometryError."""
    p = Path(path)
    source = str(path)
    archive, root = _open(p)
    with archive:
        version = _version(source, root.find("Header"))
        index = Index(source, root, archive)
        meta = root.find("ProductDefinitions/ProductMetaData")
        product = locale(meta, "Name") or p.stem
        number = locale(meta, "ProductNumber")
        elements = root.findall("ProductDefinitions/Variants/Variant")
        # Stable: variants without a sortOrder, or with the same one, keep the file's order.
        elements.sort(key=lambda v: attribute(source, v, "sortOrder", 0.0))
        variants = []
        for v in elements:
            notes: list[str] = []
            ids = emitter_ids(v)
            if not ids and len(index.emitters) == 1:
                ids = list(index.emitters)
                notes.append(
                    f"the variant names no emitter; the file's only one ({ids[0]}) is used"
                )
            emitters = [e for e in (index.emitter(i, notes) for i in ids) if e is not None]
            if not emitters:
                continue  # a sensor or an emergency-only variant: no light to design with
            lamp = emitters[0].maintenance
            variant_name = locale(v, "Name")
            variants.append(
                GldfVariant(
                    variant_id=v.get("id", ""),
                    name=_variant_name(product, variant_name),
                    variant_name=variant_name,
                    number=locale(v, "ProductNumber") or number,
                    emitters=tuple(emitters),
                    size_m=size(source, v, meta),
                    maintenance=luminaire_maintenance(source, meta, lamp),
                    notes=tuple(notes),
                )
            )
    if not variants:
        raise fail(source, None, "no variant with a light emitter", "nothing to light with")
    return GldfProduct(
        path=p,
        name=product,
        number=number,
        manufacturer=text(root, "Header/Manufacturer"),
        format_version=version,
        variants=tuple(variants),
    )


def read_member(path: str | os.PathLike, member: str) -> bytes:
    """The bytes of one file inside a GLDF (at most ``MAX_MEMBER_BYTES``)."""
    source = f"{path}:{member}"
    archive, _ = _open(Path(path))
    with archive:
        info = archive.getinfo(member)
        if info.file_size > MAX_MEMBER_BYTES:
            raise fail(source, None, "too large for a photometric file", "check the GLDF")
        try:
            return archive.read(info)
        except (zipfile.BadZipFile, OSError, ValueError) as exc:
            raise fail(source, None, f"cannot be unpacked: {exc}", "check the GLDF") from None
