"""IFC models built with ``ifcopenshell.api`` for the tests: the spatial tree (project,
site, building, one storey) and box-shaped elements placed in it."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np


@dataclass
class IfcModel:
    """An open model ``f``, the api module, its storey and ``box(cls, name, x, y, z, lx,
    ly, lz, predefined=None, contained=True)``: an element from (x, y, z), lx x ly x lz
    metres along the axes (a wall representation), in the storey unless not contained."""

    f: object
    api: object
    storey: object
    box: Callable


def ifc_model(
    schema: str = "IFC4", name: str = "Test", metres: bool = False, owner: bool = False
) -> IfcModel:
    """A new model in millimetres (the library's default) or ``metres``; ``owner``
    gives it the user and application an IFC2X3 file's entities need."""
    import ifcopenshell.api
    import ifcopenshell.api.aggregate
    import ifcopenshell.api.context
    import ifcopenshell.api.feature
    import ifcopenshell.api.geometry
    import ifcopenshell.api.owner
    import ifcopenshell.api.project
    import ifcopenshell.api.root
    import ifcopenshell.api.spatial
    import ifcopenshell.api.unit

    api = ifcopenshell.api
    f = api.project.create_file(version=schema)
    if owner:
        org = api.owner.add_organisation(f, identification="T", name="Test")
        person = api.owner.add_person(f, identification="T", family_name="Test")
        api.owner.add_person_and_organisation(f, person=person, organisation=org)
        api.owner.add_application(f, application_developer=org)
    project = api.root.create_entity(f, ifc_class="IfcProject", name=name)
    if metres:
        api.unit.assign_unit(f, length={"is_metric": True, "raw": "METERS"})
    else:
        api.unit.assign_unit(f)  # millimetres
    model = api.context.add_context(f, context_type="Model")
    body = api.context.add_context(
        f, context_type="Model", context_identifier="Body", target_view="MODEL_VIEW", parent=model
    )
    site = api.root.create_entity(f, ifc_class="IfcSite", name="Site")
    building = api.root.create_entity(f, ifc_class="IfcBuilding", name="Building")
    storey = api.root.create_entity(f, ifc_class="IfcBuildingStorey", name="Ground")
    api.aggregate.assign_object(f, relating_object=project, products=[site])
    api.aggregate.assign_object(f, relating_object=site, products=[building])
    api.aggregate.assign_object(f, relating_object=building, products=[storey])

    def box(cls, name, x, y, z, lx, ly, lz, predefined=None, contained=True):
        e = api.root.create_entity(f, ifc_class=cls, name=name, predefined_type=predefined)
        rep = api.geometry.add_wall_representation(
            f, context=body, length=lx, height=lz, thickness=ly
        )
        api.geometry.assign_representation(f, product=e, representation=rep)
        m = np.eye(4)
        m[:3, 3] = (x, y, z)
        api.geometry.edit_object_placement(f, product=e, matrix=m)
        if contained:
            api.spatial.assign_container(f, relating_structure=storey, products=[e])
        return e

    return IfcModel(f, api, storey, box)
