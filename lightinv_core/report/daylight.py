"""The report's daylight and energy section (designs with skylights and work planes).

Every number comes from the layout's ``LayoutDaylight`` (``light/daylight.py``):

- per work plane: the daylight factor DF (CIE overcast sky, %) at its grid points:
  mean, median, min; DA300 (mean over the points), sDA300/50% and the four UDI bands
  (<100, 100-300, 300-3000, >3000 lux; shares of the occupied hours, as
  ``climate.metrics`` defines them), counted over the occupied hours of the weather
  year with the sorted-hour statistics of ``light.daylight_year``;
- the climate: weather site and file, occupancy schedule and occupied hours;
- daylight-linked dimming on the control work plane: annual kWh, the same hours at full
  output, savings, mean dimming level, LENI, and a bar chart of the months;
- plans of each work plane coloured by DF and by DA300, with iso-lines.

When the weather file cannot be read (or pvlib is missing) the DF part is still shown
and the section says, in its tables' notes, why the annual part is not.
"""

from __future__ import annotations

import calendar
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from matplotlib.figure import Figure

from lightinv_core.climate.control_modes import control_text
from lightinv_core.climate.metrics import DA_THRESHOLD, UDI_BANDS
from lightinv_core.design.model import Daylight, Design, Source
from lightinv_core.errors import LightInvError
from lightinv_core.light.daylight import SDA_SHARE, AnnualEnergy, LayoutDaylight
from lightinv_core.light.daylight_year import hours_from, hours_within
from lightinv_core.report.figures import draw_table, new_figure
from lightinv_core.report.luminaires import plan_figure
from lightinv_core.report.tables import Table
from lightinv_core.report.views import Outline
from lightinv_core.sources.types import daylit
from lightinv_core.value_text import fmt

UDI_NAMES = (
    f"UDI <{UDI_BANDS[0]:.0f}",
    f"UDI {UDI_BANDS[0]:.0f}-{UDI_BANDS[1]:.0f}",
    f"UDI {UDI_BANDS[1]:.0f}-{UDI_BANDS[2]:.0f}",
    f"UDI >{UDI_BANDS[2]:.0f}",
)
"""The four UDI bands (lux), as the tables head them."""


def pct(share: float | None, digits: int = 1) -> str:
    """A share (0-1) as a percentage: "74.2"; "—" when missing."""
    if share is None or not np.isfinite(share):
        return "—"
    return f"{100.0 * float(share):.{digits}f}"


def _percent(share: float | None) -> str:
    """ "74.2%", or "—" when missing."""
    text = pct(share)
    return text if text == "—" else f"{text}%"


@dataclass(frozen=True, eq=False)
class PlaneDaylight:
    """Daylight at one work plane's grid points: ``df`` (q,) in %, ``da`` (q,) DA300
    shares and ``udi`` (q, 4) the UDI bands' shares (None without the weather year)."""

    name: str
    points: np.ndarray
    spacing: tuple[float, float]
    df: np.ndarray
    da: np.ndarray | None
    udi: np.ndarray | None

    @property
    def df_mean(self) -> float:
        return float(self.df.mean())

    @property
    def df_median(self) -> float:
        return float(np.median(self.df))

    @property
    def df_min(self) -> float:
        return float(self.df.min())

    @property
    def da_mean(self) -> float | None:
        return None if self.da is None else float(self.da.mean())

    @property
    def sda(self) -> float | None:
        """sDA300/50%: the share of points with DA300 >= 50%."""
        return None if self.da is None else float((self.da >= SDA_SHARE).mean())

    @property
    def udi_mean(self) -> np.ndarray | None:
        """(4,) the bands' shares averaged over the points."""
        return None if self.udi is None else self.udi.mean(axis=0)


