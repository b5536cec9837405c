"""A luminaire's intensity distribution: the table, its interpolation and its flux.

Angles are degrees. For type C photometry (the only kind used for lighting here) C is
the azimuth, counted anticlockwise seen from above, C0 along the luminaire's length,
and gamma is measured from the nadir (0 = straight down, 90 = horizontal, 180 =
straight up). Intensities are candela for the whole luminaire, with every multiplier
of the file (candela multiplier, ballast factor, conversion factor) already applied.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field, replace

import numpy as np

from lightinv_core.errors import PhotometryError

KINDS = ("C", "B", "A")

# Symmetries of a type C distribution about its vertical planes (docs/photometry.md).
AXIAL = "axial"  # the same in every C plane
QUADRANT = "quadrant"  # mirrored about both the C0-C180 and the C90-C270 planes
BILATERAL_C0 = "bilateral-c0"  # mirrored about the C0-C180 plane: I(C) = I(360 - C)
BILATERAL_C90 = "bilateral-c90"  # mirrored about the C90-C270 plane: I(C) = I(180 - C)
NONE = "none"

ANGLE_TOL = 1e-6
"""Degrees; angles closer than this are the same angle (files print 2-6 decimals)."""


def fail(source: str, line: int | None, what: str, todo: str) -> PhotometryError:
    """The one-line error ``SOURCE:LINE: what; todo`` (without LINE where unknown)."""
    where = f"{source}:{line}" if line else source
    text = f"{where}: {what}; {todo}"
    # One line always: a quoted token or a keyword value may carry control characters.
    return PhotometryError(" ".join(text.split()))


def quote(token: str, limit: int = 24) -> str:
    """A file's token as shown in a message: quoted, printable, at most ``limit`` chars."""
    shown = "".join(ch if ch.isprintable() else "?" for ch in token)
    if len(shown) > limit:
        shown = shown[: limit - 3] + "..."
    return f"'{shown}'"


def _key(angle: float) -> float:
    """An angle folded into [0, 360) and rounded, to compare angles of one table."""
    a = round(float(angle) % 360.0, 6)
    return 0.0 if a >= 360.0 else a


def expand_c(
    angles: Sequence[float], rows: np.ndarray, mirrors: Sequence[Callable[[float], float]]
) -> tuple[np.ndarray, np.ndarray]:
    """Complete stored C planes with their mirror images: the full set in [0, 360).

    A plane given in the file wins over a mirror image of another at the same angle (so
    a file's 360 plane never replaces its 0 plane)."""
    table: dict[float, np.ndarray] = {}
    for a, row in zip(angles, rows, strict=True):
        table.setdefault(_key(a), row)
    for mirror in mirrors:
        for a, row in zip(angles, rows, strict=True):
            table.setdefault(_key(mirror(a)), row)
    keys = sorted(table)
    return np.array(keys, dtype=float), np.array([table[k] for k in keys], dtype=float)


MIRRORS: dict[str, tuple[Callable[[float], float], ...]] = {
    AXIAL: (),
    QUADRANT: (lambda c: 180.0 - c, lambda c: 180.0 + c, lambda c: 360.0 - c),
    BILATERAL_C0: (lambda c: 360.0 - c,),
    BILATERAL_C90: (lambda c: 180.0 - c,),
    NONE: (),
}


def _gamma_weights(g_deg: np.ndarray, upto_deg: float = 180.0) -> np.ndarray:
    """Weights w with sum_j w_j I_j = integral of the piecewise-linear I(gamma) times
    sin(gamma) d gamma from the first angle to min(last, upto): exact for the
    interpolant, so flux() agrees with intensity()."""
    g = np.radians(g_deg)
    top = math.radians(upto_deg)
    w = np.zeros(len(g))
    for j in range(len(g) - 1):
        a, b = g[j], g[j + 1]
        if a >= top:
            break
        e = min(b, top)
        h = b - a
        total = math.cos(a) - math.cos(e)  # integral of sin over [a, e]
        ramp = (-(e - a) * math.cos(e) + math.sin(e) - math.sin(a)) / h  # of (t - a)/h sin t
        w[j] += total - ramp
        w[j + 1] += ramp
    return w


def _c_weights(c_deg: np.ndarray) -> np.ndarray:
    """Trapezoid weights (radians) of the periodic piecewise-linear interpolation in C."""
    if len(c_deg) == 1:
        return np.array([2.0 * math.pi])
    ext = np.append(c_deg, c_deg[0] + 360.0)
    d = np.radians(np.diff(ext))  # d[i]: from plane i to the next, the last wraps
    return 0.5 * (d + np.roll(d, 1))


def _as_angles(values, name: str, source: str) -> np.ndarray:
    arr = np.array(values, dtype=float).reshape(-1)
    if arr.size == 0:
        raise fail(source, None, f"no {name}", "a photometric table needs at least one angle")
    if not np.all(np.isfinite(arr)):
        raise fail(source, None, f"{name} are not all finite numbers", "fix the table")
    if arr.size > 1 and not np.all(np.diff(arr) > 0):
        raise fail(source, None, f"{name} do not increase", "list angles in increasing order")
    return arr


