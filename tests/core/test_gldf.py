"""GLDF import (docs/photometry.md, "GLDF") on real files from the format's own example
repositories (tests/data/gldf/SOURCES.md): products, variants, rated flux and power as
product.xml states them (read here with a plain XML parse), the photometry equal to the
same EULUMDAT file read directly, and clear errors for broken files."""

from __future__ import annotations

import json
import zipfile
from pathlib import Path
from xml.etree import ElementTree as ET

import numpy as np
import pytest

from lightinv_core.cli import main as cli_main
from lightinv_core.errors import PhotometryError
from lightinv_core.light.arrays import resolve_product
from lightinv_core.luminaires import read_photometry
from lightinv_core.luminaires.catalogue import file_entries
from lightinv_core.luminaires.formats import file_filter, is_photometry_reference
from lightinv_core.luminaires.gldf import read_gldf
from lightinv_core.luminaires.gldf_light import emitter_photometry
from lightinv_core.luminaires.ldt import parse_ldt
from tests.core.gldf_variants import with_second_variant

DATA = Path(__file__).resolve().parents[1] / "data" / "gldf"
ZUMTOBEL = DATA / "zumtobel-p-evo-r100l.gldf"
TRILUX = DATA / "trilux-belviso-s-cdp.gldf"
PHILIPS = DATA / "philips-sp542p-minimal-ldc.gldf"
GLDF_IO = DATA / "gldf-io-example.gldf"
COMPLETE = DATA / "gldf-net-files-complete.gldf"


def _xml(path: Path) -> ET.Element:
    with zipfile.ZipFile(path) as z:
        return ET.fromstring(z.read("product.xml"))


def _ldt(path: Path, name: str):
    with zipfile.ZipFile(path) as z:
        return parse_ldt(z.read(f"ldc/{name}"), name)


def _stated(path: Path) -> dict[str, tuple[float, float, str]]:
    """Per emitter id: (RatedLuminousFlux, the fixed light source's RatedInputPower, the
    photometry file's name), straight from product.xml."""
    root = _xml(path)
    defs = root.find("GeneralDefinitions")
    files = {f.get("id"): f.text for f in defs.iter("File")}
    phots = {
        p.get("id"): files[p.find("PhotometryFileReference").get("fileId")]
        for p in defs.iter("Photometry")
    }
    power = {
        s.get("id"): float(s.findtext("RatedInputPower")) for s in defs.iter("FixedLightSource")
    }
    out = {}
    for e in defs.iter("Emitter"):
        light = e.find("FixedLightEmitter")
        out[e.get("id")] = (
            float(light.findtext("RatedLuminousFlux")),
            power[light.find("LightSourceReference").get("fixedLightSourceId")],
            phots[light.find("PhotometryReference").get("photometryId")],
        )
    return out


@pytest.mark.parametrize("path", [ZUMTOBEL, PHILIPS, TRILUX])
def test_variants_names_flux_and_power_as_product_xml_states_them(path):
    root = _xml(path)
    product = read_gldf(path)
    variants = root.findall("ProductDefinitions/Variants/Variant")
    assert [v.variant_id for v in product.variants] == [v.get("id") for v in variants]
    assert product.manufacturer == root.findtext("Header/Manufacturer")
    name = root.findtext("ProductDefinitions/ProductMetaData/Name/Locale")
    assert product.name == name
    stated = _stated(path)
    for v, xml in zip(product.variants, variants, strict=True):
        ids = [e.get("emitterId") for e in xml.iter() if e.get("emitterId")]
        assert [e.emitter_id for e in v.emitters] == ids
        assert v.lumens == sum(stated[i][0] for i in ids)
        assert v.watts == sum(stated[i][1] for i in ids)
        assert v.name.startswith(name)


