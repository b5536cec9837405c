"""The view's maps at the observers (View > Colour by): each observer's glyph coloured by
its simplified DGP over the year, with a colour bar of its own and a label per eye.

Two maps, both of the figures of ``DocumentModel.observer_dgp`` (``light.dgp_observers``,
docs/daylight.md "Simplified DGP at observers in a project"):

- the share of the occupied hours whose DGPs exceeds the design's ``dgp_limit``, in %,
  drawn 0-10% from green through yellow (EN 17037's 5% of the hours) to red;
- EN 17037's glare protection level (none, minimum, medium, high), one colour each.

This module only turns figures into colours and words; ``daylight_maps`` lists the maps
and ``observer_overlay`` draws them.
"""

from __future__ import annotations

from dataclasses import dataclass

from lightinv_core.climate.sun_metrics import GLARE_LEVELS, GLARE_TIME_SHARE
from lightinv_core.kinds import Quantity
from lightinv_core.quantities import quantity_spec

SHARE = f"{Quantity.DGP}_share"
LEVEL = f"{Quantity.DGP}_level"
LEVELS = ("none", *(name for name, _ in GLARE_LEVELS))
"""EN 17037's glare protection levels, worst first (the level map's values 0-3)."""
LEVEL_COLOURS = ("#d62728", "#ff7f0e", "#bcbd22", "#2ca02c")
SHARE_TOP = 10.0  # %: the share map's range; twice EN 17037's 5% (its middle, yellow)


@dataclass(frozen=True)
class ObserverColours:
    """What the view draws at the observers: ``values`` {observer: value} through the
    colour map ``cmap`` (a name, or one colour per value with ``annotations``) over
    ``clim``; the colour bar's ``title`` and label format ``fmt``; ``labels``
    {observer: text} beside each eye."""

    values: dict[str, float]
    labels: dict[str, str]
    title: str
    clim: tuple[float, float]
    cmap: str | tuple[str, ...]
    fmt: str = "%.0f"
    annotations: dict[float, str] | None = None


def observer_maps() -> dict[str, tuple[str, str, str]]:
    """The maps at the observers, key -> (Colour by text, colour bar title, its format)."""
    noun = quantity_spec(Quantity.DGP).noun.replace(" exceedance", "")
    return {
        SHARE: (
            f"glare at the observers: {noun} (% of occupied hours above the limit)",
            "DGPs % h",
            "%.0f",
        ),
        LEVEL: ("glare at the observers: EN 17037 glare protection (level)", "EN 17037", "%.0f"),
    }


def observer_colours(key: str, figures: dict[str, dict]) -> ObserverColours:
    """The colours and labels of map ``key`` from {observer: DGP figures}."""
    labels = {name: _label(name, got) for name, got in figures.items()}
    if key == LEVEL:
        values = {name: float(LEVELS.index(got["en17037_glare"])) for name, got in figures.items()}
        names = dict(enumerate(LEVELS))
        return ObserverColours(
            values,
            labels,
            "EN 17037\nglare",
            (-0.5, 3.5),
            LEVEL_COLOURS,
            annotations={float(k): v for k, v in names.items()},
        )
    values = {name: 100.0 * got["exceedance"] for name, got in figures.items()}
    limit = next(iter(figures.values()))["limit"] if figures else 0.4
    return ObserverColours(
        values, labels, f"DGPs > {limit:.2f}\n% of hours", (0.0, SHARE_TOP), "RdYlGn_r"
    )


def _label(name: str, got: dict) -> str:
    """One observer's label: its share above the limit and its glare protection level."""
    return f"{name}: {100 * got['exceedance']:.1f}% > {got['limit']:.2f}, {got['en17037_glare']}"


def caption(key: str, figures: dict[str, dict], left_out: tuple[str, ...]) -> str:
    """The view's caption of map ``key``: what the colours mean and over which hours."""
    if not figures:
        text = "Glare at the observers: the design has no observer inside the room"
        return text + " (Design > Add observer)."
    got = next(iter(figures.values()))
    hours = f"{got['hours']:,} occupied hours"
    if key == LEVEL:
        limits = ", ".join(f"{lim:.2f} {name}" for name, lim in GLARE_LEVELS)
        text = (
            f"EN 17037 glare protection at the observers: the best level whose DGPs limit "
            f"({limits}) is exceeded in at most {100 * GLARE_TIME_SHARE:.0f}% of the {hours}"
        )
    else:
        text = (
            f"Simplified DGP at the observers: share of the {hours} with DGPs above "
            f"{got['limit']:.2f} (EN 17037: at most {100 * GLARE_TIME_SHARE:.0f}%)"
        )
    text += "\nDaylight only, sun included; surfaces in their materials"
    if left_out:
        text += f"\nNot rated (outside the room): {', '.join(left_out)}"
    return text
