"""``DocumentModel``: the open project as an editor sees it, with every editing rule.

Plain Python (the desktop window adapts it to Qt signals in ``app/document.py``; a
script or a test drives it directly). It holds the project, its scene and patches, the
radiosity operator and light model once built, the selection, the current source, the
file path and dirty flag, the result shown and the layout previewed (state.py). Each
setter applies its rule, then emits the named events of what changed, each with its
payload (events.py, changes.py).

The methods are grouped by concern, one module each, composed here as mixins over the
shared state: the project as a file (project_file.py), the scene, its drawn zones and
the picking (scene_edits.py), sources and rules (source_edits.py), intentions, work
planes, goals and climate (intent_edits.py), daylight-linked control groups
(control_edits.py), the light shown (light_view.py) and the
results (run_history.py). Mixins keep one flat API, so the window and scripts call
``doc.add_source(...)`` as before, without a forwarding method per call; each concern
calls only ``DocumentState``'s transitions, never another concern's methods.
"""

from __future__ import annotations

from lightinv_core.editing.control_edits import ControlEdits
from lightinv_core.editing.intent_edits import IntentEdits
from lightinv_core.editing.light_view import LightView
from lightinv_core.editing.project_file import ProjectFile
from lightinv_core.editing.run_history import RunHistory
from lightinv_core.editing.scene_edits import SceneEdits
from lightinv_core.editing.source_edits import SourceEdits


class DocumentModel(
    ProjectFile, SceneEdits, SourceEdits, IntentEdits, ControlEdits, LightView, RunHistory
):
    """The project, its scene, patches and light model, the selection and the results,
    and every edit of them (see the concern each method comes from)."""
