"""The daylight criteria a clear-glazing year is judged by, each with pass or fail.

- LEED v4 EQ credit Daylight, option 1 (simulation per IES LM-83): sDA300/50% of at
  least 55% of the regularly occupied floor (2 points; 75%: 3 points), and ASE1000,250
  of no more than 10% (LM-83's own threshold for "unsatisfactory" sun), both over
  LM-83's period (8:00-18:00 every day: ``clear_metrics.lm83_figures``), whatever the
  project's occupancy;
- EN 17037: daylight provision at least at its minimum level; sunlight exposure at
  least 1.5 h (its minimum); glare protection at least at its minimum level at every
  view point.

A criterion is only listed when the year measured its metric (no view point: no glare).
"""

from __future__ import annotations

from dataclasses import dataclass

EN17037_ORDER = ("none", "minimum", "medium", "high")


@dataclass(frozen=True)
class Criterion:
    """A criterion: what it asks (``text``), the value found and its requirement as
    text, and whether it passes."""

    name: str
    text: str
    value: str
    required: str
    passed: bool

    def as_dict(self) -> dict:
        """JSON-ready."""
        return dict(self.__dict__)


def _level_at_least(level: str, need: str) -> bool:
    return EN17037_ORDER.index(level) >= EN17037_ORDER.index(need)


def judge(summary: dict) -> list[Criterion]:
    """The criteria of a clear year's ``summary`` (``clear_metrics.work_plane_metrics``
    with the views and sunlight exposure added when measured)."""
    out = []
    lm83 = summary["lm83"]
    sda, ase = lm83["sda300_50"], lm83["ase1000_250"]
    out.append(
        Criterion(
            "leed_sda",
            "LEED v4 EQ Daylight option 1: sDA300/50% (LM-83 blinds, 8-18 h every day)",
            f"{100 * sda:.0f}%",
            ">= 55% (2 points), >= 75% (3 points)",
            sda >= 0.55,
        )
    )
    out.append(
        Criterion(
            "leed_ase",
            "LEED v4 EQ Daylight option 1: ASE1000,250 (8-18 h every day)",
            f"{100 * ase:.0f}%",
            "<= 10%",
            ase <= 0.10,
        )
    )
    p = summary.get("en17037_provision")
    if p:
        out.append(
            Criterion(
                "en17037_provision",
                "EN 17037 daylight provision",
                p["level"],
                "minimum or better",
                _level_at_least(p["level"], "minimum"),
            )
        )
    s = summary.get("en17037_sunlight")
    if s:
        out.append(
            Criterion(
                "en17037_sunlight",
                f"EN 17037 sunlight exposure on {s['date'][5:]}",
                f"{s['hours']:.2f} h ({s['level']})",
                ">= 1.5 h (minimum)",
                _level_at_least(s["level"], "minimum"),
            )
        )
    for k, v in enumerate(summary.get("views", [])):
        out.append(
            Criterion(
                f"en17037_glare_{k + 1}",
                f"EN 17037 glare protection at view {k + 1} (DGPs)",
                v["en17037_glare"],
                "minimum or better (DGPs > 0.45 in at most 5% of occupied hours)",
                _level_at_least(v["en17037_glare"], "minimum"),
            )
        )
    return out