def test_one_emitter_photometry_is_the_ldt_itself():
    # Zumtobel: GLDF and LDT agree on 2,400 lm, so the table is the file's, exactly.
    stated = _stated(ZUMTOBEL)["Emitter01"]
    direct = _ldt(ZUMTOBEL, stated[2])
    ph = read_photometry(f"{ZUMTOBEL}#variant1")
    assert np.array_equal(ph.c_angles, direct.c_angles)
    assert np.array_equal(ph.gamma_angles, direct.gamma_angles)
    assert np.array_equal(ph.candela, direct.candela)
    assert ph.lamp_lumens == direct.lamp_lumens == stated[0] == 2400.0
    # GLDF over photometry: the GLDF's 18 W, not the file's 19 W.
    assert direct.input_watts == 19.0 and ph.input_watts == stated[1] == 18.0
    assert ph.manufacturer == "Zumtobel" and ph.catalogue_number == "60819021"
    assert ph.warnings == ()
    # The file alone is its only variant.
    assert np.array_equal(read_photometry(ZUMTOBEL).candela, direct.candela)


def test_two_emitters_on_together_are_summed_each_at_its_gldf_rating():
    """Trilux Belviso: a direct and an indirect part. Each LDT is scaled from its lamp
    flux to the GLDF's rated flux (GLDF over photometry) and the two are added."""
    stated = _stated(TRILUX)
    ph = read_photometry(f"{TRILUX}#variant1")
    expected = 0.0
    for emitter in ("LightEmitterMain", "LightEmitterIndirect"):
        rated, _, name = stated[emitter]
        direct = _ldt(TRILUX, name)
        # Each on the sum's grid by its own interpolation (the sum's grid holds its own).
        cc, gg = np.meshgrid(ph.c_angles, ph.gamma_angles, indexing="ij")
        expected = expected + direct.intensity(cc, gg) * (rated / direct.lamp_lumens)
        assert np.isin(direct.gamma_angles, ph.gamma_angles).all()
    np.testing.assert_allclose(ph.candela, expected, rtol=1e-12)
    # Flux: each file's integral (its light output ratio) times its rating.
    main, indirect = (
        _ldt(TRILUX, stated[k][2]) for k in ("LightEmitterMain", "LightEmitterIndirect")
    )
    want = main.flux() * 7800 / 1600 + indirect.flux() * 1600 / 7800
    assert ph.flux() == pytest.approx(want, rel=1e-5)
    assert len(ph.warnings) == 2 and "scaled by 4.875" in ph.warnings[0]
    assert ph.input_watts == 36.0  # 18 W per emitter, as product.xml says (not 99 W)


@pytest.mark.parametrize("path", [TRILUX, GLDF_IO])
def test_each_emitters_table_gives_the_cie_flux_code_the_maker_states(path):
    """An independent check of the tables read through the GLDF: the CIE flux code
    (N1-N3: downward flux within 41.4, 60, 75.5 deg of the nadir, % of the downward
    flux; N4 the downward flux fraction; N5 the light output ratio) the maker's software
    wrote into product.xml, against the same numbers integrated from our table."""
    root = _xml(path)
    codes = {
        p.get("id"): p.findtext("DescriptivePhotometry/CIE-FluxCode")
        for p in root.iter("Photometry")
    }
    photometry_of = {
        e.get("id"): e.find("*/PhotometryReference").get("photometryId")
        for e in root.iter("Emitter")
    }
    checked = 0
    for v in read_gldf(path).variants:
        for e in v.emitters:
            stated = [float(x) for x in codes[photometry_of[e.emitter_id]].split()]
            ph = emitter_photometry(path, e)
            down, total = ph.flux(90.0), ph.flux()
            zonal = [100 * ph.flux(g) / down if down > 0 else 0.0 for g in (41.4, 60.0, 75.5)]
            lor = 100 * total / ph.lamp_lumens if ph.lamp_lumens else 100.0
            ours = [*zonal, 100 * down / total, lor]
            assert np.abs(np.array(ours) - stated).max() <= 0.6, (e.emitter_id, ours, stated)
            checked += 1
    assert checked == len(codes)


