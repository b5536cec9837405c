"""The light of another layout for the difference view (issue #29: its work plane was
grey with absolute labels): a pinned result's light on the patches and at the work
planes' points includes its luminaire arrays, as the design shown includes its own, so
the same layout differs from itself by zero."""

from __future__ import annotations

import numpy as np

from lightinv_core.design.model import LuminaireArray, Workplane
from lightinv_core.editing import DocumentModel, blank_project
from lightinv_core.luminaires import builtin_catalogue
from lightinv_core.operator.build import build_operator
from lightinv_core.operator.settings import OperatorSettings


def test_a_layout_with_arrays_differs_from_itself_by_zero_and_from_none_by_its_light():
    doc = DocumentModel()
    doc.set_project(blank_project("office", 0.7))
    doc.set_operator(build_operator(doc.patches, OperatorSettings(rank=100, rays=128)))
    assert doc.grid_lux_of(()) is None  # no work plane yet
    doc.add_source("lum_east")
    product = builtin_catalogue()[0].name
    array = LuminaireArray("A", "lum_west", product, (0.2, 0.5, 1.8, 5.5), rows=3, columns=1)
    doc.set_arrays((array,))
    doc.set_workplanes((Workplane("desks"),))
    sources, arrays = doc.design.sources, doc.design.arrays
    shown = doc.field.illuminance
    np.testing.assert_allclose(doc.lighting_of(sources, arrays), shown, rtol=1e-5, atol=1e-6)
    _, grid = doc.shown_grids()
    np.testing.assert_allclose(doc.grid_lux_of(sources, arrays), grid, rtol=1e-5, atol=1e-6)
    # Without the array, the difference is the array's light: positive somewhere, and
    # never negative (light only adds).
    diff = shown - doc.lighting_of(sources)
    assert diff.max() > 1.0 and diff.min() > -1e-6
    gdiff = grid - doc.grid_lux_of(sources)
    assert gdiff.max() > 1.0 and gdiff.min() > -1e-6
