"""IFC export of a design (lightinv_core/export/ifc_export.py): the file validates
with ifcopenshell's validator (schema and EXPRESS rules), and re-imported by LightInv's
IFC importer gives back every luminaire where it was and with its flux."""

from __future__ import annotations

import gzip
import hashlib
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("ifcopenshell")
import ifcopenshell
import ifcopenshell.util.element
import ifcopenshell.util.placement
import ifcopenshell.util.unit
import ifcopenshell.validate

from lightinv_core.design.model import Design, Goal, LuminaireArray, Source
from lightinv_core.design.solution import Solution
from lightinv_core.errors import LightInvError
from lightinv_core.export import export_design
from lightinv_core.export.ifc_export import write_ifc
from lightinv_core.light.arrays import zone_frame
from lightinv_core.project import OperatorSettings, OptimizerSettings, Project, SceneSpec
from lightinv_core.scene.edits import ZoneEdit
from lightinv_core.scene.importers.ifc import load_ifc
from lightinv_core.study import prepare
from tests.core.ifc_rooms import ifc_model
from tests.export.office import IES, exported

DATA = Path(__file__).resolve().parents[1] / "data" / "ifc"


def problems(path: Path, rules: bool = False) -> list:
    """What ifcopenshell's validator finds wrong: schema types, cardinalities and
    inverses; with ``rules`` also the EXPRESS WHERE and global rules (8 s here)."""
    log = ifcopenshell.validate.json_logger()
    ifcopenshell.validate.validate(str(path), log, express_rules=rules)
    return log.statements


def expected(ex) -> list[tuple[str, np.ndarray, float]]:
    """(name, position, lumens) of every luminaire of the design, as placed."""
    out = [(f.name, f.position, f.lumens) for f in ex.fixtures]
    return out + [(p.name, p.centre, p.lumens) for p in ex.panels if p.electric]


def check_round_trip(ex, fixtures: list[dict]) -> None:
    got = {f["name"]: f for f in fixtures}
    want = expected(ex)
    assert sorted(got) == sorted(n for n, _, _ in want)
    for name, pos, lumens in want:
        np.testing.assert_allclose(got[name]["position"], pos, atol=1e-6)
        assert got[name]["lumens"] == pytest.approx(lumens, rel=1e-9)


@pytest.fixture(scope="module")
def office_ifc(tmp_path_factory):
    ex = exported()
    path = tmp_path_factory.mktemp("ifc") / "office.ifc"
    return ex, write_ifc(ex, path)


def test_a_new_ifc_of_a_built_in_scene_validates_and_round_trips(office_ifc):
    """The office (a built-in scene): a new IFC4 file with the scene as proxies, three
    array luminaires of a real IES product and a Lambertian panel, a skylight and a
    work plane. No validator finding; LightInv's importer reads the room back (the
    skylight as a window zone) and every luminaire at its position with its flux."""
    ex, out = office_ifc
    assert out.counts == {"luminaires": 4, "glazing": 1, "workplanes": 1, "surfaces": 6}
    assert problems(out.path) == []
    scene = load_ifc(out.path, resolution=1.0)
    check_round_trip(ex, scene.info["ifc"]["light_fixtures"])
    assert "IfcWindow:S1" in {z.name for z in scene.zones}
    dimmed = next(f for f in scene.info["ifc"]["light_fixtures"] if f["name"] == "west.1")
    assert dimmed["watts"] == pytest.approx(20.0 * 0.8)
    np.testing.assert_allclose(dimmed["aim"], [0.0, 0.0, -1.0], atol=1e-9)


