"""The vocabulary of LightInv: every kind of thing a project names, defined once.

``StrEnum`` members compare equal to the strings written in project files, so a file's
``"kind": "skylight"`` and ``SourceKind.SKYLIGHT`` are the same value.
"""

from __future__ import annotations

from enum import StrEnum


class Kind(StrEnum):
    """A ``StrEnum`` whose repr is its string's, so messages that quote a value
    (``f"{kind!r}"``) read the same whether a model field holds the member or the
    string of a file."""

    def __repr__(self) -> str:
        return repr(self.value)


class SourceKind(Kind):
    """What emits: an electric luminaire or daylight through glazing (emitter zones take
    the same kinds)."""

    LUMINAIRE = "luminaire"  # electric: flux (lm) or exitance (lm/m²), efficacy (lm/W)
    SKYLIGHT = "skylight"  # glazing: exitance = filter x transmittance x exterior lux
    WINDOW = "window"  # glazing on any planar face (walls included), a skylight's light


_SOURCE_KINDS: list[str] = [str(k) for k in SourceKind]


def source_kind_names() -> tuple[str, ...]:
    """Every source kind a project may name: the built-in ones, then those a
    ``sources.types.register_source_type`` added (the model's validation reads this,
    being below the source types' behaviour in the layers)."""
    return tuple(_SOURCE_KINDS)


def add_source_kind(name: str) -> None:
    """Make ``name`` a valid source kind (ValueError when it is taken)."""
    if name in _SOURCE_KINDS:
        raise ValueError(f"source kind {name!r} is already registered")
    _SOURCE_KINDS.append(name)


def remove_source_kind(name: str) -> None:
    """Forget a source kind added by ``add_source_kind`` (the built-in ones stay)."""
    if name in tuple(SourceKind):
        raise ValueError(f"source kind {name!r} is built in")
    if name in _SOURCE_KINDS:
        _SOURCE_KINDS.remove(name)


class GlazingKind(Kind):
    """How glazing passes daylight (docs/daylight.md): as a glow, or with its direction."""

    DIFFUSING = "diffusing"  # the outside light on its plane x T leaves as a Lambertian exitance
    CLEAR = "clear"  # the sky and sun seen through it, T by incidence (Radiance's glass)


class RuleKind(Kind):
    """Geometric rules on source rectangles (checked before any light is computed)."""

    AREA = "area"  # each source's area within min..max, m²
    ASPECT = "aspect"  # long side / short side at most max
    MIRROR = "mirror"  # the first source is the second flipped along axis
    CENTRED = "centred"  # each rectangle centred in its zone
    SPACING = "spacing"  # two sources at least min apart, m
    ALIGN = "align"  # centres on one line parallel to axis
    SHR = "shr"  # luminaire arrays: spacing / mounting height above the work plane <= max
    CLEARANCE = "clearance"  # luminaire arrays: every opening at least min from the zone edge, m


class Quantity(Kind):
    """What an intention bounds: illuminance (lux) or reflected exitance C (lm/m²) in
    its scenario, or a daylight metric (docs/daylight.md), each per patch or grid point.
    Each one's unit, range, labels and scenario: its ``QuantitySpec`` (quantities.py)."""

    LUX = "lux"  # illuminance H = (B - E) / rho, lux
    C = "C"  # reflected exitance C = B - E, lm/m²
    DF = "df"  # daylight factor under the CIE overcast sky, % (daylight only)
    DA = "da"  # daylight autonomy DA300: share of occupied hours with >= 300 lux daylight
    UDI = "udi"  # useful daylight: share of occupied hours with 100-3000 lux daylight
    SDA = "sda"  # 1 where DA300 >= 50%, else 0: its average is sDA300/50%
    ASE = "ase"  # 1 where direct sun > 1000 lux in > 250 occupied hours: ASE1000,250
    UGR = "ugr"  # CIE 117 unified glare rating at the design's observers (luminaires only)
    EN17037 = "en17037"  # EN 17037 daylight provision of a work plane: a level score 0-3
    SUNLIGHT = "sunlight"  # EN 17037 sunlight exposure at observers: hours of sun on a day
    CDA = "cda"  # continuous daylight autonomy cDA300: mean of min(E / 300, 1) over the hours
    DGP = "dgp"  # share of occupied hours with simplified DGP above the limit, at observers


MAX_LUX = 1e6
"""Lux (and lm/m²): ten times full sunlight, the largest illuminance a design may name."""


class Scenario(Kind):
    """The light an intention is judged in (docs/daylight.md, scenarios)."""

    DESIGN = "design"  # luminaires plus skylights at the design exterior lux (the paper's)
    NIGHT = "night"  # luminaires only
    OVERCAST = "overcast"  # luminaires plus the CIE overcast sky through the glazing
    ANNUAL = "annual"  # daylight through every occupied hour of the weather file


class Bound(Kind):
    """The bounds of an intention: per patch (min, max), area-weighted mean (at least
    ``average``, at most ``max_average``), U0."""

    MIN = "min"  # lower bound on every patch
    MAX = "max"  # upper bound on every patch
    AVERAGE = "average"  # lower bound on the area-weighted mean
    UNIFORMITY = "uniformity"  # lower bound on U0 = min / mean, in [0, 1]
    MAX_AVERAGE = "max_average"  # upper bound on the area-weighted mean (ASE <= 10%)


UPPER_BOUNDS = frozenset({Bound.MAX, Bound.MAX_AVERAGE})
"""The bounds a value must stay at or below (the others: at or above)."""


def bound_sign(bound: str) -> str:
    """ "≤" for an upper bound, "≥" for a lower one."""
    return "≤" if bound in UPPER_BOUNDS else "≥"


class GoalKind(Kind):
    """What to optimise: electric power (W, minimised), reflected light power (lm,
    maximised), the match error e (paper eq. 11, minimised), installed power, luminaire
    count, and the climate goals: annual energy (kWh), sDA (maximised), glazing area (m²).
    Each one's names, unit and direction: its ``GoalSpec`` (goals.py)."""

    MIN_ELECTRIC_POWER = "min_electric_power"  # sum of flux / efficacy, W
    MAX_LIGHT_POWER = "max_light_power"  # sum_i C_i A_i, lm
    MATCH = "match"  # e = ||C - C_obj|| / ||C_obj||, no unit
    MIN_INSTALLED_POWER = "min_installed_power"  # rated power of every luminaire at full output, W
    MIN_LUMINAIRE_COUNT = "min_luminaire_count"  # luminaires in arrays plus luminaire sources
    MIN_ANNUAL_ENERGY = "min_annual_energy"  # electric lighting energy with dimming, kWh/a
    MAX_SDA = "max_sda"  # sDA300/50% of the control work plane, fraction
    MIN_GLAZING_AREA = "min_glazing_area"  # area of the skylight sources, m²


class VariableName(Kind):
    """A source's optimisation variables: rectangle corners (m), flux (lm), filter."""

    U0 = "u0"  # first corner along the zone's u axis, m
    V0 = "v0"  # first corner along v, m
    U1 = "u1"  # opposite corner along u, m
    V1 = "v1"  # opposite corner along v, m
    FLUX = "flux"  # a luminaire's luminous flux, lm
    FILTER = "filter"  # a skylight's filter, fraction in [0, 1]


class ArrayVariable(Kind):
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


class Edition(Kind):
    """The edition of EN 12464-1 a work plane follows: its grid rule and its presets."""

    EN12464_2011 = "EN 12464-1:2011"  # points per side rounded up, each side on its own
    EN12464_2021 = "EN 12464-1:2021"  # cell from the longer side, points per side rounded
