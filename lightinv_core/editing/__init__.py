"""The editing model: the open project, its scene, light and results, and every rule of
editing them, without Qt (the desktop window adapts it; scripts and tests use it as is).

``DocumentModel`` (document.py) holds the state and emits named events (events.py);
the rules are pure functions of the design (rules.py), of the results (results.py) and
of drawn zones (zones.py); the light shown comes from the ``LightModel`` (lighting.py).
"""

from lightinv_core.editing.document import (
    DocumentModel,
    blank_project,
    load_scene_of,
    obj_project,
)
from lightinv_core.editing.events import EVENTS, Events
from lightinv_core.editing.lighting import ShownLight
from lightinv_core.editing.results import result_label

__all__ = [
    "EVENTS",
    "DocumentModel",
    "Events",
    "ShownLight",
    "blank_project",
    "load_scene_of",
    "obj_project",
    "result_label",
]