def test_the_file_carries_products_photometry_glazing_and_results(office_ifc):
    """One type per product with its wattage, the IES file referenced and the table as
    a goniometric source (cd/lm x rated flux = the file's candela); the skylight an
    opening filled by a window; the work plane's Em, U0 and the standard."""
    ex, out = office_ifc
    f = ifcopenshell.open(str(out.path))
    fx = ex.fixtures[0]
    t = next(t for t in f.by_type("IfcLightFixtureType") if t.Name == fx.product)
    assert ifcopenshell.util.element.get_psets(t)["Pset_LightFixtureTypeCommon"][
        "TotalWattage"
    ] == pytest.approx(20.0)
    doc = t.HasAssociations[0].RelatingDocument
    assert doc.Name == IES.name and doc.Location.endswith(IES.name)
    source = t.RepresentationMaps[0].MappedRepresentation.Items[0]
    assert source.is_a("IfcLightSourceGoniometric")
    assert source.LuminousFlux == pytest.approx(fx.rated_lumens)
    dist = source.LightDistributionDataSource
    cd = np.array([d.LuminousIntensity for d in dist.DistributionData]) * source.LuminousFlux
    np.testing.assert_allclose(cd, fx.photometry.candela, rtol=1e-12)
    np.testing.assert_allclose(
        np.degrees([d.MainPlaneAngle for d in dist.DistributionData]), fx.photometry.c_angles
    )
    window = f.by_type("IfcWindow")[0]
    opening = window.FillsVoids[0].RelatingOpeningElement
    assert opening.VoidsElements[0].RelatingBuildingElement.Name == "roof"
    glazing = ifcopenshell.util.element.get_psets(window)["LightInv_Glazing"]
    assert glazing["VisibleTransmittance"] == pytest.approx(0.5 * 0.6)
    plane = ifcopenshell.util.element.get_psets(f.by_type("IfcAnnotation")[0])
    wp = plane["LightInv_WorkPlane"]
    assert wp["Em"] == pytest.approx(ex.planes[0].em)
    assert wp["U0"] == pytest.approx(ex.planes[0].u0)
    assert wp["Standard"].startswith("EN 12464-1")
    # The edition is the work plane's own (a project without one reads as 2011).
    assert wp["Standard"] == str(ex.project.design.workplanes[0].edition)


@pytest.mark.slow  # the EXPRESS rules take 8 s
def test_the_new_file_meets_the_express_rules(office_ifc):
    """The schema's WHERE rules and global rules too (a light source in a 'LightSource'
    representation, the window's and opening's shapes, unique GlobalIds, ...)."""
    assert problems(office_ifc[1].path, rules=True) == []


def test_the_validator_finds_a_broken_file(office_ifc, tmp_path):
    """The validation above can fail: an opening without the element it voids (an
    inverse attribute IFC4 requires) is reported."""
    _, out = office_ifc
    f = ifcopenshell.open(str(out.path))
    f.remove(f.by_type("IfcRelVoidsElement")[0])
    f.write(str(tmp_path / "broken.ifc"))
    assert problems(tmp_path / "broken.ifc")


@pytest.fixture(scope="module")
def house(tmp_path_factory) -> Path:
    path = tmp_path_factory.mktemp("house") / "IfcOpenHouse_IFC4.ifc"
    path.write_bytes(gzip.decompress((DATA / "IfcOpenHouse_IFC4.ifc.gz").read_bytes()))
    return path


