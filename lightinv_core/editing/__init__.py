"""The editing model: the open project, its scene, light and results, and every rule of
editing them, without Qt (the desktop window adapts it; scripts and tests use it as is).

``DocumentModel`` (document.py) is composed of one mixin per concern over the shared
state (state.py) and emits named events (events.py), each with a frozen payload of what
changed (changes.py); the rules are pure functions of the design (rules.py), of the
results (results.py) and of drawn zones (zones.py); the light shown comes from the
``LightModel`` (lighting.py).
"""

from lightinv_core.editing.changes import (
    DesignChanged,
    LightingChanged,
    OperatorChanged,
    PathChanged,
    ResultsChanged,
    SceneChanged,
    SelectionChanged,
)
from lightinv_core.editing.document import DocumentModel
from lightinv_core.editing.events import EVENT_TYPES, EVENTS, Events
from lightinv_core.editing.lighting import ShownLight
from lightinv_core.editing.project_file import blank_project, obj_project
from lightinv_core.editing.results import result_label
from lightinv_core.editing.state import load_scene_of

__all__ = [
    "EVENTS",
    "EVENT_TYPES",
    "DesignChanged",
    "DocumentModel",
    "Events",
    "LightingChanged",
    "OperatorChanged",
    "PathChanged",
    "ResultsChanged",
    "SceneChanged",
    "SelectionChanged",
    "ShownLight",
    "blank_project",
    "load_scene_of",
    "obj_project",
    "result_label",
]
