"""The IFC file an export writes into (``ifc_export``): a copy of the project's IFC
model or a new IFC4 file with its project, units, site, building and storey; its
'Body' and 'Lighting' contexts; and scene points and directions in the file's world
coordinates and length unit (the inverse of the importer's: its ``scale`` and up
axis); what differs between the schemas a model may be in (``SCHEMAS``: IFC4 and
IFC2X3). ifcopenshell (the ``ifc`` extra) is imported only when a file is written.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from lightinv_core.errors import LightInvError
from lightinv_core.export.design import ExportDesign

MISSING = "IFC export needs the optional extra: pip install 'lightinv[ifc]'"


def libraries():
    """ifcopenshell and its api modules, or LightInvError naming the extra."""
    try:
        import ifcopenshell
        import ifcopenshell.api.aggregate
        import ifcopenshell.api.context
        import ifcopenshell.api.owner
        import ifcopenshell.api.pset
        import ifcopenshell.api.root
        import ifcopenshell.api.spatial
        import ifcopenshell.api.type
        import ifcopenshell.api.unit
        import ifcopenshell.guid
        import ifcopenshell.util.unit
    except ImportError:
        raise LightInvError(MISSING) from None
    return ifcopenshell


def _document_ifc4(f, location: str, name: str, description: str):
    # IfcDocumentReference(Location, Identification, Name, Description, ReferencedDocument)
    return f.createIfcDocumentReference(location, None, name, description, None)


def _document_ifc2x3(f, location: str, name: str, description: str):
    # IFC2X3: IfcDocumentReference(Location, ItemReference, Name), no description
    return f.createIfcDocumentReference(location, None, name)


@dataclass(frozen=True)
class Schema:
    """What the export writes differently in one IFC schema."""

    fixture: str  # the luminaire occurrence's class (typed by an IfcLightFixtureType)
    predefined: bool  # IfcWindow and IfcOpeningElement have a PredefinedType
    owner_history: bool  # every rooted entity needs an IfcOwnerHistory
    document: object  # (file, location, name, description) -> IfcDocumentReference


SCHEMAS = {
    "IFC4": Schema("IfcLightFixture", True, False, _document_ifc4),
    # IFC2X3 has no IfcLightFixture occurrence: a flow terminal typed as a light fixture.
    "IFC2X3": Schema("IfcFlowTerminal", False, True, _document_ifc2x3),
}


class IfcWriter:
    """One IFC file being written: its contexts, container and unit conversion."""

    def __init__(self, ifc, ex: ExportDesign, model_path: Path | None):
        self.ifc, self.ex = ifc, ex
        api = ifc.api
        if model_path is not None:
            self.f = ifc.open(str(model_path))
            if self.f.schema not in SCHEMAS:
                raise LightInvError(
                    f"{model_path.name} is {self.f.schema}: the design can be added to IFC4 "
                    "or IFC2X3 models only; export the model from its authoring tool as IFC4"
                )
            self.unit = ifc.util.unit.calculate_unit_scale(self.f)  # m per file unit
            self.angle = ifc.util.unit.calculate_unit_scale(self.f, "PLANEANGLEUNIT")
            spec = ex.project.scene
            self.scale, self.up = float(spec.scale or 1.0), spec.up or "z"
            self.container = next(
                iter(self.f.by_type("IfcBuildingStorey") or self.f.by_type("IfcBuilding")), None
            )
            contexts = self.f.by_type("IfcGeometricRepresentationContext")
            sub = "IfcGeometricRepresentationSubContext"
            model = next(
                (c for c in contexts if c.ContextType == "Model" and not c.is_a(sub)), None
            )
            if model is None:
                model = api.context.add_context(self.f, context_type="Model")
        else:
            self.f = ifc.file(schema="IFC4")
            self.unit, self.angle, self.scale, self.up = 1.0, 1.0, 1.0, "z"
            project = api.root.create_entity(self.f, "IfcProject", name=ex.name)
            api.unit.assign_unit(self.f, length={"is_metric": True, "raw": "METERS"})
            model = api.context.add_context(self.f, context_type="Model")
            site = api.root.create_entity(self.f, "IfcSite", name="Site")
            building = api.root.create_entity(self.f, "IfcBuilding", name=ex.name)
            storey = api.root.create_entity(self.f, "IfcBuildingStorey", name="LightInv scene")
            api.aggregate.assign_object(self.f, [site], project)
            api.aggregate.assign_object(self.f, [building], site)
            api.aggregate.assign_object(self.f, [storey], building)
            for p in (site, building, storey):
                p.ObjectPlacement = self.placement()
            self.container = storey
        self.body = api.context.add_context(
            self.f, context_type="Model", context_identifier="Body", target_view="MODEL_VIEW",
            parent=model,
        )  # fmt: skip
        self.lighting = api.context.add_context(
            self.f, context_type="Model", context_identifier="Lighting", target_view="MODEL_VIEW",
            parent=model,
        )  # fmt: skip
        self.schema = SCHEMAS[self.f.schema]
        self.history = None
        if self.schema.owner_history:
            self.history = self._owner_history()
        self.placed: list = []

    def _owner_history(self):
        """An ``IfcOwnerHistory`` for what the export adds: the model's own user and
        application (every IFC2X3 model has them), else LightInv as both."""
        api, f = self.ifc.api, self.f
        if not f.by_type("IfcApplication") or not f.by_type("IfcPersonAndOrganization"):
            org = api.owner.add_organisation(f, identification="LightInv", name="LightInv")
            if not f.by_type("IfcApplication"):
                api.owner.add_application(
                    f, application_developer=org, version="1", application_full_name="LightInv",
                    application_identifier="LightInv",
                )  # fmt: skip
            if not f.by_type("IfcPersonAndOrganization"):
                person = api.owner.add_person(f, identification="LightInv", family_name="LightInv")
                api.owner.add_person_and_organisation(f, person=person, organisation=org)
        return api.owner.create_owner_history(f)

    def relation(self, cls: str, *attrs):
        """A relationship entity ``cls`` with a new GlobalId, the owner history the
        schema needs and ``attrs`` after them (Name, Description, ...)."""
        return self.f.create_entity(cls, self.ifc.guid.new(), self.history, *attrs)

    def predefined(self, value: str) -> dict:
        """``{"PredefinedType": value}`` where windows and openings have one, else {}."""
        return {"PredefinedType": value} if self.schema.predefined else {}

    def document(self, location: str, name: str, description: str):
        """An ``IfcDocumentReference`` to ``location`` (a URI) in the schema's form."""
        return self.schema.document(self.f, location, name, description)

    def point(self, p) -> list[float]:
        """A scene point (m) in the file's world coordinates and length unit."""
        x, y, z = (float(c) / self.scale for c in p)
        if self.up == "y":  # the importer turned (x, y, z) into (x, -z, y)
            x, y, z = x, z, -y
        return [x / self.unit, y / self.unit, z / self.unit]

    def direction(self, d) -> list[float]:
        x, y, z = (float(c) for c in d)
        return [x, z, -y] if self.up == "y" else [x, y, z]

    def placement(self, origin=None, z=None, x=None):
        """An absolute ``IfcLocalPlacement`` at scene point ``origin`` with local axes
        ``z`` and ``x`` (scene directions); the identity without ``origin``."""
        f = self.f
        if origin is None:
            return f.createIfcLocalPlacement(None, self.axes([0.0, 0.0, 0.0], None, None))
        return f.createIfcLocalPlacement(None, self.axes(self.point(origin), z, x))

    def axes(self, loc, z, x):
        f = self.f
        if z is None:
            return f.createIfcAxis2Placement3D(f.createIfcCartesianPoint(loc), None, None)
        zz = np.asarray(self.direction(z), float)
        xx = np.asarray(self.direction(x), float)
        xx = xx - (xx @ zz) * zz
        return f.createIfcAxis2Placement3D(
            f.createIfcCartesianPoint([float(c) for c in loc]),
            f.createIfcDirection([float(c) for c in zz / np.linalg.norm(zz)]),
            f.createIfcDirection([float(c) for c in xx / np.linalg.norm(xx)]),
        )

    def entity(self, cls: str, name: str, **attrs):
        e = self.ifc.api.root.create_entity(self.f, cls, name=name)
        for k, v in attrs.items():
            setattr(e, k, v)
        self.placed.append(e)
        return e

    def pset(self, product, name: str, values: dict) -> None:
        api = self.ifc.api
        pset = api.pset.add_pset(self.f, product=product, name=name)
        api.pset.edit_pset(self.f, pset=pset, properties=values)

    def shape(self, context, kind: str, rep_type: str, items):
        return self.f.createIfcProductDefinitionShape(
            None, None, [self.f.createIfcShapeRepresentation(context, kind, rep_type, items)]
        )