@dataclass(frozen=True, eq=False)
class DaylightSection:
    """What the section shows (see the module): ``planes`` per work plane, the weather
    ``site``, ``weather`` file name, occupied ``hours`` of ``year_hours``, ``energy``
    on the ``control`` work plane (None without the weather year) and ``problem``, why
    the annual part is missing ("" when it is not)."""

    daylight: Daylight
    planes: tuple[PlaneDaylight, ...]
    site: str | None
    weather: str
    hours: int | None
    year_hours: int | None
    energy: AnnualEnergy | None
    control: str | None
    installed_w: float
    skylights: tuple[Source, ...]
    problem: str = ""
    weather_info: dict | None = None

    @property
    def savings(self) -> float | None:
        """Share (0-1) of the full-output energy that dimming saves."""
        e = self.energy
        if e is None or not e.full_kwh > 0:
            return None
        return 1.0 - e.energy_kwh / e.full_kwh


def has_daylight(design: Design, sources) -> bool:
    """Whether a layout gets the section: skylight sources and work planes."""
    return bool(design.workplanes) and bool(daylit(sources))


def _weather_name(daylight: Daylight) -> str:
    if daylight.weather == "builtin":
        from lightinv_core.climate.weather import BUILTIN

        return f"built-in ({BUILTIN.name})"
    return Path(daylight.weather).name


def daylight_section(lay: LayoutDaylight, skylights=()) -> DaylightSection:
    """The section's numbers from one layout's ``LayoutDaylight`` (with work planes)."""
    if lay.points is None or lay.grids is None:
        raise LightInvError("the daylight section needs work planes")
    pts = lay.points
    year, problem = None, ""
    try:
        year = pts.year()
    except LightInvError as exc:
        problem = str(exc)
    planes = []
    for name, span in lay.grids.spans.items():
        df = 100.0 * pts.overcast_daylight(span)[:, 0]
        da = udi = None
        if year is not None:
            da = pts.da(span)[:, 0]
            a = pts.coefficients(span)[:, 0, :]
            lo, mid, hi = UDI_BANDS
            clear = pts.clear_hours(span)
            if clear is None:
                at_lo, at_mid = hours_from(year, a, lo), hours_from(year, a, mid)
                useful = hours_within(year, a, mid, hi)
            else:  # clear glazing's light hour by hour (light/clear_glazing.py)
                lux = a @ year.exterior + clear
                at_lo, at_mid = (lux >= lo).sum(1), (lux >= mid).sum(1)
                useful = ((lux >= mid) & (lux <= hi)).sum(1)
            counts = np.stack([year.hours - at_lo, at_lo - at_mid, useful, at_mid - useful], 1)
            udi = counts / year.hours
        planes.append(
            PlaneDaylight(
                name,
                lay.grids.points[span],
                tuple(lay.grids.grids[name].spacing),
                df,
                da,
                udi,
            )
        )
    energy = None
    if year is not None:
        try:
            energy = lay.energy()
        except LightInvError as exc:
            problem = str(exc)
    return DaylightSection(
        lay.design.daylight,
        tuple(planes),
        None if year is None else year.site,
        _weather_name(lay.design.daylight),
        None if year is None else year.hours,
        None if year is None else int(year.every.shape[1]),
        energy,
        lay.control,
        lay.installed_w,
        tuple(skylights),
        problem,
        None if year is None else year.weather,
    )


def _missing(section: DaylightSection) -> str:
    return (
        f"The weather year could not be used: {section.problem.rstrip('.')}. The annual "
        "metrics (DA300, sDA, UDI) and the dimming energy are not shown."
    )


def _weather_rows(info: dict | None) -> list[tuple[str, str]]:
    """How the weather file was read: its format and hours, the time convention, the
    illuminance decision and every note (filled values, a doubtful clock)."""
    if not info:
        return []
    rows = [
        ("weather data", f"{info['format']}, {info['hours']:,} hours, {info['time_convention']}"),
        ("daylight illuminance", info["illuminance"]),
    ]
    rows += [("weather note", note) for note in info.get("notes", [])]
    return rows


