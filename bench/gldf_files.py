"""Benchmark and check: the GLDF files of tests/data/gldf read as LightInv reads them.
Prints JSON.

    python bench/gldf_files.py [FILE.gldf ...]

For each file and variant: the rated flux (lm) and power (W) product.xml states, the
flux the variant's table integrates to, its warnings; for each emitter whose
``Photometry`` states a CIE flux code (N1-N3: downward flux within 41.4, 60, 75.5 deg,
% of the downward flux; N4: downward flux fraction, %; N5: light output ratio, %), the
code the maker's software wrote and the same five numbers integrated from LightInv's
table (the file's, before the GLDF's rating scales it). And the CPU time to read each
file's variants (product.xml, the zipped photometry, the tables), median of 5.
"""

from __future__ import annotations

import contextlib
import json
import statistics
import sys
import time
import zipfile
from pathlib import Path
from xml.etree import ElementTree as ET

from lightinv_core.errors import LightInvError
from lightinv_core.luminaires.formats import file_products
from lightinv_core.luminaires.gldf import read_gldf
from lightinv_core.luminaires.gldf_light import emitter_photometry, variant_photometry

DATA = Path(__file__).resolve().parents[1] / "tests" / "data" / "gldf"


def flux_code(ph) -> list[float]:
    """N1-N5 of a type C table (see the module)."""
    down, total = ph.flux(90.0), ph.flux()
    zonal = [100 * ph.flux(g) / down if down > 0 else 0.0 for g in (41.4, 60.0, 75.5)]
    lor = 100 * total / ph.lamp_lumens if ph.lamp_lumens else 100.0
    return [round(x, 2) for x in (*zonal, 100 * down / total, lor)]


def one(path: Path) -> dict:
    root = ET.fromstring(zipfile.ZipFile(path).read("product.xml"))
    codes = {
        p.get("id"): p.findtext("DescriptivePhotometry/CIE-FluxCode")
        for p in root.iter("Photometry")
    }
    phot_of = {}
    for e in root.iter("Emitter"):
        ref = e.find("*/PhotometryReference")
        if ref is not None:
            phot_of[e.get("id")] = ref.get("photometryId")
    try:
        product = read_gldf(path)
    except LightInvError as exc:
        return {"file": path.name, "error": str(exc)}
    variants = []
    for v in product.variants:
        row = {"variant": v.variant_id, "name": v.name, "rated_lm": v.lumens, "rated_W": v.watts}
        try:
            ph = variant_photometry(path, v.variant_id, product)
            row.update(table_lm=round(ph.flux(), 1), warnings=list(ph.warnings))
            emitters = []
            for e in v.emitters:
                stated = codes.get(phot_of.get(e.emitter_id))
                entry = {"emitter": e.emitter_id, "file": e.member, "stated_code": stated}
                entry["our_code"] = flux_code(emitter_photometry(path, e))
                emitters.append(entry)
            row["emitters"] = emitters
        except LightInvError as exc:
            row["error"] = str(exc)
        variants.append(row)
    times = []
    for _ in range(5):
        t = time.process_time()
        with contextlib.suppress(LightInvError):
            file_products(path)
        times.append(time.process_time() - t)
    return {
        "file": path.name,
        "bytes": path.stat().st_size,
        "manufacturer": product.manufacturer,
        "format_version": product.format_version,
        "variants": variants,
        "read_cpu_ms": round(1000 * statistics.median(times), 1),
    }


def main(argv: list[str]) -> None:
    files = [Path(a) for a in argv] or sorted(DATA.glob("*.gldf"))
    print(json.dumps({"files": [one(f) for f in files]}, indent=1, ensure_ascii=False))


if __name__ == "__main__":
    main(sys.argv[1:])
