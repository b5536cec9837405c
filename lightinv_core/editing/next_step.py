"""What a designer should do next on the open design: the first step of the product's
workflow the design still lacks (issue #29: an imported model was a black box, with no
word of where to begin).

The workflow, in order: draw emitter zones where light may go, add light in them
(luminaire arrays or sources), add a work plane, say what light it needs (an EN 12464-1
preset, or any intention), and run the optimiser. ``next_step`` reads only the scene's
zones, the design and whether a run has left results; it knows nothing of the window,
whose hint names the buttons to press (the texts here name them as the window shows
them).
"""

from __future__ import annotations

from dataclasses import dataclass

from lightinv_core.design.model import Design
from lightinv_core.scene.model import Scene

STEPS = ("zones", "light", "workplane", "intention", "run")
"""The workflow's steps, in the order a design needs them."""


@dataclass(frozen=True)
class NextStep:
    """The step a design needs next: its ``key`` (one of ``STEPS``), its ``number``
    (1-based, of ``len(STEPS)``) and what to do, in words (``text``)."""

    key: str
    text: str

    @property
    def number(self) -> int:
        """1 for the first step of ``STEPS``."""
        return STEPS.index(self.key) + 1

    def hint(self) -> str:
        """The step as a hint: "Next (step 2 of 5): ..."."""
        return f"Next (step {self.number} of {len(STEPS)}): {self.text}"


TEXTS = {
    "zones": (
        "draw where light may go. Choose 'luminaire zone' or 'skylight zone' in the "
        "toolbar, press Draw zone and drag a rectangle on the ceiling (Top view looks "
        "through it), or Draw polygon and click its corners."
    ),
    "light": (
        "add light in the zones. Luminaires tab: pick a catalogue product and press Add "
        "array…; or Properties > Source: Add source (a skylight or a panel)."
    ),
    "workplane": "add a work plane to judge the light on (Luminaires tab, Add work plane…)",
    "intention": (
        "say what light the work plane needs. Luminaires tab: choose an EN 12464-1 "
        "intention in the box beside Add work plane… (or Select patches, then Add intention)."
    ),
    "run": (
        "press Run (toolbar, F5): the optimiser places and sizes the light to meet the "
        "intentions at the least cost."
    ),
}


def next_step(scene: Scene | None, design: Design | None, has_results: bool) -> NextStep | None:
    """The first step of the workflow the design lacks, or None when every step is done
    (a run has left results) or nothing is open. A design that already has light skips
    the zones (a built-in scene's zones, or sources placed by hand); any intention
    (on picked patches too) counts as saying what light is needed, work plane or not."""
    if scene is None or design is None:
        return None
    lit = bool(design.sources or design.arrays)
    if not lit and not scene.zones:
        key = "zones"
    elif not lit:
        key = "light"
    elif not design.intentions and not design.workplanes:
        key = "workplane"
    elif not design.intentions:
        key = "intention"
    elif not has_results:
        key = "run"
    else:
        return None
    return NextStep(key, TEXTS[key])


def document_next_step(doc) -> NextStep | None:
    """``next_step`` of an editing document (``DocumentModel``): its scene, its design
    and whether its project holds a run's results."""
    project = doc.project
    if project is None:
        return None
    return next_step(doc.scene, project.design, bool(project.runs or project.solutions))