@dataclass(frozen=True, eq=False)
class Photometry:
    """A luminaire's photometric table (see the module for angle conventions).

    ``candela`` has shape (len(c_angles), len(gamma_angles)), cd. For type C,
    ``c_angles`` is the full set in [0, 360) after the file's symmetry was expanded; a
    single plane means a rotationally symmetric luminaire. Type B and A tables are
    stored as read (``c_angles`` = horizontal, ``gamma_angles`` = vertical angles) but
    cannot be interpolated or integrated. ``lamp_lumens`` is the rated lamp flux (lm)
    the table was measured with, or None for absolute photometry; ``opening`` is the
    luminous opening (width across C90-C270, length along C0-C180, height), metres, as
    the file gives it (IES shape codes such as a negative width are kept; a EULUMDAT
    circle is read as the IES one). ``notes`` say what the reader did that the user may
    want to know; ``warnings`` what changes the light or makes the table doubtful (a
    lamp-tilt table not applied, a light output ratio above 100%), for the user to see
    (``light_warnings``).
    """

    kind: str
    c_angles: np.ndarray
    gamma_angles: np.ndarray
    candela: np.ndarray
    lamp_lumens: float | None = None
    input_watts: float | None = None
    opening: tuple[float, float, float] = (0.0, 0.0, 0.0)
    name: str = ""
    manufacturer: str = ""
    catalogue_number: str = ""
    source: str = ""
    n_lamps: int = 1
    lamp: str = ""
    notes: tuple[str, ...] = field(default=())
    warnings: tuple[str, ...] = field(default=())

    def __post_init__(self) -> None:
        src = self.source or "photometry"
        if self.kind not in KINDS:
            raise fail(src, None, f"unknown photometry type {self.kind!r}", "use 'C', 'B' or 'A'")
        c = _as_angles(self.c_angles, "C angles", src)
        g = _as_angles(self.gamma_angles, "gamma angles", src)
        cd = np.array(self.candela, dtype=float)
        if cd.shape != (c.size, g.size):
            raise fail(
                src,
                None,
                f"candela table has shape {cd.shape}, expected {(c.size, g.size)}",
                "give one row of intensities per C angle",
            )
        if not np.all(np.isfinite(cd)) or np.any(cd < 0):
            raise fail(src, None, "candela values must be finite and >= 0", "fix the table")
        if self.kind == "C":
            if c[0] < 0 or c[-1] >= 360.0:
                raise fail(src, None, "C angles must lie in [0, 360)", "fold 360 onto 0")
            if g[0] < 0 or g[-1] > 180.0:
                raise fail(src, None, "gamma angles must lie in [0, 180]", "fix the table")
            if g.size < 2:
                raise fail(src, None, "only one gamma angle", "give at least two")
        for name, value in (("lamp_lumens", self.lamp_lumens), ("input_watts", self.input_watts)):
            if value is not None and not (math.isfinite(value) and value > 0):
                raise fail(src, None, f"{name} = {value!r}", "give a positive number or None")
        if isinstance(self.n_lamps, bool) or not isinstance(self.n_lamps, int) or self.n_lamps < 1:
            raise fail(src, None, f"n_lamps = {self.n_lamps!r}", "give a whole number >= 1")
        for arr in (c, g, cd):
            arr.flags.writeable = False  # frozen means the tables too
        object.__setattr__(self, "c_angles", c)
        object.__setattr__(self, "gamma_angles", g)
        object.__setattr__(self, "candela", cd)
        object.__setattr__(self, "opening", tuple(float(x) for x in self.opening))
        object.__setattr__(self, "notes", tuple(self.notes))
        object.__setattr__(self, "warnings", tuple(self.warnings))

    def _require_c(self, what: str) -> None:
        if self.kind != "C":
            raise fail(
                self.source or "photometry",
                None,
                f"{what} needs type C photometry, this table is type {self.kind}",
                "convert the file to type C (C planes, gamma from the nadir)",
            )

    def intensity(self, c_deg, gamma_deg) -> np.ndarray:
        """Intensity (cd) towards (C, gamma) in degrees, broadcast like numpy: bilinear
        in (C, gamma), periodic in C, 0 outside the table's gamma range."""
        self._require_c("intensity")
        c, g = np.broadcast_arrays(np.asarray(c_deg, float), np.asarray(gamma_deg, float))
        cs, gs, cd = self.c_angles, self.gamma_angles, self.candela
        if cs.size == 1:
            i = np.zeros(c.shape, dtype=int)
            i1, t = i, np.zeros(c.shape)
        else:
            # Into [cs[0], cs[0] + 360), then the interval that holds it (the last wraps).
            cc = cs[0] + np.mod(c - cs[0], 360.0)
            ext = np.append(cs, cs[0] + 360.0)
            i = np.clip(np.searchsorted(ext, cc, side="right") - 1, 0, cs.size - 1)
            t = (cc - ext[i]) / (ext[i + 1] - ext[i])
            i1 = (i + 1) % cs.size
        j = np.clip(np.searchsorted(gs, g, side="right") - 1, 0, gs.size - 2)
        u = (g - gs[j]) / (gs[j + 1] - gs[j])
        val = (1 - t) * ((1 - u) * cd[i, j] + u * cd[i, j + 1]) + t * (
            (1 - u) * cd[i1, j] + u * cd[i1, j + 1]
        )
        inside = (g >= gs[0] - ANGLE_TOL) & (g <= gs[-1] + ANGLE_TOL)
        return np.where(inside, val, 0.0)

    def flux(self, gamma_max_deg: float = 180.0) -> float:
        """Luminous flux (lm) of the interpolated distribution over gamma <= gamma_max
        (180: the whole sphere, 90: the lower hemisphere), integrated exactly."""
        self._require_c("flux")
        wc = _c_weights(self.c_angles)
        wg = _gamma_weights(self.gamma_angles, gamma_max_deg)
        return float(wc @ self.candela @ wg)

    def max_intensity(self) -> float:
        """The largest intensity in the table (cd); interpolation never exceeds it."""
        return float(self.candela.max())

    def symmetry(self, rtol: float = 1e-9) -> str:
        """Which mirror symmetry the type C table has (AXIAL, QUADRANT, BILATERAL_C0,
        BILATERAL_C90 or NONE), as writers use it to store fewer planes."""
        self._require_c("symmetry")
        cd = self.candela
        atol = rtol * max(self.max_intensity(), 1e-300)
        if cd.shape[0] == 1 or np.allclose(cd, cd[0], rtol=rtol, atol=atol):
            return AXIAL
        index = {_key(a): k for k, a in enumerate(self.c_angles)}

        def holds(mirror: Callable[[float], float]) -> bool:
            for k, a in enumerate(self.c_angles):
                m = index.get(_key(mirror(a)))
                if m is None or not np.allclose(cd[k], cd[m], rtol=rtol, atol=atol):
                    return False
            return True

        about_c0 = holds(lambda c: 360.0 - c)
        about_c90 = holds(lambda c: 180.0 - c)
        if about_c0 and about_c90:
            return QUADRANT
        return BILATERAL_C0 if about_c0 else BILATERAL_C90 if about_c90 else NONE

    def stored_planes(self, symmetry: str) -> np.ndarray:
        """Indices of the C planes a file with ``symmetry`` stores (the others are mirror
        images), or an empty array if this grid lacks a plane that symmetry starts or
        ends on."""
        c = self.c_angles
        lo, hi = {
            AXIAL: (0.0, 0.0),
            QUADRANT: (0.0, 90.0),
            BILATERAL_C0: (0.0, 180.0),
            BILATERAL_C90: (90.0, 270.0),
            NONE: (0.0, 360.0),
        }[symmetry]
        if symmetry == AXIAL:
            return np.array([0])
        if symmetry == NONE:
            return np.arange(c.size)
        keys = {_key(a) for a in c}
        if lo not in keys or hi not in keys:
            return np.array([], dtype=int)
        return np.nonzero((c >= lo - ANGLE_TOL) & (c <= hi + ANGLE_TOL))[0]


