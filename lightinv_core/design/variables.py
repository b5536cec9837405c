"""The optimisation variables of a design and their decoding into source parameters.

x is a flat vector of the free variables; ``decode`` turns a stack of them
(m, nvar) into per-candidate rectangles (m, S, 4), fluxes and filters (m, S),
applying the tied rules: a ``centred`` source's second corner mirrors its first
through the zone centre, and a ``mirror`` source copies its original flipped
along a zone axis. Tied values are never variables.

Luminaire arrays' variables follow the sources' (``decode_arrays``). Rows, columns and
rotation are whole numbers: their variables are continuous over [lo - 0.499, hi + 0.499]
and rounded to the nearest whole number when decoded, so every method (VNS, CMA-ES,
NSGA-II) searches them unchanged and each whole value gets an equal share of a random
start.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from lightinv_core.design.model import CORNERS, Design, DesignError, LuminaireArray, Source

ROUNDED = ("rows", "columns", "rotation")
"""Array variables decoded to whole numbers."""
HALF = 0.499


@dataclass(frozen=True)
class Variable:
    """One free variable: ``source`` index (of the design's sources, or of its arrays
    when ``owner`` is "array"), ``name``, bounds."""

    source: int
    name: str
    lo: float
    hi: float
    owner: str = "source"


@dataclass(frozen=True)
class ArrayLayout:
    """Decoded luminaire arrays of m candidates: ``rect`` (m, A, 4) m, ``rows`` and
    ``columns`` (m, A) int, ``rotation`` (m, A) degrees (0 or 90), ``dimming`` (m, A)."""

    rect: np.ndarray
    rows: np.ndarray
    columns: np.ndarray
    rotation: np.ndarray
    dimming: np.ndarray

    @property
    def count(self) -> np.ndarray:
        """Luminaires of each array, (m, A)."""
        return self.rows * self.columns

    def take(self, idx: np.ndarray) -> ArrayLayout:
        """The layouts of candidates ``idx``."""
        return ArrayLayout(*(getattr(self, f)[idx] for f in self.__dataclass_fields__))


class Variables:
    """Layout of x for a design whose zones have the given (width, height) in metres."""

    def __init__(self, design: Design, zone_size: dict[str, tuple[float, float]]):
        self.design = design
        names = [s.name for s in design.sources]
        self.zone_size = np.array([zone_size[s.zone] for s in design.sources], dtype=float).reshape(
            -1, 2
        )
        self.centred = np.zeros(len(names), bool)
        self.mirrors: list[tuple[int, int, int]] = []  # (derived, original, axis 0=u 1=v)
        for r in design.rules:
            if r.kind == "centred":
                for n in r.sources:
                    self.centred[names.index(n)] = True
            elif r.kind == "mirror":
                d, o = names.index(r.sources[0]), names.index(r.sources[1])
                self.mirrors.append((d, o, 0 if r.axis == "u" else 1))
        derived = {d for d, _, _ in self.mirrors}
        if len(derived) != len(self.mirrors):
            raise DesignError("a source can mirror only one original")
        self.vars: list[Variable] = []
        for i, s in enumerate(design.sources):
            if i in derived:
                continue
            w, h = self.zone_size[i]
            for name in s.free:
                if self.centred[i] and name in ("u1", "v1"):
                    continue
                if name in CORNERS:
                    hi = w if name[0] == "u" else h
                    if self.centred[i]:
                        hi *= 0.5
                    self.vars.append(Variable(i, name, 0.0, hi))
                elif name == "flux":
                    self.vars.append(Variable(i, name, *s.flux_range))
                else:
                    self.vars.append(Variable(i, name, 0.0, 1.0))
        # Arrays' zone sizes bound their corner variables; a caller that only lays out
        # the sources may leave them out.
        self.array_zone_size = np.array(
            [zone_size.get(a.zone, (np.nan, np.nan)) for a in design.arrays], dtype=float
        ).reshape(-1, 2)
        for i, a in enumerate(design.arrays):
            self.vars += _array_variables(i, a, self.array_zone_size[i])
        self.lo = np.array([v.lo for v in self.vars])
        self.hi = np.array([v.hi for v in self.vars])
        self.base_rect = np.array([s.rect for s in design.sources], dtype=float).reshape(-1, 4)
        self.base_flux = np.array([s.flux if s.flux is not None else 0.0 for s in design.sources])
        self.base_filter = np.array([s.filter for s in design.sources], dtype=float)

    @property
    def n(self) -> int:
        """Number of free variables."""
        return len(self.vars)

    def initial(self) -> np.ndarray:
        """x of the design as written (clipped to the bounds)."""
        x = np.empty(self.n)
        for q, v in enumerate(self.vars):
            if v.owner == "array":
                a = self.design.arrays[v.source]
                x[q] = a.rect[CORNERS.index(v.name)] if v.name in CORNERS else _array_value(a, v)
            elif v.name in CORNERS:
                x[q] = self.base_rect[v.source, CORNERS.index(v.name)]
            elif v.name == "flux":
                x[q] = self.base_flux[v.source]
            else:
                x[q] = self.base_filter[v.source]
        return np.clip(x, self.lo, self.hi)

    def decode(self, X: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Rectangles (m, S, 4), fluxes (m, S) and filters (m, S) for X (m, nvar)."""
        X = np.atleast_2d(X)
        m = X.shape[0]
        rect = np.repeat(self.base_rect[None], m, axis=0)
        flux = np.repeat(self.base_flux[None], m, axis=0)
        filt = np.repeat(self.base_filter[None], m, axis=0)
        for q, v in enumerate(self.vars):
            if v.owner == "array":
                continue
            if v.name in CORNERS:
                rect[:, v.source, CORNERS.index(v.name)] = X[:, q]
            elif v.name == "flux":
                flux[:, v.source] = X[:, q]
            else:
                filt[:, v.source] = X[:, q]
        for i in np.flatnonzero(self.centred):
            w, h = self.zone_size[i]
            rect[:, i, 2] = w - rect[:, i, 0]
            rect[:, i, 3] = h - rect[:, i, 1]
        for d, o, axis in self.mirrors:
            rect[:, d] = rect[:, o]
            flux[:, d], filt[:, d] = flux[:, o], filt[:, o]
            size_d, size_o = self.zone_size[d, axis], self.zone_size[o, axis]
            for c in (axis, axis + 2):
                rect[:, d, c] = size_d - rect[:, o, c] * (size_d / size_o)
        return rect, flux, filt

    def sources_at(self, x: np.ndarray) -> tuple[Source, ...]:
        """The design's sources with the parameters of x (nvar,) filled in and the tied
        rules applied: rectangles (m), filters, and fluxes (lm) of sources that have one."""
        rect, flux, filt = self.decode(np.asarray(x, dtype=float)[None])
        out = []
        for j, s in enumerate(self.design.sources):
            # Corners reported low to high (u0 <= u1, v0 <= v1): the same rectangle, in
            # the order people read (an optimiser or a mirror may swap them).
            u0, v0, u1, v1 = (float(c) for c in rect[0, j])
            kw = {
                "rect": (min(u0, u1), min(v0, v1), max(u0, u1), max(v0, v1)),
                "filter": float(filt[0, j]),
            }
            if s.flux is not None:
                kw["flux"] = float(flux[0, j])
            out.append(replace(s, **kw))
        return tuple(out)

    def decode_arrays(self, X: np.ndarray) -> ArrayLayout:
        """The luminaire arrays of X (m, nvar), whole-number variables rounded."""
        X = np.atleast_2d(X)
        m, arrays = X.shape[0], self.design.arrays
        base = np.array([a.rect for a in arrays], dtype=float).reshape(-1, 4)
        rect = np.repeat(base[None], m, axis=0)
        values = {
            key: np.repeat(np.array([float(getattr(a, key)) for a in arrays])[None], m, axis=0)
            for key in ("rows", "columns", "rotation", "dimming")
        }
        values["rotation"] = values["rotation"] / 90.0
        for q, v in enumerate(self.vars):
            if v.owner != "array":
                continue
            if v.name in CORNERS:
                rect[:, v.source, CORNERS.index(v.name)] = X[:, q]
            else:
                values[v.name][:, v.source] = X[:, q]
        whole = {}
        for key in ROUNDED:
            lo, hi = self._whole_bounds(key)
            whole[key] = np.clip(np.rint(values[key]), lo, hi).astype(np.int64)
        return ArrayLayout(
            rect,
            whole["rows"],
            whole["columns"],
            90 * whole["rotation"],
            values["dimming"],
        )

    def _whole_bounds(self, key: str) -> tuple[np.ndarray, np.ndarray]:
        arrays = self.design.arrays
        if key == "rotation":
            return np.zeros(len(arrays)), np.ones(len(arrays))
        rng = np.array([getattr(a, f"{key}_range") for a in arrays], dtype=float).reshape(-1, 2)
        return rng[:, 0], rng[:, 1]

    def arrays_at(self, x: np.ndarray) -> tuple[LuminaireArray, ...]:
        """The design's arrays with the parameters of x (nvar,) filled in."""
        lay = self.decode_arrays(np.asarray(x, dtype=float)[None])
        out = []
        for j, a in enumerate(self.design.arrays):
            u0, v0, u1, v1 = (float(c) for c in lay.rect[0, j])
            out.append(
                replace(
                    a,
                    rect=(min(u0, u1), min(v0, v1), max(u0, u1), max(v0, v1)),
                    rows=int(lay.rows[0, j]),
                    columns=int(lay.columns[0, j]),
                    rotation=int(lay.rotation[0, j]),
                    dimming=float(lay.dimming[0, j]),
                )
            )
        return tuple(out)


