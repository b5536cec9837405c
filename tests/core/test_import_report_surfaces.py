"""The report's per-group tables on an imported IFC model (found in the first-day
walkthrough, docs/walkthrough-first-day.md): AC20-FZK-Haus's 72 groups, 34 of them
rafters (``IfcMember:Sparren-1`` ...) with one reflectance, took four pages of surfaces
and three of illuminances, a row each. Groups of one IFC class alike in reflectance (and
its origin) now share a row."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from lightinv_core.report.room import surfaces_table
from lightinv_core.report.tables import MERGED, group_table


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


class Field:
    """A LightField's per-group statistics: ``lux[name]`` the group's (min, average, max)."""

    def __init__(self, patches, lux: dict[str, tuple[float, float, float]]):
        self.patches, self.lux = patches, lux

    def group_stats(self, name: str):
        lo, avg, hi = self.lux[name]
        one = lambda v: np.array([v])  # noqa: E731 (one scenario)
        return SimpleNamespace(min=one(lo), average=one(avg), max=one(hi), uniformity=one(lo / avg))


def test_the_illuminance_table_merges_alike_rafters_with_their_combined_values():
    groups = [("IfcMember:S1", 0.7, 1.0), ("IfcMember:S2", 0.7, 3.0), ("IfcMember:S3", 0.7, 1.0)]
    groups += [("IfcSlab:Floor", 0.2, 50.0)]
    p = prepared(groups).patches
    lux = {"IfcMember:S1": (10, 20, 30), "IfcMember:S2": (5, 40, 90), "IfcMember:S3": (15, 20, 25)}
    lux["IfcSlab:Floor"] = (200, 400, 600)
    rows = group_table(Field(p, lux)).rows
    assert [r[0] for r in rows] == ["IfcMember: 3 groups", "IfcSlab:Floor"]
    merged = rows[0]
    # min and max over the three, the average weighted by area (20 x 1 + 40 x 3 + 20 x 1) / 5
    assert (merged[1], merged[2]) == ("3", "5.0")
    assert [float(v) for v in merged[3:6]] == pytest.approx([5, 32, 90])
    assert float(merged[6]) == pytest.approx(5 / 32, abs=1e-3)
    assert [float(v) for v in rows[1][3:7]] == pytest.approx([200, 400, 600, 0.5])