def climate_table(section: DaylightSection) -> Table:
    """The weather, schedule and daylight settings the section's numbers assume."""
    d = section.daylight
    days = "Monday to Friday" if d.weekdays else "every day"
    hours = f"{section.hours:,} of {section.year_hours:,}" if section.hours is not None else "—"
    rows = [
        ("weather site", section.site or "— (weather file not read)"),
        ("weather file", section.weather),
        *_weather_rows(section.weather_info),
        ("occupancy", f"{d.occupancy[0]:g}-{d.occupancy[1]:g} h local standard time, {days}"),
        ("occupied hours a year", hours),
        ("north", f"{d.north_deg:g}° (compass bearing of the scene's +y axis)"),
        ("ground reflectance", f"{d.ground_reflectance:g}"),
        ("glazing transmittance", f"{d.transmittance:g}"),
        ("skylights", ", ".join(f"{s.name} ({s.zone})" for s in section.skylights) or "—"),
    ]
    return Table(
        "Daylight: climate and schedule",
        ("setting", "value"),
        tuple(rows),
        note=_missing(section) if section.problem else "",
    )


def daylight_table(section: DaylightSection) -> Table:
    """Per work plane: DF mean / median / min (%), DA300 mean, sDA300/50% and the UDI
    bands (% of the occupied hours, averaged over the grid points)."""
    rows = []
    for p in section.planes:
        udi = p.udi_mean
        bands = [pct(None)] * 4 if udi is None else [pct(u) for u in udi]
        rows.append(
            (
                p.name,
                str(len(p.points)),
                fmt(p.df_mean, 3),
                fmt(p.df_median, 3),
                fmt(p.df_min, 3),
                pct(p.da_mean),
                pct(p.sda),
                *bands,
            )
        )
    note = (
        "DF: daylight under the CIE overcast sky as % of the horizontal exterior "
        "illuminance (ground reflection included). DA300: share of the occupied hours with "
        f"at least {DA_THRESHOLD:.0f} lux of daylight, averaged over the points; "
        f"sDA300/50%: share of the points with DA300 >= {100 * SDA_SHARE:.0f}%; UDI: "
        "shares of the occupied hours in each band of daylight illuminance, averaged over "
        "the points (UDI 100-3000 = the middle two)."
    )
    if section.problem:
        note += " The annual columns are empty: the weather year could not be used (above)."
    return Table(
        "Daylight per work plane (%)",
        (
            "work plane",
            "points",
            "DF mean",
            "DF median",
            "DF min",
            "DA300 mean",
            "sDA300/50%",
            *UDI_NAMES,
        ),
        tuple(rows),
        note=note,
    )


def energy_table(section: DaylightSection) -> Table:
    """Daylight-linked dimming over the weather year on the control work plane."""
    d, e = section.daylight, section.energy
    rows = [
        ("control work plane", section.control or "—"),
        ("installed electric power", f"{fmt(section.installed_w)} W"),
        (
            "dimming",
            f"to {fmt(d.target_lux)} lux mean, from {pct(d.min_level, 0)}% to full output; "
            f"standby {fmt(d.standby_w)} W all year",
        ),
    ]
    if e is not None:
        rows += [
            ("annual energy with dimming", f"{fmt(e.energy_kwh)} kWh"),
            ("annual energy at full output", f"{fmt(e.full_kwh)} kWh"),
            ("savings by dimming", _percent(section.savings)),
            ("mean dimming level", _percent(e.mean_level)),
            ("LENI", f"{fmt(e.leni)} kWh/m² a (over {fmt(e.floor_m2)} m² of floor)"),
        ]
    note = (
        "Luminaires dimmed each occupied hour so the control plane's mean illuminance, "
        "daylight plus electric, reaches the target; off outside the schedule. Full output: "
        "the same hours undimmed. LENI = annual energy / floor area (simplified EN 15193-1)."
    )
    if e is not None and e.groups:
        note = note.replace("so the control plane's mean", "so each control group's sensor")
    if e is None:
        note = _missing(section)
    return Table("Daylight-linked dimming energy", ("item", "value"), tuple(rows), note=note)


def control_groups_table(section: DaylightSection) -> Table | None:
    """Each daylight-linked control group's year (None with the one default group)."""
    e = section.energy
    if e is None or not e.groups:
        return None
    rows = tuple(
        (
            g.name,
            control_text(g.mode, g.target_lux, g.dead_band),
            str(g.luminaires),
            f"{fmt(g.watts)} W",
            str(g.sensor_points),
            _percent(g.min_level),
            _percent(g.mean_level),
            f"{fmt(g.energy_kwh)} kWh",
            f"{fmt(g.leni)}",
        )
        for g in e.groups
    )
    head = ("group", "control", "luminaires", "power", "sensor points", "floor", "mean level")
    return Table(
        "Control groups",
        (*head, "annual energy", "LENI kWh/m² a"),
        rows,
        note="Each group is controlled by its own sensor region (the mean daylight of its "
        "points) with its own luminaires' light there: dimming tops the daylight up to "
        "its target, switching is off while the daylight alone meets it; standby is "
        "counted once, in the total. "
        "LENI per group over the whole floor, so the groups' LENIs add up.",
    )