def _array_variables(i: int, a: LuminaireArray, size: np.ndarray) -> list[Variable]:
    """The free variables of array ``i`` in a zone of ``size`` (w, h) m."""
    out = []
    for name in a.free:
        if name in CORNERS and not np.all(np.isfinite(size)):
            raise DesignError(f"array {a.name!r}: the size of zone {a.zone!r} is not known")
        if name in CORNERS:
            lo, hi = 0.0, float(size[0] if name[0] == "u" else size[1])
        elif name in ("rows", "columns"):
            lo, hi = getattr(a, f"{name}_range")
            lo, hi = lo - HALF, hi + HALF
        elif name == "rotation":
            lo, hi = -HALF, 1 + HALF
        else:
            lo, hi = a.dimming_range
        out.append(Variable(i, name, float(lo), float(hi), "array"))
    return out


def _array_value(a: LuminaireArray, v: Variable) -> float:
    """x of array variable ``v`` for the array as written."""
    if v.name == "rotation":
        return a.rotation / 90.0
    return float(getattr(a, v.name))


def array_layout(arrays) -> ArrayLayout:
    """The layout (one candidate) of luminaire arrays as written."""
    arrays = tuple(arrays)
    return ArrayLayout(
        np.array([[a.rect for a in arrays]], dtype=float).reshape(1, -1, 4),
        np.array([[a.rows for a in arrays]], dtype=np.int64).reshape(1, -1),
        np.array([[a.columns for a in arrays]], dtype=np.int64).reshape(1, -1),
        np.array([[a.rotation for a in arrays]], dtype=np.int64).reshape(1, -1),
        np.array([[a.dimming for a in arrays]], dtype=float).reshape(1, -1),
    )
