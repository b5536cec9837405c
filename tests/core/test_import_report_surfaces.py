"""The report's surfaces table on an imported IFC model (found in the first-day
walkthrough, docs/walkthrough-first-day.md): AC20-FZK-Haus's 72 groups, 40 of them
rafters (``IfcMember:Sparren-1`` ...) with one reflectance, took four pages, a row each.
Groups of one IFC class alike in reflectance and its origin now share a row."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from lightinv_core.report.room import MERGED, surfaces_table


def prepared(groups: list[tuple[str, float, float]]):
    """Patches of one 1 m² patch per (group, reflectance) pair and ``area`` m² each."""
    names = [g for g, _, _ in groups]
    return SimpleNamespace(
        patches=SimpleNamespace(
            group_names=tuple(names),
            group_id=np.arange(len(names)),
            area=np.array([a for _, _, a in groups]),
            rho=np.array([r for _, r, _ in groups]),
            surface_names=tuple(n.replace(":", " ") for n in names),
            surface_id=np.arange(len(names)),
        )
    )


PROJECT = SimpleNamespace(scene=SimpleNamespace(reflectances=(), builtin=None, materials=None))


def test_rafters_alike_share_one_row_and_others_keep_theirs():
    rafters = [(f"IfcMember:Sparren-{k}", 0.7, 0.4) for k in range(1, 41)]
    odd = [("IfcMember:Pfosten", 0.5, 1.0)]  # another reflectance: its own row
    walls = [("IfcWall:Ext-1", 0.5, 20.0), ("IfcWall:Ext-2", 0.5, 18.0)]  # fewer than MERGED
    table = surfaces_table(PROJECT, prepared([*walls, *rafters, *odd, ("floor", 0.2, 30.0)]))
    rows = {r[0]: r for r in table.rows}
    assert list(rows) == [
        "IfcWall:Ext-1",
        "IfcWall:Ext-2",
        "IfcMember: 40 groups",
        "IfcMember:Pfosten",
        "floor",
    ]
    merged = rows["IfcMember: 40 groups"]
    assert float(merged[1]) == pytest.approx(16.0)  # 40 x 0.4 m²
    assert merged[2] == "0.70"
    first = "IfcMember Sparren-1, IfcMember Sparren-10, IfcMember Sparren-11"
    assert merged[3] == f"{first} and 37 more"
    assert rows["IfcWall:Ext-1"][1] == "20.0"


def test_a_set_reflectance_keeps_its_group_apart():
    groups = [(f"IfcSlab:S{k}", 0.3, 2.0) for k in range(MERGED)]
    project = SimpleNamespace(
        scene=SimpleNamespace(reflectances=(("IfcSlab:S0", 0.3),), builtin=None, materials=None)
    )
    rows = [r[0] for r in surfaces_table(project, prepared(groups)).rows]
    # S0's value was set in the materials panel: the other two are too few to merge.
    assert rows == ["IfcSlab:S0", "IfcSlab:S1", "IfcSlab:S2"]
    rows = [r[0] for r in surfaces_table(PROJECT, prepared(groups)).rows]
    assert rows == [f"IfcSlab: {MERGED} groups"]
