"""The vocabulary of LightInv: every kind of thing a project names, defined once.

``StrEnum`` members compare equal to the strings written in project files, so a file's
``"kind": "skylight"`` and ``SourceKind.SKYLIGHT`` are the same value.
"""

from __future__ import annotations

from enum import StrEnum


class SourceKind(StrEnum):
    """What emits: an electric luminaire or daylight through glazing (emitter zones take
    the same kinds)."""

    LUMINAIRE = "luminaire"
    SKYLIGHT = "skylight"


class RuleKind(StrEnum):
    """Geometric rules on source rectangles (checked before any light is computed)."""

    AREA = "area"
    ASPECT = "aspect"
    MIRROR = "mirror"
    CENTRED = "centred"
    SPACING = "spacing"
    ALIGN = "align"


class Quantity(StrEnum):
    """What an intention bounds: illuminance (lux) or reflected exitance C (lm/m²)."""

    LUX = "lux"
    C = "C"


class Bound(StrEnum):
    """The bounds of an intention: per patch (min, max), area-weighted mean, U0."""

    MIN = "min"
    MAX = "max"
    AVERAGE = "average"
    UNIFORMITY = "uniformity"


class GoalKind(StrEnum):
    """What to optimise: electric power (W, minimised), reflected light power (lm,
    maximised), or the match error e (paper eq. 11, minimised)."""

    MIN_ELECTRIC_POWER = "min_electric_power"
    MAX_LIGHT_POWER = "max_light_power"
    MATCH = "match"


class VariableName(StrEnum):
    """A source's optimisation variables: rectangle corners (m), flux (lm), filter."""

    U0 = "u0"
    V0 = "v0"
    U1 = "u1"
    V1 = "v1"
    FLUX = "flux"
    FILTER = "filter"
