"""An EN 12464-1 preset's glare limit UGR_L as a UGR intention, and where its observers
sit when the design has none yet.

A preset (``en12464.py``) names UGR_L beside Em and U0: "Writing, typing, reading, data
processing" asks UGR at most 19. The work-plane intention bounds Em and U0 on the
plane's grid; UGR is judged at eyes (``design.model.Observer``), so the limit is a
second intention, on observers (``preset_glare_intention``).

**Default observers** (``default_observers``), when the design has none: the rule of
CIE 190's standard rooms, an eye at the middle of a wall looking across the room, once
along each of the plane's axes (crosswise and endwise views of the same luminaires):

- one at the middle of the plane's edge of least y, looking towards +y (azimuth 90 deg),
- one at the middle of its edge of least x, looking towards +x (azimuth 0 deg),

both seated (eye 1.2 m above the plane's floor group), on the plane's edge (its floor
group's extent in plan less the plane's border) and at least ``EDGE_INSET`` (0.5 m)
inside the floor's extent: a chair is not against the wall. The extent is a bounding
rectangle: on an L-shaped floor an eye may fall outside the room, which the Achieved tab
and the solve then say (move it).
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence

import numpy as np

from lightinv_core.design.en12464 import Requirement, plane_presets, requirement
from lightinv_core.design.model import SEATED_EYE, Design, Intention, Observer, Workplane
from lightinv_core.errors import DesignError, LightInvError
from lightinv_core.kinds import Quantity
from lightinv_core.scene.patches import Patches

EDGE_INSET = 0.5
"""m: a default observer sits at least this far inside its floor's extent."""
VIEWS = (("along y", 90.0), ("along x", 0.0))
"""The default observers: (name suffix, view azimuth in degrees)."""


def floor_extent(patches: Patches, group: str) -> tuple[np.ndarray, np.ndarray]:
    """(lo, hi): the plan rectangle (x, y m) of floor group ``group``'s patches."""
    try:
        idx = patches.group_index(group)
    except LightInvError:
        raise DesignError(
            f"no group {group!r} for the observers to stand on; groups: "
            f"{', '.join(patches.group_names)}"
        ) from None
    o, e1, e2 = patches.origin[idx], patches.edge1[idx], patches.edge2[idx]
    corners = np.concatenate([o, o + e1, o + e2, o + e1 + e2])[:, :2]
    return corners.min(axis=0), corners.max(axis=0)


def default_observers(
    patches: Patches, plane: Workplane, taken: Iterable[str] = ()
) -> tuple[Observer, ...]:
    """The two seated observers of the module's rule for work plane ``plane``, named
    "<plane> along y" and "<plane> along x" (a "-2" ... suffix when ``taken``)."""
    lo, hi = floor_extent(patches, plane.group)
    inset = max(float(plane.border), EDGE_INSET)
    inset = min(inset, 0.5 * float(np.min(hi - lo)))  # a narrow floor: its middle
    mid = 0.5 * (lo + hi)
    places = ((float(mid[0]), float(lo[1] + inset)), (float(lo[0] + inset), float(mid[1])))
    names = set(taken)
    out = []
    for (suffix, azimuth), (x, y) in zip(VIEWS, places, strict=True):
        name = unique_name(f"{plane.name} {suffix}", names)
        names.add(name)
        out.append(
            Observer(
                name, (round(x, 3), round(y, 3)), SEATED_EYE, azimuth=azimuth, group=plane.group
            )
        )
    return tuple(out)


def unique_name(name: str, taken: Iterable[str]) -> str:
    """``name``, or ``name-2``, ``name-3``, ... the first not in ``taken``."""
    taken = set(taken)
    k, out = 2, name
    while out in taken:
        out, k = f"{name}-{k}", k + 1
    return out


def preset_ugr_limit(key: str, edition: str) -> float | None:
    """The preset's UGR_L (None where the edition gives none)."""
    return requirement(key, edition).ugr_l


def preset_glare_intention(
    key: str, plane: Workplane, observers: Sequence[str], taken: Iterable[str] = ()
) -> Intention:
    """UGR at most the preset's UGR_L (of ``plane``'s edition) at ``observers``, named
    "<plane> UGR_L" (suffixed when ``taken``); DesignError when the preset has none or
    no observer is given."""
    r = requirement(key, plane.edition)
    if r.ugr_l is None:
        raise DesignError(f"{r.activity} ({r.edition}) gives no UGR_L")
    if not observers:
        raise DesignError("a UGR limit needs an observer: add one (Design > Add observer)")
    return Intention(
        unique_name(f"{plane.name} UGR_L", taken),
        observers=tuple(observers),
        quantity=Quantity.UGR,
        max=float(r.ugr_l),
    )


def strictest_preset(design: Design) -> Requirement | None:
    """The design's preset (of its work planes' intentions) with the lowest UGR_L, the
    limit a new observer is offered; None without one."""
    rows = [r for _, r in plane_presets(design) if r.ugr_l is not None]
    return min(rows, key=lambda r: r.ugr_l) if rows else None


def preset_glare_limit(
    design: Design, patches: Patches, plane: Workplane, key: str
) -> tuple[tuple[Observer, ...], Intention]:
    """What applying preset ``key`` to ``plane`` adds for glare: (the observers to add,
    the UGR_L intention). At every observer of the design when it has some (none
    added), else at ``default_observers`` of the plane."""
    new = () if design.observers else default_observers(patches, plane, ())
    names = [o.name for o in (*design.observers, *new)]
    taken = {i.name for i in design.intentions}
    return new, preset_glare_intention(key, plane, names, taken)
