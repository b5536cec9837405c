"""The unified glare rating (UGR) of CIE 117:1995 at an observer.

    UGR = 8 log10( 0.25 / Lb * sum_i L_i² omega_i / p_i² )

``Lb`` is the background luminance (cd/m²; CIE 117: Lb = E_ind / pi, E_ind the indirect
vertical illuminance at the eye), ``L_i`` a luminaire's luminance towards the eye
(cd/m²), ``omega_i`` the solid angle of its luminous opening seen from the eye (sr) and
``p_i`` the Guth position index of its place in the field of view.

- **Luminance**: the intensity towards the eye (the photometric table, the luminaire's
  aim, c0 and dimming) over the luminous opening projected on a plane across the line
  from the luminaire to the eye: the bottom face ``A cos(gamma)`` plus, where the file
  gives a luminous height, the sides ``h (w |cos C| + l |sin C|) sin(gamma)`` (a disc's
  side: ``h D sin(gamma)``). A file without a luminous opening (width and length 0) has
  no luminance: ``NoLuminousArea`` says so, nothing is guessed.
- **Position index**: Guth's formula (Luckiesh and Guth's data as fitted by Guth; the form
  Radiance's evalglare uses; CIE 117 tabulates the index in its Table 4.1), degrees,

      ln p = (35.2 - 0.31889 tau - 1.22 exp(-2 tau / 9)) 1e-3 sigma
             + (21 + 0.26667 tau - 0.002963 tau²) 1e-5 sigma²,

  sigma the angle between the line of sight and the direction of the luminaire, tau the
  angle between the vertical plane through the line of sight and the plane through the
  line of sight and the luminaire (tan tau = T / H). It smooths CIE 117's Table 4.1 (p by
  H/R and T/R): median 4.5% from its cells, at most 10.6% (tests/core/test_ugr.py).
- **Field limits**: a luminaire counts if it is in front of the eye (R > 0), no further
  sideways than T/R = 3 and no higher than the top of Table 4.1's defined cells (H/R at
  most 1.7 for T/R < 0.4, 1.8 for T/R < 0.9, else 1.9): the table's edges, beyond which
  CIE 117 gives no index. CIE 117 gives none below the line of sight either; a luminaire
  there is rated with |H| (a choice, stated here).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from lightinv_core.errors import LightInvError
from lightinv_core.luminaires.photometry import Photometry

TR_MAX = 3.0
"""Largest T/R of CIE 117's position-index table: luminaires further sideways are out."""
_HR_TOP = ((0.4, 1.7), (0.9, 1.8), (math.inf, 1.9))
"""(T/R below which, the largest H/R with a position index in Table 4.1)."""


class NoLuminousArea(LightInvError):
    """A photometric file without a luminous opening: its luminance is undefined."""


def background_luminance(indirect_vertical_lux: float) -> float:
    """CIE 117's background luminance Lb (cd/m²) from the indirect vertical illuminance
    at the eye (lux): Lb = E_ind / pi."""
    e = float(indirect_vertical_lux)
    if not (math.isfinite(e) and e > 0):
        raise LightInvError(f"indirect vertical illuminance must be > 0 lux, got {e!r}")
    return e / math.pi


def guth_index(sigma_deg, tau_deg) -> np.ndarray:
    """Guth position index p (CIE 117's formula, see the module) at the angles sigma and
    tau in degrees, broadcast like numpy."""
    s = np.asarray(sigma_deg, dtype=float)
    t = np.abs(np.asarray(tau_deg, dtype=float))
    ln_p = (35.2 - 0.31889 * t - 1.22 * np.exp(-2.0 * t / 9.0)) * 1e-3 * s + (
        21.0 + 0.26667 * t - 0.002963 * t * t
    ) * 1e-5 * s * s
    return np.exp(ln_p)


def position_index(h_over_r, t_over_r) -> np.ndarray:
    """Guth position index at CIE 117's table coordinates H/R (height above the line of
    sight over the distance along it) and T/R (sideways over along)."""
    h = np.abs(np.asarray(h_over_r, dtype=float))
    t = np.abs(np.asarray(t_over_r, dtype=float))
    sigma = np.degrees(np.arctan(np.hypot(h, t)))
    tau = np.degrees(np.arctan2(t, h))
    return guth_index(sigma, tau)


def in_field(h_over_r, t_over_r) -> np.ndarray:
    """Whether a luminaire at H/R, T/R (R > 0) is inside CIE 117's field (the module)."""
    h = np.abs(np.asarray(h_over_r, dtype=float))
    t = np.abs(np.asarray(t_over_r, dtype=float))
    top = np.select([t < lim for lim, _ in _HR_TOP], [hr for _, hr in _HR_TOP])
    return (t <= TR_MAX) & (h <= top + 1e-9)


def luminous_area(opening: Sequence[float]) -> float:
    """Area (m²) of the bottom face of a luminous opening (width, length, height) in
    LM-63's codes: a rectangle, or a circle/ellipse when width and length are negative."""
    w, length = float(opening[0]), float(opening[1])
    if w < 0 and length < 0:
        return math.pi * w * length / 4.0
    return abs(w) * abs(length)


