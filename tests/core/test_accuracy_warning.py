"""The operator's accuracy warning (issue #29, major 6): right after a model is imported,
before any zone exists, its error is estimated on scattered single patches emitting,
light no source can give, and it said "34.4% ... fix a higher rank (--rank)". A scene
without zones gets no such warning; one with zones still does when the target is
missed, worded for whoever reads it."""

from __future__ import annotations

from dataclasses import replace

from lightinv_core.editing import DocumentModel
from lightinv_core.editing.project_file import obj_project
from lightinv_core.operator.build import build_operator
from lightinv_core.operator.cache import CLI_REMEDY, accuracy_warning, get_operator
from lightinv_core.operator.settings import OperatorSettings
from tests.core.test_zone_on_cut_surface import draw, write_room


def test_no_accuracy_warning_before_any_zone_and_one_after_when_missed(tmp_path):
    doc = DocumentModel()
    doc.set_project(obj_project(write_room(tmp_path), resolution=0.5))
    bare = build_operator(doc.patches, OperatorSettings())
    # The estimate misses the 1% target by far on light no source gives, so the build
    # keeps its first rank (no doubling with no zones) and counts the target as met...
    assert bare.info["nz"] == 0 and bare.info["tol_met"]
    assert bare.info["estimated_rel_error"] > 0.2
    # ... so nothing is said about it.
    assert accuracy_warning(bare) is None
    warned: list[str] = []
    get_operator(doc.patches, OperatorSettings(), use_cache=False, warn=warned.append)
    assert not any("estimated error" in w for w in warned)

    # With a zone, the default target is met well within 1%...
    draw(doc, "sky", "skylight", 3.0, 3.5, 1.0)
    zoned = build_operator(doc.patches, OperatorSettings())
    assert zoned.info["nz"] > 0 and zoned.info["estimated_rel_error"] < 0.01
    assert accuracy_warning(zoned) is None
    # ... and a target it cannot meet is still told, with the reader's remedy.
    strict = build_operator(doc.patches, replace(OperatorSettings(), tol=1e-6))
    assert not strict.info["tol_met"]
    cli = accuracy_warning(strict)
    assert cli is not None and cli.endswith(CLI_REMEDY) and "--rank" in cli
    window = accuracy_warning(strict, "use a larger patch size")
    assert window.endswith("use a larger patch size") and "--" not in window