LOR_ALLOWANCE = 0.01
"""A light output ratio up to 1 + this passes: a table's flux differs from the lamps'
by the integration rule and the digits printed (0.01-0.1% in the files tested)."""


def output_ratio_warning(ph: Photometry) -> str | None:
    """The warning for relative type C photometry whose table integrates to more than
    its lamps give (light output ratio = table flux / rated lamp lumens above 100%), or
    None."""
    if ph.kind != "C" or ph.lamp_lumens is None:
        return None
    flux = ph.flux()
    ratio = flux / ph.lamp_lumens
    if ratio <= 1.0 + LOR_ALLOWANCE:
        return None
    return (
        f"light output ratio {100.0 * ratio:.1f}%: the table integrates to {flux:,.0f} lm, "
        f"more than the {ph.lamp_lumens:,.0f} lm of its lamps; check the lamp lumens and "
        "the multipliers (the table is used as it is)"
    )


def with_output_ratio_warning(ph: Photometry) -> Photometry:
    """``ph`` with ``output_ratio_warning`` added to its warnings (if there is one)."""
    warning = output_ratio_warning(ph)
    return ph if warning is None else replace(ph, warnings=(*ph.warnings, warning))


def light_warnings(tables: Iterable[Photometry]) -> list[str]:
    """Every warning of ``tables`` once, each after its file: "FILE: warning". The one
    list the command line, the window and the report show."""
    out: list[str] = []
    for ph in tables:
        for warning in ph.warnings:
            line = f"{ph.source or ph.name or 'photometry'}: {warning}"
            if line not in out:
                out.append(line)
    return out