def projected_area(opening: Sequence[float], c_deg, gamma_deg) -> np.ndarray:
    """Luminous area (m²) seen from (C, gamma) (degrees, as leaving the luminaire): the
    bottom face times cos(gamma) and, with a luminous height, the sides (the module)."""
    w, length = float(opening[0]), float(opening[1])
    h = abs(float(opening[2])) if len(opening) > 2 else 0.0
    c = np.radians(np.asarray(c_deg, dtype=float))
    g = np.radians(np.asarray(gamma_deg, dtype=float))
    bottom = luminous_area(opening) * np.maximum(np.cos(g), 0.0)
    if h == 0.0:
        return bottom
    if w < 0 and length < 0:  # a disc or ellipse: the width of its outline across the view
        across = np.hypot(length * np.sin(c), w * np.cos(c))
    else:
        across = abs(w) * np.abs(np.cos(c)) + abs(length) * np.abs(np.sin(c))
    return bottom + h * across * np.sin(g)


def luminance(ph: Photometry, c_deg, gamma_deg) -> np.ndarray:
    """Mean luminance (cd/m²) of the luminous opening seen from (C, gamma): intensity
    over projected area. Raises NoLuminousArea if the file gives no opening."""
    area = projected_area(ph.opening, c_deg, gamma_deg)
    if luminous_area(ph.opening) <= 0.0:
        raise NoLuminousArea(
            f"{ph.source or ph.name or 'photometry'}: the file gives no luminous opening "
            "(width and length 0), so its luminance and UGR are undefined; use a file "
            "that states the luminous area"
        )
    intensity = ph.intensity(c_deg, gamma_deg)
    return np.divide(intensity, area, out=np.zeros_like(area), where=area > 0)


@dataclass(frozen=True)
class GlareTerms:
    """Each luminaire's part of the UGR sum at one observer (arrays, one per luminaire):
    luminance L (cd/m²), solid angle omega (sr), position index p (nan when out),
    whether it ``counts`` (in the field of view and lit towards the eye)."""

    luminance: np.ndarray
    omega: np.ndarray
    p: np.ndarray
    counts: np.ndarray

    @property
    def total(self) -> float:
        """sum L² omega / p² over the luminaires that count (cd²/m⁴ sr)."""
        k = self.counts
        return float(np.sum(self.luminance[k] ** 2 * self.omega[k] / self.p[k] ** 2))


def _view_frame(view_direction) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    f = np.asarray(view_direction, dtype=float).reshape(3)
    norm = float(np.linalg.norm(f))
    if not (math.isfinite(norm) and norm > 0):
        raise LightInvError(f"view direction must be a non-zero vector, got {f.tolist()}")
    f = f / norm
    up = np.array([0.0, 0.0, 1.0]) - f[2] * f
    if np.linalg.norm(up) < 1e-6:
        raise LightInvError("the view direction is vertical: UGR needs a line of sight")
    up /= np.linalg.norm(up)
    return f, up, np.cross(f, up)


def glare_terms(observer, view_direction, luminaires: Sequence) -> GlareTerms:
    """The UGR sum's terms of ``luminaires`` (``PlacedLuminaire``s: position, aim, c0,
    dimming, photometry) for an eye at ``observer`` (m) looking along
    ``view_direction``. Each luminaire is seen at its photometric centre."""
    eye = np.asarray(observer, dtype=float).reshape(3)
    fwd, up, side = _view_frame(view_direction)
    n = len(luminaires)
    out = {k: np.zeros(n) for k in ("L", "omega")}
    p = np.full(n, np.nan)
    counts = np.zeros(n, dtype=bool)
    for i, lum in enumerate(luminaires):
        v = np.asarray(lum.position, dtype=float) - eye
        dist = float(np.linalg.norm(v))
        r, h, t = float(v @ fwd), float(v @ up), float(v @ side)
        if dist <= 0 or r <= 0 or not in_field(h / r, t / r):
            continue
        to_eye = -v / dist
        c, gamma = lum.angles(to_eye)
        area = float(projected_area(lum.photometry.opening, c, gamma))
        lum_l = float(lum.dimming * luminance(lum.photometry, c, gamma))
        out["L"][i], out["omega"][i] = lum_l, area / dist**2
        p[i] = float(position_index(h / r, t / r))
        counts[i] = lum_l > 0 and area > 0
    return GlareTerms(out["L"], out["omega"], p, counts)


def ugr_from_sum(total: float, background: float) -> float:
    """8 log10(0.25 / Lb * total); -inf when no luminaire is in view (total 0)."""
    if not (math.isfinite(background) and background > 0):
        raise LightInvError(f"background luminance must be > 0 cd/m², got {background!r}")
    if total <= 0:
        return -math.inf
    return 8.0 * math.log10(0.25 / background * total)


def ugr(observer, view_direction, luminaires: Sequence, background_luminance: float) -> float:
    """CIE 117 UGR for an eye at ``observer`` (m) looking along ``view_direction``, from
    ``luminaires`` (``PlacedLuminaire``s) on a background of ``background_luminance``
    (cd/m², see ``background_luminance()``); -inf if no luminaire is in view."""
    terms = glare_terms(observer, view_direction, luminaires)
    return ugr_from_sum(terms.total, float(background_luminance))