def test_light_source_colour_and_maintenance():
    v = read_gldf(GLDF_IO).variants[0]
    root = _xml(GLDF_IO)
    source = root.find("GeneralDefinitions/LightSources/FixedLightSource")
    assert v.cct_k == float(source.findtext("ColorInformation/CorrelatedColorTemperature"))
    assert v.cri_ra == float(source.findtext("ColorInformation/ColorRenderingIndex"))
    led = source.find("LightSourceMaintenance/LedMaintenanceFactor")
    assert v.maintenance.lamp == ((float(led.get("hours")), float(led.text), 1.0),)
    assert v.maintenance.lifetime_h == float(source.find("LightSourceMaintenance").get("lifetime"))
    # CIE lamp factors (LLMF, LSF by burning time) of a changeable lamp in an equipment.
    c = read_gldf(COMPLETE).variants[0]
    assert c.maintenance.lamp == ((125.0, 0.9, 0.91), (150.0, 0.8, 0.82))
    assert (c.lumens, c.watts) == (800.0, 110.0)  # the lamp's flux, the equipment's power
    assert "alternative modes" in c.notes[0]


def test_catalogue_entries_one_per_variant_named_product_and_variant():
    entries = file_entries(TRILUX)
    assert [e.name for e in entries] == ["Belviso S CDP LED9400nw ETD 03"]
    assert entries[0].reference == f"{TRILUX}#variant1"
    philips = file_entries(PHILIPS)
    assert [e.name for e in philips] == ["Pendelleuchten SP542P LED66S/940 Variant 1"]
    assert philips[0].watts == 47.5
    product = resolve_product(philips[0].reference)
    assert product.watts == 47.5 and product.lumens == pytest.approx(6600, rel=0.01)
    assert is_photometry_reference(f"{PHILIPS}#variant1") and "*.gldf" in file_filter()


def _rezip(path: Path, tmp: Path, change) -> Path:
    out = tmp / path.name
    with zipfile.ZipFile(path) as src, zipfile.ZipFile(out, "w") as dst:
        for info in src.infolist():
            data = change(info.filename, src.read(info))
            if data is not None:
                dst.writestr(info, data)
    return out


def test_clear_errors(tmp_path):
    broken = tmp_path / "broken.gldf"
    broken.write_bytes(ZUMTOBEL.read_bytes()[:5000])  # a download cut short
    with pytest.raises(PhotometryError, match=r"broken\.gldf: not a GLDF file \(not a zip"):
        read_gldf(broken)
    missing = _rezip(ZUMTOBEL, tmp_path, lambda n, d: None if n.endswith(".LDT") else d)
    with pytest.raises(PhotometryError, match=r"'60819021_\(STD_LEO\)\.LDT' named in product"):
        read_gldf(missing)
    ies_xml = _rezip(
        ZUMTOBEL,
        tmp_path,
        lambda n, d: d.replace(b"ldc/eulumdat", b"ldc/iesxml") if n == "product.xml" else d,
    )
    with pytest.raises(PhotometryError, match=r"of type 'ldc/iesxml'; LightInv reads EULUMDAT"):
        read_photometry(ies_xml)
    bad_ldt = _rezip(ZUMTOBEL, tmp_path, lambda n, d: d[:400] if n.endswith(".LDT") else d)
    with pytest.raises(PhotometryError, match=r"\.gldf:ldc/60819021_\(STD_LEO\)\.LDT:\d+: "):
        read_photometry(bad_ldt)  # the EULUMDAT reader's message, naming the file inside
    with pytest.raises(PhotometryError, match=r"emitter 'emitter-1' is rotated \(X 1 deg"):
        read_photometry(COMPLETE)
    with pytest.raises(PhotometryError, match=r"no variant 'nope'; it has: variant1"):
        read_photometry(f"{ZUMTOBEL}#nope")
    no_xml = tmp_path / "empty.gldf"
    with zipfile.ZipFile(no_xml, "w") as z:
        z.writestr("ldc/x.ldt", "x")
    with pytest.raises(PhotometryError, match=r"no product\.xml in the zip"):
        read_gldf(no_xml)


