"""The tabular UGR of a product (CIE 117:1995 section 4, CIE 190:2010): the standard
rooms, each evaluated with ``ugr.py``'s formula.

**The rooms.** The luminaires are ``H = 2 m`` above the eye, on a square grid of spacing
``S = 0.25 H`` filling a room X wide (across the line of sight) and Y deep (along it),
one at the centre of each S x S cell: N = XY / S² luminaires. The observer sits at the
middle of one wall of length X and looks horizontally along Y. Rooms: X = 2H with Y =
2H, 3H, 4H, 6H, 8H, 12H; X = 4H with the same; X = 8H and 12H with Y = 4H, 6H, 8H (and
8H x 12H): 19 rooms, as DIALux/Relux catalogues and eulumdat-ugr list them.

**Position index.** CIE 117's Table 4.1, interpolated bilinearly (``position_table.py``),
as CIE 190 prescribes for the table; observers in a room are rated with Guth's formula.

**Orientations.** *Crosswise*: the luminaire's C0-C180 plane lies along the line of
sight (C = atan2(T, R) from a luminaire to the eye, T sideways, R ahead); *endwise*: the
C90-C270 plane does (C = 90 - atan2(T, R)). This is the convention eulumdat-ugr gives as
CIE 117's equations 4.5 and 4.6. Luminaires further than gamma = 85 deg from the nadir
as seen from the eye (the far rows of the deepest rooms) are left out as eulumdat-ugr
does, as well as those outside CIE 117's field (``ugr.in_field``).

**Background luminance.** Lb = E_WID / pi, E_WID the indirect illuminance of the walls
between the eye plane (the reference plane, reflectance 20%) and the luminaire plane (the
ceiling), as CIE 190's transfer-factor method defines it. It is computed here as the
three-surface radiosity of that box (floor, walls, ceiling; exact view factors of
parallel rectangles), which reproduces CIE 190's transfer-factor table within 0.0013
(tests/core/test_ugr.py). The direct flux the luminaires send to the floor is integrated
exactly over the floor rectangle from every luminaire of the grid (the C-averaged
distribution, as CIE 190 uses zonal fluxes), the rest of the downward flux goes to the
walls and the upward flux to the ceiling. CIE 190 gets the floor share from zonal
multipliers instead; that is where the two methods differ.

The table is for the luminaire's own flux (the table's integral): CIE 190's "corrected"
values, which already include 8 log10(flux / 1000 lm) relative to a 1,000 lm table.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from lightinv_core.luminaires.photometry import Photometry
from lightinv_core.luminaires.position_table import table_position_index
from lightinv_core.luminaires.ugr import in_field, luminance, projected_area, ugr_from_sum

H = 2.0
"""m, luminaires above the eye in the standard rooms."""
SPACING = 0.25
"""Spacing-to-height ratio of the standard rooms' grid."""
GAMMA_MAX = 85.0
"""deg; luminaires seen further from the nadir are left out of the table."""
ROOMS: tuple[tuple[int, int], ...] = (
    *((2, y) for y in (2, 3, 4, 6, 8, 12)),
    *((4, y) for y in (2, 3, 4, 6, 8, 12)),
    *((8, y) for y in (4, 6, 8, 12)),
    *((12, y) for y in (4, 6, 8)),
)
"""(X / H, Y / H) of the 19 standard rooms."""
REFLECTANCES: tuple[tuple[float, float, float], ...] = (
    (0.7, 0.5, 0.2),
    (0.7, 0.3, 0.2),
    (0.5, 0.5, 0.2),
    (0.5, 0.3, 0.2),
    (0.3, 0.3, 0.2),
)
"""(ceiling, walls, reference plane) reflectances of the table's columns."""
ORIENTATIONS = ("crosswise", "endwise")
_AZIMUTHS = 720  # floor-flux integration: midpoints of 0.5 deg sectors
_GAMMA_STEP = 0.1  # deg, the C-averaged distribution's integration grid


def parallel_view_factor(x: float, y: float, h: float) -> float:
    """View factor between two directly opposed parallel x-by-y rectangles h apart
    (the closed form of e.g. Howell's catalogue, C-11)."""
    a, b = x / h, y / h
    log_term = 0.5 * math.log((1 + a * a) * (1 + b * b) / (1 + a * a + b * b))
    arctans = a * math.sqrt(1 + b * b) * math.atan(a / math.sqrt(1 + b * b)) + b * math.sqrt(
        1 + a * a
    ) * math.atan(b / math.sqrt(1 + a * a))
    return 2.0 / (math.pi * a * b) * (log_term + arctans - a * math.atan(a) - b * math.atan(b))


