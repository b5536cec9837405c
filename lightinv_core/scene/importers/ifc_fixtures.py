"""The light fixtures of an IFC model, read beside its surfaces: where each one is,
where it points, its flux and power, for ``scene.info["ifc"]``. IFC4 has
``IfcLightFixture`` occurrences; IFC2X3 has none (a light is an ``IfcFlowTerminal``
typed by an ``IfcLightFixtureType``).

A fixture's position is the origin of its placement and its aim the placement's
local -z (as ``export.ifc_export`` writes them, and as a downlight hangs in most
authoring tools); its flux is LightInv's own ``LightInv_Luminaire.LuminousFlux`` when
the file has it (a design exported by LightInv), else the rated flux of the
``IfcLightSourceGoniometric`` of its type, else unknown (None); its power
``LightInv_Luminaire.ElectricPower``, else its type's
``Pset_LightFixtureTypeCommon.TotalWattage``.
"""

from __future__ import annotations

import numpy as np

from lightinv_core.scene.importers.geometry import z_up


def _goniometric_flux(t) -> float | None:
    """The rated flux (lm) of the first goniometric light source of type ``t``."""
    for m in getattr(t, "RepresentationMaps", None) or ():
        for item in m.MappedRepresentation.Items or ():
            if item.is_a("IfcLightSourceGoniometric"):
                return float(item.LuminousFlux)
    return None


def _fixtures(model) -> list:
    """The model's light fixture occurrences, in either schema."""
    import ifcopenshell.util.element

    if model.schema != "IFC2X3":
        return list(model.by_type("IfcLightFixture"))
    return [
        e
        for e in model.by_type("IfcFlowTerminal")
        if (t := ifcopenshell.util.element.get_type(e)) is not None
        and t.is_a("IfcLightFixtureType")
    ]


def light_fixtures(model, scale: float = 1.0, up: str = "z") -> list[dict]:
    """Every ``IfcLightFixture`` of the opened ``model`` (ifcopenshell) as a dict: name,
    class, position (m, the scene's axes: the file's unit, times ``scale``, turned by
    ``up`` as the surfaces are), aim (unit vector), lumens and watts (None when the
    file gives none), type (its type's name or "")."""
    import ifcopenshell.util.element
    import ifcopenshell.util.placement
    import ifcopenshell.util.unit

    unit = ifcopenshell.util.unit.calculate_unit_scale(model)
    out = []
    for e in _fixtures(model):
        if e.ObjectPlacement is None:
            continue
        m = ifcopenshell.util.placement.get_local_placement(e.ObjectPlacement)
        pos = z_up(m[None, :3, 3] * unit * scale, up)[0]
        aim = z_up(-m[None, :3, 2], up)[0]
        psets = ifcopenshell.util.element.get_psets(e)  # the type's inherited
        own = psets.get("LightInv_Luminaire", {})
        t = ifcopenshell.util.element.get_type(e)
        lumens = own.get("LuminousFlux")
        if lumens is None and t is not None:
            lumens = _goniometric_flux(t)
        watts = own.get("ElectricPower")
        if watts is None:
            watts = psets.get("Pset_LightFixtureTypeCommon", {}).get("TotalWattage")
        out.append(
            {
                "name": e.Name or e.GlobalId,
                "position": [float(c) for c in pos],
                "aim": [float(c) for c in aim / max(np.linalg.norm(aim), 1e-12)],
                "lumens": None if lumens is None else float(lumens),
                "watts": None if watts is None else float(watts),
                "type": (t.Name or "") if t is not None else "",
            }
        )
    return out
