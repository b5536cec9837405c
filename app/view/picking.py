"""Picking in the viewport: the scene's triangles seen in a display rectangle (VTK's
hardware selector, so hidden ones are left out), and the camera ray through a display
point. Display coordinates are VTK's: pixels, origin bottom-left."""

from __future__ import annotations

import numpy as np
import vtk


def scene_cells_in(plotter, x0: int, y0: int, x1: int, y1: int) -> np.ndarray:
    """Ids of the cells of the plotter's "scene" actor visible in a display rectangle
    (the viewport maps them to patches)."""
    # A drag may end outside the view (negative or beyond its size): the selector
    # takes unsigned pixel coordinates inside the window, so clip to it.
    w, h = plotter.render_window.GetSize()
    xs = sorted(min(max(int(x), 0), max(w - 1, 0)) for x in (x0, x1))
    ys = sorted(min(max(int(y), 0), max(h - 1, 0)) for y in (y0, y1))
    sel = vtk.vtkHardwareSelector()
    sel.SetRenderer(plotter.renderer)
    sel.SetFieldAssociation(vtk.vtkDataObject.FIELD_ASSOCIATION_CELLS)
    sel.SetArea(xs[0], ys[0], xs[1], ys[1])
    result = sel.Select()
    scene_actor = plotter.actors.get("scene")
    ids = []
    for i in range(result.GetNumberOfNodes()):
        node = result.GetNode(i)
        prop = node.GetProperties().Get(vtk.vtkSelectionNode.PROP())
        if prop is scene_actor and node.GetSelectionList() is not None:
            arr = node.GetSelectionList()
            ids.append(np.array([arr.GetValue(j) for j in range(arr.GetNumberOfTuples())]))
    return np.concatenate(ids).astype(np.int64) if ids else np.zeros(0, np.int64)


def camera_ray(renderer, x: int, y: int) -> tuple[np.ndarray, np.ndarray]:
    """World points on the camera ray through a display point (near, far)."""
    out = []
    for z in (0.0, 1.0):
        renderer.SetDisplayPoint(x, y, z)
        renderer.DisplayToWorld()
        w = np.array(renderer.GetWorldPoint())
        out.append(w[:3] / w[3])
    return out[0], out[1]


def plan_point(viewport, pos, z: float) -> np.ndarray | None:
    """(x, y) m where the ray under the cursor ``pos`` (a widget point) meets the plane at
    height ``z`` m; None when the ray runs parallel to it or the plane is behind the eye
    (dragging observers and sensor regions in plan)."""
    near, far = viewport.ray(*viewport.display(pos))
    dz = far[2] - near[2]
    if abs(dz) < 1e-12:
        return None
    t = (z - near[2]) / dz
    return None if t < 0 else (near + t * (far - near))[:2]