def test_an_imported_ifc_gets_the_design_in_a_copy(house, tmp_path):
    """IfcOpenHouse (a real IFC4 model): an array in a zone drawn under the south roof
    and one of its windows designed as glazing. The design goes into a copy (the
    original's bytes unchanged; every original entity kept), the opening voids the
    wall the window stood in, it validates, and re-imported the luminaires are back."""
    before = hashlib.sha256(house.read_bytes()).hexdigest()
    zone = ZoneEdit("lum_roof", "luminaire", "IfcSlab:South roof", (1.0, 0.5, 8.0, 2.5))
    scene = SceneSpec(obj=str(house), resolution=0.5, zones=(zone,))
    window = "IfcWindow:3lY7vAqg1AOuHmhrmPSRNL"
    empty = Design((), (Goal("min_electric_power"),))
    project = Project(
        "House", scene, empty, OperatorSettings(rank=40, rays=64), OptimizerSettings()
    )
    prepared = prepare(project)
    w, h = zone_frame(prepared.patches, window).size
    glass = Source("W1", window, "window", (0.0, 0.0, w, h), filter=0.9)
    arr = LuminaireArray("roof", "lum_roof", str(IES), (0.0, 0.0, 7.0, 2.0), rows=1, columns=3,
                         watts=20.0)  # fmt: skip
    design = Design((glass,), (Goal("min_electric_power"),), arrays=(arr,))
    project = replace(
        project, design=design, solutions=(Solution((glass,), {}, 0.0, arrays=(arr,)),)
    )
    ex = export_design(project, prepared)
    out = write_ifc(ex, tmp_path / "house-lit.ifc")
    assert hashlib.sha256(house.read_bytes()).hexdigest() == before
    assert out.counts["luminaires"] == 3 and out.counts["glazing"] == 1
    assert problems(out.path) == []
    old, new = ifcopenshell.open(str(house)), ifcopenshell.open(str(out.path))
    for cls in ("IfcWall", "IfcSlab", "IfcWindow", "IfcOpeningElement"):
        assert len(new.by_type(cls)) == len(old.by_type(cls)) + (
            cls in ("IfcWindow", "IfcOpeningElement")
        )
    added = next(w for w in new.by_type("IfcWindow") if w.Name == "W1")
    host = added.FillsVoids[0].RelatingOpeningElement.VoidsElements[0].RelatingBuildingElement
    assert host.is_a("IfcWall")
    check_round_trip(ex, load_ifc(out.path, resolution=0.5).info["ifc"]["light_fixtures"])
    with pytest.raises(LightInvError, match="never overwritten"):
        write_ifc(ex, house)


def schema_room(path: Path, schema: str = "IFC2X3") -> Path:
    """A 6 x 4 x 3 m room in ``schema`` (IFC2X3: Revit's default export) in millimetres:
    four walls, floor and roof slabs, a 1.5 x 1.2 m window in an opening of the south
    wall and a 2 x 4 m ceiling covering; with the user and application every IFC2X3
    file has (its entities need an owner history)."""
    m = ifc_model(schema, name="Old", owner=True)
    api, f, box = m.api, m.f, m.box

    t = 0.2
    box("IfcSlab", "Floor", -t, -t, -t, 6.4, 4.4, t, predefined="FLOOR")
    south = box("IfcWall", "South", -t, -t, 0, 6.4, t, 3.0)
    box("IfcWall", "North", -t, 4.0, 0, 6.4, t, 3.0)
    box("IfcWall", "West", -t, 0, 0, t, 4.0, 3.0)
    box("IfcWall", "East", 6.0, 0, 0, t, 4.0, 3.0)
    box("IfcSlab", "Roof", -t, -t, 3.0, 6.4, 4.4, t, predefined="ROOF")
    hole = box("IfcOpeningElement", "W1 opening", 1.0, -0.3, 0.9, 1.5, 0.4, 1.2, contained=False)
    api.feature.add_feature(f, feature=hole, element=south)
    window = box("IfcWindow", "W1", 1.0, -0.1, 0.9, 1.5, 0.05, 1.2)
    api.feature.add_filling(f, opening=hole, element=window)
    box("IfcCovering", "Panel", 4.0, 0, 2.7, 2.0, 4.0, 0.02, predefined="CEILING")
    if schema == "IFC2X3":  # add_filling leaves its relation without the owner history
        history = f.by_type("IfcOwnerHistory")[0]
        for e in f.by_type("IfcRoot"):
            e.OwnerHistory = e.OwnerHistory or history
    f.write(str(path))
    return path


