"""The optimisation variables of a design and their decoding into source parameters.

x is a flat vector of the free variables; ``decode`` turns a stack of them
(m, nvar) into per-candidate rectangles (m, S, 4), fluxes and filters (m, S),
applying the tied rules: a ``centred`` source's second corner mirrors its first
through the zone centre, and a ``mirror`` source copies its original flipped
along a zone axis. Tied values are never variables.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from lightinv_core.design.model import CORNERS, Design, DesignError, Source


@dataclass(frozen=True)
class Variable:
    """One free variable: ``source`` index, ``name`` (u0, v0, u1, v1, flux, filter), bounds."""

    source: int
    name: str
    lo: float
    hi: float


class Variables:
    """Layout of x for a design whose zones have the given (width, height) in metres."""

    def __init__(self, design: Design, zone_size: dict[str, tuple[float, float]]):
        self.design = design
        names = [s.name for s in design.sources]
        self.zone_size = np.array([zone_size[s.zone] for s in design.sources])
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
        self.lo = np.array([v.lo for v in self.vars])
        self.hi = np.array([v.hi for v in self.vars])
        self.base_rect = np.array([s.rect for s in design.sources], dtype=float)
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
            if v.name in CORNERS:
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
