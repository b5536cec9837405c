"""The vocabulary of LightInv: every kind of thing a project names, defined once.

``StrEnum`` members compare equal to the strings written in project files, so a file's
``"kind": "skylight"`` and ``SourceKind.SKYLIGHT`` are the same value.
"""

from __future__ import annotations

from enum import StrEnum


class SourceKind(StrEnum):
    """What emits: an electric luminaire or daylight through glazing (emitter zones take
    the same kinds)."""

    LUMINAIRE = "luminaire"  # electric: flux (lm) or exitance (lm/m²), efficacy (lm/W)
    SKYLIGHT = "skylight"  # glazing: exitance = filter x transmittance x exterior lux


class RuleKind(StrEnum):
    """Geometric rules on source rectangles (checked before any light is computed)."""

    AREA = "area"  # each source's area within min..max, m²
    ASPECT = "aspect"  # long side / short side at most max
    MIRROR = "mirror"  # the first source is the second flipped along axis
    CENTRED = "centred"  # each rectangle centred in its zone
    SPACING = "spacing"  # two sources at least min apart, m
    ALIGN = "align"  # centres on one line parallel to axis
    SHR = "shr"  # luminaire arrays: spacing / mounting height above the work plane <= max
    CLEARANCE = "clearance"  # luminaire arrays: every opening at least min from the zone edge, m


class Quantity(StrEnum):
    """What an intention bounds: illuminance (lux) or reflected exitance C (lm/m²)."""

    LUX = "lux"  # illuminance H = (B - E) / rho, lux
    C = "C"  # reflected exitance C = B - E, lm/m²


class Bound(StrEnum):
    """The bounds of an intention: per patch (min, max), area-weighted mean, U0."""

    MIN = "min"  # lower bound on every patch
    MAX = "max"  # upper bound on every patch
    AVERAGE = "average"  # lower bound on the area-weighted mean
    UNIFORMITY = "uniformity"  # lower bound on U0 = min / mean, in [0, 1]


class GoalKind(StrEnum):
    """What to optimise: electric power (W, minimised), reflected light power (lm,
    maximised), or the match error e (paper eq. 11, minimised)."""

    MIN_ELECTRIC_POWER = "min_electric_power"  # sum of flux / efficacy, W
    MAX_LIGHT_POWER = "max_light_power"  # sum_i C_i A_i, lm
    MATCH = "match"  # e = ||C - C_obj|| / ||C_obj||, no unit
    MIN_INSTALLED_POWER = "min_installed_power"  # rated power of every luminaire at full output, W
    MIN_LUMINAIRE_COUNT = "min_luminaire_count"  # luminaires in arrays plus luminaire sources


class VariableName(StrEnum):
    """A source's optimisation variables: rectangle corners (m), flux (lm), filter."""

    U0 = "u0"  # first corner along the zone's u axis, m
    V0 = "v0"  # first corner along v, m
    U1 = "u1"  # opposite corner along u, m
    V1 = "v1"  # opposite corner along v, m
    FLUX = "flux"  # a luminaire's luminous flux, lm
    FILTER = "filter"  # a skylight's filter, fraction in [0, 1]


class ArrayVariable(StrEnum):
    """A luminaire array's optimisation variables: the corners of the rectangle it fills
    (m), its rows and columns (whole numbers), rotation (0 or 90 degrees), dimming."""

    U0 = "u0"
    V0 = "v0"
    U1 = "u1"
    V1 = "v1"
    ROWS = "rows"  # luminaires along the zone's v axis
    COLUMNS = "columns"  # luminaires along u
    ROTATION = "rotation"  # 0: the product's C0 plane along u; 90: along v
    DIMMING = "dimming"  # output fraction of every luminaire of the array, (0, 1]
