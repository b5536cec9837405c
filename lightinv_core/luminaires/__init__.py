"""Luminaire photometry: IES LM-63 and EULUMDAT files, analytic distributions, the catalogue.

See docs/photometry.md. ``read_photometry`` reads either format into a ``Photometry``
(type C: intensity(C, gamma) in cd, flux in lm); ``analytic`` makes tables from
formulas; ``catalogue`` reads resources/luminaires/catalogue.json.
"""

from __future__ import annotations

from typing import Any

from lightinv_core.luminaires.analytic import batwing_linear, downlight, lambertian_panel
from lightinv_core.luminaires.formats import read_photometry, write_photometry
from lightinv_core.luminaires.ies import parse_ies, read_ies, write_ies
from lightinv_core.luminaires.ldt import parse_ldt, read_ldt, write_ldt
from lightinv_core.luminaires.photometry import Photometry

_CATALOGUE = ("CatalogueEntry", "builtin_catalogue", "generate_builtin", "read_catalogue")

__all__ = [
    "CatalogueEntry",
    "Photometry",
    "batwing_linear",
    "builtin_catalogue",
    "downlight",
    "generate_builtin",
    "lambertian_panel",
    "parse_ies",
    "parse_ldt",
    "read_catalogue",
    "read_ies",
    "read_ldt",
    "read_photometry",
    "write_ies",
    "write_ldt",
    "write_photometry",
]


def __getattr__(name: str) -> Any:
    # The catalogue is imported on first use, not here: `python -m
    # lightinv_core.luminaires.catalogue` would otherwise run a module already imported.
    if name in _CATALOGUE:
        from lightinv_core.luminaires import catalogue

        return getattr(catalogue, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