def test_cli_prints_each_variant(capsys, tmp_path):
    # A second variant added to the Zumtobel file: the CLI describes both.
    path = with_second_variant(ZUMTOBEL, tmp_path / "two.gldf")
    assert cli_main(["photometry", str(path)]) == 0
    text = capsys.readouterr().out
    assert "2 products" in text and text.count("flux 2,401 lm, 18 W") == 2
    assert "GLDF variant variant2: 2,400 lm, 18 W" in text
    assert cli_main(["photometry", f"{path}#variant2", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["name"] == "P-EVO R100L LED2500-830 BC AL WH [STD] wide"
    assert data["stated"]["rated_lumens"] == 2400.0 and data["watts"] == 18.0


def test_a_project_keeps_a_gldf_variant_relative_and_lights_with_it(tmp_path):
    """An array of a GLDF variant: saved relative to the project, read back absolute,
    and its luminaires placed with the variant's table and the GLDF's power."""
    import shutil

    from lightinv_core.design.model import Design, Goal, LuminaireArray, Workplane
    from lightinv_core.project import Project, SceneSpec, load_project, save_project

    folder = tmp_path / "luminaires"
    folder.mkdir()
    gldf = shutil.copy(ZUMTOBEL, folder / ZUMTOBEL.name)
    array = LuminaireArray("A1", "lum_west", f"{gldf}#variant1", (0.0, 0.0, 2.0, 6.0), 2, 1)
    design = Design(
        sources=(),
        goals=(Goal("min_electric_power"),),
        arrays=(array,),
        workplanes=(Workplane("wp"),),
    )
    path = tmp_path / "p.json"
    save_project(Project("gldf", SceneSpec(builtin="office", resolution=0.5), design), path)
    saved = json.loads(path.read_text())["arrays"][0]["product"]
    assert saved == f"luminaires/{ZUMTOBEL.name}#variant1"
    (back,) = load_project(path).design.arrays
    assert back.product == f"{gldf}#variant1"
    product = resolve_product(back.product)
    assert product.watts == 18.0 and product.name == "P-EVO R100L LED2500-830 BC AL WH [STD]"
    direct = _ldt(ZUMTOBEL, "60819021_(STD_LEO).LDT")
    assert np.array_equal(product.photometry.candela, direct.candela)


def test_a_registered_format_is_read_everywhere(tmp_path):
    """The registry, not the suffixes: a format added from here (gzipped EULUMDAT) is
    read by read_photometry, named by arrays, listed in the file chooser's filter."""
    import gzip

    from lightinv_core.luminaires.formats import (
        PhotometryFormat,
        register_format,
        unregister_format,
    )

    def read(path, variant):
        return parse_ldt(gzip.decompress(Path(path).read_bytes()), str(path))

    with zipfile.ZipFile(ZUMTOBEL) as z:
        ldt = z.read("ldc/60819021_(STD_LEO).LDT")
    packed = tmp_path / "p-evo.ldz"
    packed.write_bytes(gzip.compress(ldt))
    register_format(PhotometryFormat("EULUMDAT, gzipped", (".ldz",), read))
    try:
        assert "*.ldz" in file_filter() and is_photometry_reference(str(packed))
        product = resolve_product(str(packed))
        assert np.array_equal(product.photometry.candela, parse_ldt(ldt).candela)
        assert [e.name for e in file_entries(packed)] == [product.name]
    finally:
        unregister_format("EULUMDAT, gzipped")
    assert not is_photometry_reference(str(packed)) and "*.ldz" not in file_filter()


def test_the_ra_check_reads_a_gldf_variants_stated_ra():
    from lightinv_core.luminaires.rendering import product_ra

    # TRILUX's product.xml states <ColorRenderingIndex>80</...>; Zumtobel's states none.
    xml = ET.fromstring(zipfile.ZipFile(TRILUX).read("product.xml"))
    stated = [e.text for e in xml.iter() if e.tag.endswith("ColorRenderingIndex")]
    assert stated == ["80"]
    assert product_ra(f"{TRILUX}#variant1") == 80.0
    assert product_ra(str(TRILUX)) == 80.0
    assert product_ra(str(ZUMTOBEL)) is None
    assert product_ra(str(DATA / "missing.gldf")) is None
