"""A real GLDF file with a second variant added (the shipped examples have one each):
the same product.xml with its first variant copied under a new id and name, every
other member of the zip unchanged."""

from __future__ import annotations

import io
import zipfile
from pathlib import Path
from xml.etree import ElementTree as ET


def with_second_variant(
    src: Path, dst: Path, variant_id: str = "variant2", name: str = "wide"
) -> Path:
    """Write ``src`` to ``dst`` with a copy of its first variant as ``variant_id``."""

    def change(data: bytes) -> bytes:
        root = ET.fromstring(data)
        variants = root.find("ProductDefinitions/Variants")
        copy = ET.fromstring(ET.tostring(variants[0]))
        copy.set("id", variant_id)
        copy.find("Name/Locale").text = name
        variants.append(copy)
        buf = io.BytesIO()
        ET.ElementTree(root).write(buf, encoding="utf-8", xml_declaration=True)
        return buf.getvalue()

    with zipfile.ZipFile(src) as a, zipfile.ZipFile(dst, "w") as b:
        for info in a.infolist():
            data = a.read(info)
            b.writestr(info, change(data) if info.filename == "product.xml" else data)
    return dst
