"""The editing rules ask a source's type and a rule's table, never switch on a kind: the
name, starting setting and surfaces of a new source or zone come from its type (a kind
registered from this module, or a built-in kind given another type), and every rule
kind has its text."""

from __future__ import annotations

import numpy as np
import pytest

from lightinv_core.design.model import Design, Goal, Rule
from lightinv_core.editing import DocumentModel, blank_project
from lightinv_core.editing import rules as edit_rules
from lightinv_core.editing.zones import on_walls
from lightinv_core.errors import DesignError
from lightinv_core.kinds import RuleKind
from lightinv_core.sources.types import (
    OVERHEAD_OR_WALL,
    SOURCE_TYPES,
    DiffusingGlazing,
    ZoneLuminaire,
    register_source_type,
    unregister_source_type,
)


class Pendant(ZoneLuminaire):
    """A luminaire kind of its own: new ones are called P1, P2, ..."""

    kind = "pendant"
    label = "Pendant"
    stem = "P"


class RoofLight(DiffusingGlazing):
    """A daylit kind of its own: new ones are called R1, ...; only on surfaces facing
    down."""

    kind = "roof_light"
    label = "Roof light"
    stem = "R"


class WallPanel(DiffusingGlazing):
    """Skylights as a type placed on walls too (its placement, not whether it is
    daylit, says where it goes)."""

    stem = "W"
    placement = OVERHEAD_OR_WALL


@pytest.fixture
def kinds():
    """Two kinds registered for one test, then removed."""
    registered = [register_source_type(Pendant()), register_source_type(RoofLight())]
    yield registered
    for t in registered:
        unregister_source_type(t.kind)


def test_a_new_source_is_named_and_started_by_its_type(monkeypatch):
    # The project model holds only the built-in kinds on this branch (the schema's
    # branch of issue 28 opens it to registered ones): give the built-in kinds other
    # types, so the names and settings can only come from the types.
    monkeypatch.setitem(SOURCE_TYPES, "luminaire", Pendant())
    monkeypatch.setitem(SOURCE_TYPES, "skylight", RoofLight())
    d = Design((), (Goal("min_electric_power"),))
    p = edit_rules.new_source(d, "z", "luminaire", (2.0, 2.0))
    assert (p.name, p.flux) == ("P1", edit_rules.NEW_LUMINAIRE_FLUX)
    assert p.free == ("u0", "v0", "u1", "v1", "flux")
    d = edit_rules.with_source(d, p)
    assert edit_rules.new_source(d, "z", "luminaire", (2.0, 2.0)).name == "P2"
    r = edit_rules.new_source(d, "z", "skylight", (2.0, 2.0))
    assert (r.name, r.filter, r.flux) == ("R1", 1.0, None)
    assert r.free == ("u0", "v0", "u1", "v1", "filter")
    with pytest.raises(DesignError, match="unknown source kind 'lamp'"):
        edit_rules.new_source(d, "z", "lamp", (2.0, 2.0))


def test_only_kinds_placed_on_walls_go_on_walls(kinds, monkeypatch):
    assert on_walls("luminaire") and on_walls("pendant")
    assert not on_walls("skylight") and not on_walls("roof_light")
    doc = DocumentModel()
    doc.set_project(blank_project("office", 0.7))
    ids = doc.patches.group_index("walls")
    wall = int(ids[np.argmin(np.linalg.norm(doc.patches.centroid[ids] - (6, 8, 1.5), axis=1))])
    ray = ((6.0, 4.0, 1.5), (0.0, 1.0, 0.0), wall)
    name, _ = doc.zone_surface("pendant", *ray)
    assert doc.scene.surface(name).group == "walls"
    with pytest.raises(DesignError, match="roof_light zones are drawn on ceilings and roofs"):
        doc.zone_surface("roof_light", *ray)
    monkeypatch.setitem(SOURCE_TYPES, "skylight", WallPanel())  # the type decides
    name, _ = doc.zone_surface("skylight", *ray)
    assert doc.scene.surface(name).group == "walls"


def test_every_rule_kind_has_its_text():
    assert set(edit_rules.RULE_TEXT) == set(RuleKind)
    cases = {
        Rule(RuleKind.AREA, ("L1", "L2"), min=0.5, max=4.0): (
            "area L1, L2",
            "at least 0.5 m² and at most 4 m²",
        ),
        Rule(RuleKind.ASPECT, ("L1",), max=2.0): ("aspect L1", "at most 2"),
        Rule(RuleKind.SPACING, ("L1", "L2"), min=1.0): ("spacing L1, L2", "at least 1 m"),
        Rule(RuleKind.MIRROR, ("L2", "L1"), axis="v"): ("mirror L2", "of L1 along v"),
        Rule(RuleKind.ALIGN, ("L1", "L2"), axis="u"): ("align L1, L2", "along u"),
        Rule(RuleKind.CENTRED, ("L1",)): ("centred L1", "in their zones"),
        Rule(RuleKind.SHR, ("A",), max=1.25): ("spacing/height A", "at most 1.25"),
        Rule(RuleKind.CLEARANCE, ("A",), min=0.3): (
            "clearance A",
            "at least 0.3 m from the zone's edges",
        ),
    }
    for rule, text in cases.items():
        assert edit_rules.rule_text(rule) == text