def wall_indirect_lux(
    x: float, y: float, h: float, flux: tuple[float, float, float], rho: tuple[float, ...]
) -> float:
    """Mean indirect illuminance (lux) of the walls of an x-by-y-by-h box whose floor,
    walls and ceiling receive ``flux`` (lm) directly and reflect ``rho`` (ceiling, walls,
    floor), by the three-surface radiosity with exact view factors."""
    rc, rw, rf = rho
    af, aw = x * y, 2.0 * h * (x + y)
    ffc = parallel_view_factor(x, y, h)
    fwf = (1.0 - ffc) * af / aw
    # Rows: floor, walls, ceiling; F[s, t] the view factor from s to t.
    f = np.array([[0.0, 1 - ffc, ffc], [fwf, 1 - 2 * fwf, fwf], [ffc, 1 - ffc, 0.0]])
    r = np.array([rf, rw, rc])
    direct = np.array(flux, dtype=float) / np.array([af, aw, af])
    exitance = np.linalg.solve(np.eye(3) - r[:, None] * f, r * direct)
    return float(f[1] @ exitance)


def _cumulative_down(ph: Photometry) -> tuple[np.ndarray, np.ndarray]:
    """(gamma grid in deg, integral of the C-averaged intensity times sin(gamma) from 0
    to each gamma, in lm/sr) below the horizontal."""
    g = np.arange(0.0, 90.0 + _GAMMA_STEP / 2, _GAMMA_STEP)
    c = np.arange(0.0, 360.0, 1.0)
    mean = ph.intensity(c[:, None], g[None, :]).mean(axis=0)
    f = mean * np.sin(np.radians(g))
    cum = np.concatenate([[0.0], np.cumsum(0.5 * (f[1:] + f[:-1]) * np.radians(_GAMMA_STEP))])
    return g, cum


def _grid(x_h: float, y_h: float) -> tuple[np.ndarray, np.ndarray]:
    """(T, R) of the standard room's luminaires, m, relative to the eye."""
    s = SPACING * H
    t = (np.arange(round(x_h * H / s)) + 0.5) * s - x_h * H / 2.0
    r = (np.arange(round(y_h * H / s)) + 0.5) * s
    tt, rr = np.meshgrid(t, r)
    return tt.reshape(-1), rr.reshape(-1)


def _to_edge(start: np.ndarray, step: np.ndarray, size: float) -> np.ndarray:
    """Distance along a horizontal direction (component ``step``) from ``start`` to the
    edge of [0, size] it moves towards; infinite for a direction across that axis."""
    with np.errstate(divide="ignore", invalid="ignore"):
        ahead = np.where(step > 0, (size - start) / step, -start / step)
    return np.where(step == 0, np.inf, ahead)


def floor_share(ph: Photometry, x_h: float, y_h: float) -> float:
    """Share of the downward flux of the standard room's luminaires that reaches the
    reference plane directly (the rest of it reaches the walls)."""
    g, cum = _cumulative_down(ph)
    if cum[-1] <= 0:
        return 0.0
    tt, rr = _grid(x_h, y_h)
    px, py = tt + x_h * H / 2.0, rr  # in the floor rectangle [0, X] x [0, Y]
    az = (np.arange(_AZIMUTHS) + 0.5) * (2 * math.pi / _AZIMUTHS)
    cx, cy = np.cos(az)[None, :], np.sin(az)[None, :]
    reach = np.minimum(_to_edge(px[:, None], cx, x_h * H), _to_edge(py[:, None], cy, y_h * H))
    gamma_max = np.degrees(np.arctan2(reach, H))
    on_floor = np.interp(gamma_max, g, cum).mean()
    return float(on_floor / cum[-1])


@dataclass(frozen=True)
class FluxFractions:
    """Where a luminaire's flux goes: ``down`` and ``up`` (shares of its flux below and
    above the horizontal) and, in the 4H x 8H standard room, the shares reaching the
    reference plane, the walls and the ceiling directly (CIE 190's F_DF, F_DW, F_DC)."""

    down: float
    up: float
    floor: float
    walls: float
    ceiling: float


