"""EN 12464-1 lighting requirements for a few common activities, as grid intentions.

Two editions of "Light and lighting - Lighting of work places - Part 1: Indoor work
places", each a table of rows (``TABLE``), one ``Requirement`` per activity and edition:

- EN 12464-1:2011, clause 5 (reference numbers 5.x.y: table 5.26 "Offices", row 2):
  maintained illuminance Em (lux) on the task area, its uniformity U0 = Emin / Em,
  the glare limit UGR_L and the least colour rendering index Ra.
- EN 12464-1:2021, clause 6's schedule renumbered (tables 1-55; 34.2 is table 34
  "Offices", row 2): Em *required* and Em *modified* (the higher value the designer
  applies when context modifiers hold: visual work critical, errors costly, small
  details or low contrast, long task duration, the occupants' low visual capacity),
  U0, UGR_L and Ra. The modified Em is stored with the row; the intention asks the
  required one unless told otherwise (``preset_intention(..., modified=True)``).

The standard itself is sold by the standards bodies; the 2021 rows are transcribed from
published summaries of its tables: the office table of Performance in Lighting's
EN 12464-1 page (https://performanceinlighting.com/ww/us/en-12464-1: "Ēm required /
modified, Uo, Ra, RUGL", its row "Filing, copying, etc. 300 500 0,40 80"), the issue's
office row (500 / 1000 lx, U0 0.60, UGR_L 19, Ra 80) and the lighting makers'
summaries of tables 1 (traffic zones), 34 (offices) and 44 (educational premises). A
national annex can change them: for a project under one, enter its values as an
intention on the work plane. Ra is a property of the lamps: the report and the window
check it against the products' stated Ra (``ra_check``).
"""

from __future__ import annotations

from dataclasses import dataclass

from lightinv_core.design.model import Design, DesignError, Intention
from lightinv_core.kinds import Edition, Scenario
from lightinv_core.luminaires.rendering import product_ra

EDITION_2011 = Edition.EN12464_2011
EDITION_2021 = Edition.EN12464_2021
EDITIONS = tuple(Edition)
"""The editions the presets come from, oldest first."""
DEFAULT_EDITION = EDITION_2021
"""The edition a new work plane follows."""
LEGACY_EDITION = EDITION_2011
"""The edition of a work plane saved before editions were named (its grid unchanged)."""
EDITION = LEGACY_EDITION
"""Kept for older callers: the edition of ``REQUIREMENTS``."""


@dataclass(frozen=True)
class Requirement:
    """One activity's requirement in one edition: ``em`` lux (required), ``em_mod`` lux
    (modified; None where the edition has no such column), ``u0``, ``ugr_l``, ``ra``,
    and its ``reference`` (table row) in ``edition``."""

    key: str
    activity: str
    em: float
    u0: float
    ra: int
    reference: str
    edition: str = EDITION_2011
    ugr_l: float | None = None
    em_mod: float | None = None

    @property
    def label(self) -> str:
        """The activity, its edition and table row, and its values, for lists."""
        mod = f" (modified {self.em_mod:g})" if self.em_mod is not None else ""
        return (
            f"{self.activity} ({self.edition} ref. {self.reference}): {self.em:g} lux{mod}, "
            f"U0 {self.u0:.2f}"
        )

    @property
    def values(self) -> str:
        """Em (and modified Em), U0, UGR_L and Ra as one line, e.g. for the report."""
        mod = f" (modified {self.em_mod:g})" if self.em_mod is not None else ""
        ugr = f", UGR_L {self.ugr_l:g}" if self.ugr_l is not None else ""
        return f"Em {self.em:g} lux{mod}, U0 {self.u0:.2f}{ugr}, Ra {self.ra}"


def _rows(edition: str, rows: tuple[tuple, ...]) -> tuple[Requirement, ...]:
    return tuple(
        Requirement(key, activity, em, u0, ra, ref, edition, ugr, mod)
        for key, activity, em, mod, u0, ugr, ra, ref in rows
    )