def test_an_ifc2x3_model_gets_the_design_in_a_copy(tmp_path):
    """An IFC2X3 model (Revit's default export): the luminaires go in as
    ``IfcFlowTerminal`` occurrences typed by an ``IfcLightFixtureType`` (IFC2X3 has no
    ``IfcLightFixture``), the window without a PredefinedType, the photometry's
    document reference in the IFC2X3 form; the copy validates, the original's bytes
    are unchanged and re-read, every luminaire is where it was with its flux."""
    old = schema_room(tmp_path / "old.ifc")
    assert problems(old) == []  # the model itself is valid
    before = hashlib.sha256(old.read_bytes()).hexdigest()
    empty = Design((), (Goal("min_electric_power"),))
    project = Project(
        "Old", SceneSpec(obj=str(old), resolution=0.5), empty,
        OperatorSettings(rank=40, rays=64), OptimizerSettings(),
    )  # fmt: skip
    prepared = prepare(project)  # LightInv reads the IFC2X3 model itself
    w, h = zone_frame(prepared.patches, "IfcWindow:W1").size
    glass = Source("G1", "IfcWindow:W1", "window", (0.0, 0.0, w, h), filter=0.9)
    arr = LuminaireArray("ceiling", "IfcCovering:Panel", str(IES), (0.2, 0.2, 1.8, 3.8),
                         rows=2, columns=2, watts=20.0)  # fmt: skip
    design = Design((glass,), (Goal("min_electric_power"),), arrays=(arr,))
    project = replace(
        project, design=design, solutions=(Solution((glass,), {}, 0.0, arrays=(arr,)),)
    )
    ex = export_design(project, prepared)
    out = write_ifc(ex, tmp_path / "old-lit.ifc")
    assert hashlib.sha256(old.read_bytes()).hexdigest() == before
    assert out.counts["luminaires"] == 4 and out.counts["glazing"] == 1
    assert problems(out.path, rules=True) == []  # the EXPRESS rules too (under 1 s here)
    f = ifcopenshell.open(str(out.path))
    assert f.schema == "IFC2X3"
    terminals = f.by_type("IfcFlowTerminal")
    assert len(terminals) == 4
    t = ifcopenshell.util.element.get_type(terminals[0])
    assert t.is_a("IfcLightFixtureType") and t.PredefinedType == "DIRECTIONSOURCE"
    doc = t.HasAssociations[0].RelatingDocument
    assert doc.Name == IES.name and doc.Location.endswith(IES.name)
    source = t.RepresentationMaps[0].MappedRepresentation.Items[0]
    assert source.LuminousFlux == pytest.approx(ex.fixtures[0].rated_lumens)
    added = next(w for w in f.by_type("IfcWindow") if w.Name == "G1")
    host = added.FillsVoids[0].RelatingOpeningElement.VoidsElements[0].RelatingBuildingElement
    assert host.Name == "South"
    assert all(e.OwnerHistory is not None for e in f.by_type("IfcRoot"))
    # Re-imported by LightInv: positions (the file's mm) and fluxes as designed.
    check_round_trip(ex, load_ifc(out.path, resolution=0.5).info["ifc"]["light_fixtures"])


def test_lightinv_reads_an_ifc2x3_model(tmp_path):
    """LightInv's importer reads an IFC2X3 model: its window a zone, no light fixtures
    (IFC2X3 has no ``IfcLightFixture`` to ask for: ``ifc_fixtures`` reads flow
    terminals typed as light fixtures instead)."""
    scene = load_ifc(schema_room(tmp_path / "old.ifc"), resolution=0.5)
    assert "IfcWindow:W1" in {z.name for z in scene.zones}
    assert scene.info["ifc"]["light_fixtures"] == []


def test_an_ifc4x3_model_is_refused_with_what_to_do(tmp_path):
    """A schema the export does not write (IFC4X3): one line says so and what to do;
    nothing is written."""
    old = tmp_path / "old.ifc"
    ifcopenshell.file(schema="IFC4X3").write(str(old))
    ex = exported()
    ex.project = replace(ex.project, scene=replace(ex.project.scene, builtin=None, obj=str(old)))
    with pytest.raises(LightInvError, match=r"old\.ifc is IFC4X3: the design can be added to IFC4"):
        write_ifc(ex, tmp_path / "new.ifc")
    assert not (tmp_path / "new.ifc").exists()