def flux_fractions(ph: Photometry, room: tuple[float, float] = (4, 8)) -> FluxFractions:
    """The ``FluxFractions`` of ``ph`` (type C), the direct shares in ``room`` (X/H, Y/H)."""
    total = ph.flux()
    down = ph.flux(90.0) / total if total > 0 else 0.0
    floor = down * floor_share(ph, *room)
    return FluxFractions(down, 1.0 - down, floor, down - floor, 1.0 - down)


def glare_sum(ph: Photometry, x_h: float, y_h: float, orientation: str) -> float:
    """sum L² omega / p² of the standard room's luminaires (cd²/m⁴ sr)."""
    tt, rr = _grid(x_h, y_h)
    horizontal = np.hypot(tt, rr)
    gamma = np.degrees(np.arctan2(horizontal, H))
    # CIE 190 takes p from CIE 117's Table 4.1; Guth's smooth formula (ugr.guth_index),
    # a few percent above the table near the line of sight, made the DN150 downlight's
    # table 0.24 UGR lower than eulumdat-ugr's (docs/photometry.md).
    p = table_position_index(H / rr, tt / rr)
    keep = in_field(H / rr, tt / rr) & (gamma <= GAMMA_MAX) & np.isfinite(p)
    tt, rr, gamma, p = tt[keep], rr[keep], gamma[keep], p[keep]
    c = np.degrees(np.arctan2(tt, rr))
    if orientation == "endwise":
        c = 90.0 - c
    elif orientation != "crosswise":
        raise ValueError(f"orientation must be crosswise or endwise, got {orientation!r}")
    c = np.mod(c, 360.0)
    lum = luminance(ph, c, gamma)
    omega = projected_area(ph.opening, c, gamma) / (horizontal[keep] ** 2 + H * H)
    return float(np.sum(lum**2 * omega / p**2))


@dataclass(frozen=True)
class UgrTable:
    """A product's UGR table: ``values[room, reflectance, orientation]`` for ``ROOMS``,
    ``REFLECTANCES`` and ``ORIENTATIONS`` (crosswise, endwise)."""

    values: np.ndarray
    flux: float

    def at(
        self,
        room: tuple[int, int] = (4, 8),
        reflectances: tuple[float, float, float] = (0.7, 0.5, 0.2),
        orientation: str = "crosswise",
    ) -> float:
        """The UGR of one room (X/H, Y/H), reflectance set and orientation."""
        return float(
            self.values[
                ROOMS.index(tuple(room)),
                REFLECTANCES.index(tuple(reflectances)),
                ORIENTATIONS.index(orientation),
            ]
        )


def _room_values(ph: Photometry, i: int) -> np.ndarray:
    """UGR of room ``ROOMS[i]``: (reflectance set, orientation)."""
    x_h, y_h = ROOMS[i]
    total, down = ph.flux(), ph.flux(90.0)
    n = round(x_h / SPACING) * round(y_h / SPACING)
    to_floor = n * down * floor_share(ph, x_h, y_h)
    flux = (to_floor, n * down - to_floor, n * (total - down))
    sums = [glare_sum(ph, x_h, y_h, o) for o in ORIENTATIONS]
    out = np.full((len(REFLECTANCES), len(ORIENTATIONS)), np.nan)
    for j, rho in enumerate(REFLECTANCES):
        lb = wall_indirect_lux(x_h * H, y_h * H, H, flux, rho) / math.pi
        for k, s in enumerate(sums):
            out[j, k] = ugr_from_sum(s, lb) if lb > 0 else np.nan
    return out


def ugr_table(ph: Photometry) -> UgrTable:
    """The CIE 190 UGR table of a type C ``ph`` with a luminous opening (the module);
    ``NoLuminousArea`` without one."""
    values = np.array([_room_values(ph, i) for i in range(len(ROOMS))])
    return UgrTable(values, ph.flux())


def catalogue_ugr(ph: Photometry) -> tuple[float, float]:
    """(crosswise, endwise) UGR in the 4H x 8H room at 70/50/20: the value catalogues
    quote, for 1/19 of the table's time. ``NoLuminousArea`` without an opening."""
    values = _room_values(ph, ROOMS.index((4, 8)))
    return float(values[0, 0]), float(values[0, 1])