# key, activity, Em, Em modified, U0, UGR_L, Ra, reference
TABLE: dict[str, tuple[Requirement, ...]] = {
    EDITION_2011: _rows(
        EDITION_2011,
        (
            ("corridor", "Circulation areas and corridors", 100, None, 0.40, 28, 40, "5.1.1"),
            ("archive", "Archives", 200, None, 0.40, 25, 80, "5.26.7"),
            ("filing", "Filing, copying, etc.", 300, None, 0.40, 19, 80, "5.26.1"),
            ("reception", "Reception desk", 300, None, 0.60, 22, 80, "5.26.6"),
            ("classroom", "Classrooms, tutorial rooms", 300, None, 0.60, 19, 80, "5.36.2"),
            (
                "office",
                "Writing, typing, reading, data processing",
                500,
                None,
                0.60,
                19,
                80,
                "5.26.2",
            ),
            ("meeting", "Conference and meeting rooms", 500, None, 0.60, 19, 80, "5.26.5"),
            ("cad", "CAD work stations", 500, None, 0.60, 19, 80, "5.26.4"),
            ("drawing", "Technical drawing", 750, None, 0.70, 16, 80, "5.26.3"),
        ),
    ),
    EDITION_2021: _rows(
        EDITION_2021,
        (
            ("corridor", "Corridors and circulation areas", 100, 150, 0.40, 28, 40, "1.1"),
            ("archive", "Archives", 200, 300, 0.40, 25, 80, "34.7"),
            ("filing", "Filing, copying, etc.", 300, 500, 0.40, 19, 80, "34.1"),
            ("reception", "Reception desk", 300, 500, 0.60, 22, 80, "34.6"),
            ("classroom", "Classrooms, tutorial rooms", 500, 1000, 0.60, 19, 80, "44.2"),
            (
                "office",
                "Writing, typing, reading, data processing",
                500,
                1000,
                0.60,
                19,
                80,
                "34.2",
            ),
            ("meeting", "Conference and meeting rooms", 500, 1000, 0.60, 19, 80, "34.5"),
            ("cad", "CAD work stations", 500, 1000, 0.60, 19, 80, "34.4"),
            ("drawing", "Technical drawing", 750, 1500, 0.70, 16, 80, "34.3"),
        ),
    ),
}
"""Each edition's presets, lowest Em first (the order the lists show)."""

REQUIREMENTS = TABLE[EDITION_2011]
"""The 2011 presets (kept for older callers; ``requirements(edition)`` for either)."""


def check_edition(edition: str) -> str:
    """``edition`` if LightInv has its presets and grid rule, else DesignError."""
    if edition not in TABLE:
        raise DesignError(
            f"unknown EN 12464-1 edition {edition!r}; editions: {', '.join(EDITIONS)}"
        )
    return edition


def requirements(edition: str = LEGACY_EDITION) -> tuple[Requirement, ...]:
    """The presets of ``edition`` (2011 by default, like ``requirement``)."""
    return TABLE[check_edition(edition)]


def requirement(key: str, edition: str = LEGACY_EDITION) -> Requirement:
    """The preset called ``key`` in ``edition`` (DesignError listing the keys otherwise)."""
    rows = requirements(edition)
    for r in rows:
        if r.key == key:
            return r
    keys = ", ".join(r.key for r in rows)
    raise DesignError(f"no {edition} preset {key!r}; presets: {keys}")


def preset_intention(
    key: str,
    grid: str,
    name: str | None = None,
    edition: str = LEGACY_EDITION,
    modified: bool = False,
) -> Intention:
    """An intention on work plane ``grid`` asking for the preset's Em (its modified Em
    with ``modified``) and U0 at night (luminaires only): the standard's values must
    hold without daylight."""
    r = requirement(key, edition)
    em = r.em_mod if modified and r.em_mod is not None else r.em
    return Intention(
        name or r.key, grid=grid, average=em, uniformity=r.u0, scenario=Scenario.NIGHT.value
    )


def preset_of(it: Intention, edition: str | None = None) -> Requirement | None:
    """The EN 12464-1 preset of ``edition`` (default 2011) an intention was made from
    (its name is the preset's key, perhaps with a "-2" suffix, and its Em, required or
    modified, and U0 are the preset's), else None."""
    key = it.name.split("-")[0]
    try:
        r = requirement(key, edition) if edition is not None else requirement(key)
    except DesignError:
        return None
    if it.grid is None or it.average not in (r.em, r.em_mod) or it.uniformity != r.u0:
        return None
    return r


def ra_check(required: int, stated: list[float | None]) -> tuple[str, bool | None]:
    """The products' Ra against a preset's ``required`` Ra: (text, verdict). The verdict
    is None when a product states no Ra ("not stated"), False when one is below."""
    if not stated:
        return "no luminaires", None
    known = [s for s in stated if s is not None]
    if len(known) < len(stated):
        low = [s for s in known if s < required]
        if low:
            return f"Ra {min(low):g} (one product not stated)", False
        return "not stated", None
    low = min(known)
    return f"Ra {low:g}", bool(low >= required)


def plane_presets(design: Design) -> list[tuple[str, Requirement]]:
    """(work plane, preset) of every intention made from a preset of its plane's
    edition, in the intentions' order."""
    planes = {w.name: w for w in design.workplanes}
    return [
        (it.grid, r)
        for it in design.intentions
        if it.grid in planes and (r := preset_of(it, planes[it.grid].edition)) is not None
    ]


def ra_warnings(design: Design) -> list[str]:
    """One line per array product whose stated Ra is below the highest Ra the design's
    presets ask, or that states none."""
    presets = plane_presets(design)
    if not presets or not design.arrays:
        return []
    need = max((r for _, r in presets), key=lambda r: r.ra)
    out = []
    for product in dict.fromkeys(a.product for a in design.arrays):
        ra = product_ra(product)
        short = product.replace("\\", "/").rsplit("/", 1)[-1]
        if ra is None:
            out.append(f"{short} states no Ra: {need.activity} asks Ra ≥ {need.ra}")
        elif ra < need.ra:
            out.append(
                f"{short}: Ra {ra:g} is below the Ra {need.ra} that {need.activity} asks "
                f"({need.edition})"
            )
    return out
