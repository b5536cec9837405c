"""IFC windows without a body: glazing placed from the window's own data.

Some exporters write an ``IfcWindow`` with no geometry: only its placement and its
``OverallWidth`` and ``OverallHeight``, filling an opening cut in its wall. Such a
window becomes a thin pane (``PANE`` deep, centred on its placement's x-z plane: IFC
places a window's width along its local x, its height along z) that goes through the
import as a window with a body does, so its face towards the room becomes its glazing
zone. A window that fills no opening, or lacks a size, is skipped with the reason
(``skipped_windows``): nothing says where its glass is, and a pane floating in a wall
would be a wrong daylight zone.
"""

from __future__ import annotations

import numpy as np

from lightinv_core.scene.importers.ifc_geometry import Element

PANE = 0.05
"""Depth (m) of the pane a window without a body becomes."""
NO_OPENING = (
    "no geometry, and it fills no opening in a wall or roof: nothing places its glass "
    "(draw a window zone on the wall in the window instead)"
)
NO_SIZE = (
    "no geometry, and no OverallWidth and OverallHeight: its opening's size is not "
    "given (draw a window zone on the wall in the window instead)"
)
NO_PLACEMENT = (
    "no geometry, and no placement: nothing says where in its opening its glass is "
    "(draw a window zone on the wall in the window instead)"
)
CORNERS = np.array([(i, j, k) for i in (0, 1) for j in (0, 1) for k in (0, 1)], float)
QUADS = (  # the faces of the unit box, counter-clockwise seen from outside
    (0, 2, 6, 4),
    (1, 5, 7, 3),
    (0, 4, 5, 1),
    (2, 3, 7, 6),
    (0, 1, 3, 2),
    (4, 6, 7, 5),
)


def pane(matrix: np.ndarray, width: float, height: float) -> tuple[np.ndarray, np.ndarray]:
    """(vertices (8, 3), outward triangles (12, 3)) of a window's pane in world
    metres: ``width`` along the placement's x, ``height`` along its z, ``PANE`` deep
    about its x-z plane; ``matrix`` the placement (4 x 4, metres)."""
    local = CORNERS * (width, PANE, height) - (0.0, PANE / 2, 0.0)
    world = local @ matrix[:3, :3].T + matrix[:3, 3]
    tri = np.array([t for a, b, c, d in QUADS for t in ((a, b, c), (a, c, d))], np.int64)
    if np.linalg.det(matrix[:3, :3]) < 0:  # a mirrored placement turns the faces inside out
        tri = tri[:, ::-1]
    return world, tri


def fills_opening(window) -> bool:
    """Whether ``window`` fills an opening (IfcRelFillsElement)."""
    return any(
        getattr(fill, "RelatingOpeningElement", None) is not None
        for fill in getattr(window, "FillsVoids", ()) or ()
    )


def bodiless_windows(model, seen: set[int], label, in_roof) -> tuple[list[Element], dict]:
    """Windows of ``model`` that are no element yet (not in ``seen``: no body, no parts)
    and have no representation: an ``Element`` (a pane) for each that fills an opening
    and has a size, and id -> why for the others. ``label`` names an entity, ``in_roof``
    says whether a window sits in a roof."""
    import ifcopenshell.util.placement
    import ifcopenshell.util.unit

    scale = float(ifcopenshell.util.unit.calculate_unit_scale(model))
    out: list[Element] = []
    why: dict[int, str] = {}
    for window in model.by_type("IfcWindow"):
        if window.id() in seen or getattr(window, "Representation", None) is not None:
            continue
        width = getattr(window, "OverallWidth", None)
        height = getattr(window, "OverallHeight", None)
        if not fills_opening(window):
            why[window.id()] = NO_OPENING
            continue
        if not (width and height and width > 0 and height > 0):
            why[window.id()] = NO_SIZE
            continue
        if getattr(window, "ObjectPlacement", None) is None:
            why[window.id()] = NO_PLACEMENT
            continue
        m = np.array(ifcopenshell.util.placement.get_local_placement(window.ObjectPlacement))
        m[:3, 3] *= scale
        v, t = pane(m, width * scale, height * scale)
        out.append(
            Element(window.id(), "IfcWindow", label(window), v, t, roof_host=in_roof(window))
        )
    return out, why