def energy_figure(section: DaylightSection) -> Figure | None:
    """The energy page: the dimming table (and the control groups') above a bar chart of
    each month's lighting energy (kWh); None without the energy (no weather year)."""
    if section.energy is None:
        return None
    fig = new_figure()
    y = draw_table(fig, energy_table(section), 0.94)
    groups = control_groups_table(section)
    if groups is not None:
        y = draw_table(fig, groups, y - 0.02)
    monthly_chart(section, fig, (0.08, 0.06, 0.87, max(y - 0.12, 0.15)))
    return fig


def monthly_chart(section: DaylightSection, fig, rect=(0.08, 0.1, 0.87, 0.78)) -> None:
    """Each month's lighting energy with dimming (kWh) as bars, in ``rect`` of ``fig``."""
    e = section.energy
    ax = fig.add_axes(rect)
    months = [calendar.month_abbr[m] for m in range(1, 13)]
    kwh = np.asarray(e.monthly_kwh, float)
    bars = ax.bar(months, kwh, color="C0")
    ax.bar_label(bars, labels=[fmt(v, 3) for v in kwh], fontsize=8, padding=2)
    ax.set_ylabel("kWh")
    ax.set_ylim(0, max(float(kwh.max()), 1e-9) * 1.2)
    ax.grid(axis="y", alpha=0.3)
    ax.set_title(
        f"Lighting energy per month with dimming (kWh; {fmt(e.energy_kwh)} kWh a year)",
        fontsize=11,
        loc="left",
    )


def _outlines(section: DaylightSection, outlines) -> list[Outline]:
    names = {s.name for s in section.skylights}
    return [o for o in outlines if o.kind == "source" and o.label in names]


def df_figures(section: DaylightSection, outlines=()) -> list[Figure]:
    """A plan of each work plane coloured by DF (%), the skylights' outlines dashed."""
    return [df_plan(section, p, outlines) for p in section.planes]


def df_plan(section: DaylightSection, p, outlines=(), fig=None):
    """The DF (%) plan of one work plane ``p`` (a ``section.planes`` item), into ``fig``
    when given."""
    title = (
        f"Daylight factor on work plane {p.name} at z = {p.points[0, 2]:.2f} m "
        f"(CIE overcast sky): mean {fmt(p.df_mean, 3)}%, median {fmt(p.df_median, 3)}%, "
        f"min {fmt(p.df_min, 3)}%"
    )
    return plan_figure(
        p.points,
        p.df,
        p.spacing,
        title,
        "daylight factor (%)",
        cmap="cividis",
        level_format="%.2g",
        outlines=_outlines(section, outlines),
        fig=fig,
    )


def da_figures(section: DaylightSection, outlines=()) -> list[Figure]:
    """A plan of each work plane coloured by DA300 (% of the occupied hours); none
    without the weather year."""
    return [da_plan(section, p, outlines) for p in section.planes if p.da is not None]


def da_plan(section: DaylightSection, p, outlines=(), fig=None):
    """The DA300 plan of one work plane ``p`` with its DA values, into ``fig`` when given."""
    title = (
        f"Daylight autonomy DA300 on work plane {p.name}: mean {pct(p.da_mean)}%, "
        f"sDA300/50% {pct(p.sda)}%\n{section.site}, {section.hours:,} occupied hours"
    )
    return plan_figure(
        p.points,
        100.0 * p.da,
        p.spacing,
        title,
        f"DA300 (% of occupied hours with daylight >= {DA_THRESHOLD:.0f} lux)",
        cmap="viridis",
        level_format="%.0f",
        vmax=100.0,
        outlines=_outlines(section, outlines),
        fig=fig,
    )
