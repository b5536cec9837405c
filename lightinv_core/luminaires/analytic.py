"""Analytic intensity distributions as photometric tables, scaled to a luminaire flux.

All are type C, gamma from the nadir, intensities in cd, normalised in closed form to
the requested flux Phi (lm); the tables' own flux (``Photometry.flux``, exact for the
interpolated table) differs from Phi by the sampling error only (< 0.1% at the default
2.5 degree step). Each is treated as absolute photometry of an LED luminaire whose
rated "lamp" flux is the luminaire flux (light output ratio 100%).

- ``downlight``: I = I0 cos^n(gamma) for gamma <= 90, 0 above; Phi = 2 pi I0 / (n + 1).
- ``lambertian_panel``: the downlight with n = 1; Phi = pi I0.
- ``batwing_linear``: I = I0 cos^2(gamma) (1 + a sin^2(C) sin^2(gamma)) for gamma <= 90:
  cos^2 along the luminaire (C0 plane), a batwing across it (C90 plane) peaking at
  gamma_p where sin^2(gamma_p) = (a - 1) / (2a), blended by sin^2(C) in between;
  Phi = (2 pi / 3) I0 (1 + a / 5).
- ``direct_indirect_linear``: the batwing below (share 1 - u of the flux) and a
  Lambertian uplight above, I = I_up cos(180 - gamma) for gamma >= 90 (share u);
  each part scaled in closed form: Phi_down = (2 pi / 3) I0 (1 + a / 5), Phi_up = pi I_up.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from lightinv_core.errors import PhotometryError
from lightinv_core.luminaires.photometry import Photometry

MAKER = "LightInv (analytic)"


def _check(name: str, value: float | None, lo: float, hi: float, *, optional: bool = False) -> None:
    if value is None and optional:
        return
    ok = isinstance(value, int | float) and not isinstance(value, bool) and math.isfinite(value)
    if not ok or not lo <= float(value) <= hi:  # type: ignore[arg-type]
        raise PhotometryError(
            f"{name} = {value!r} is out of range; give a number in {lo:g}..{hi:g}"
        )


def _angles(step: float, span: float) -> np.ndarray:
    """0..span (excluded when span is 360) in equal steps that divide it."""
    _check("angle step (deg)", step, 0.1, 45.0)
    n = round(span / step)
    if abs(n * step - span) > 1e-9:
        raise PhotometryError(f"angle step {step:g} does not divide {span:g}; choose one that does")
    if span >= 360.0:
        return np.arange(n) * (360.0 / n)
    return np.linspace(0.0, span, n + 1)


def tabulate(
    func: Callable[[np.ndarray, np.ndarray], np.ndarray],
    c_angles,
    gamma_angles,
    *,
    lumens: float | None = None,
    watts: float | None = None,
    size_m: tuple[float, float, float] = (0.0, 0.0, 0.0),
    name: str = "",
    catalogue_number: str = "",
) -> Photometry:
    """A table of ``func(C_deg, gamma_deg)`` (cd, broadcast over a C x gamma grid); with
    ``lumens``, scaled numerically so that its flux is exactly that (lm)."""
    c = np.asarray(c_angles, dtype=float)
    g = np.asarray(gamma_angles, dtype=float)
    cd = np.broadcast_to(np.asarray(func(c[:, None], g[None, :]), dtype=float), (c.size, g.size))
    ph = _photometry(c, g, np.array(cd), None, watts, size_m, name, catalogue_number)
    if lumens is None:
        return ph
    _check("lumens", lumens, 1e-6, 1e10)
    total = ph.flux()
    if total <= 0:
        raise PhotometryError(
            f"{name or 'distribution'}: emits no light; cannot scale it to a flux"
        )
    return _photometry(
        c, g, ph.candela * (lumens / total), lumens, watts, size_m, name, catalogue_number
    )


def _photometry(c, g, cd, lumens, watts, size_m, name, catalogue_number) -> Photometry:
    _check("watts", watts, 1e-6, 1e9, optional=True)
    for k, x in enumerate(size_m):
        _check(f"size_m[{k}]", x, 0.0, 1000.0)
    return Photometry(
        kind="C",
        c_angles=c,
        gamma_angles=g,
        candela=cd,
        lamp_lumens=lumens,
        input_watts=None if watts is None else float(watts),
        opening=(float(size_m[0]), float(size_m[1]), float(size_m[2])),
        name=name,
        manufacturer=MAKER,
        catalogue_number=catalogue_number,
        lamp="LED" if lumens is not None else "",
    )


def _cos_lower(g_deg: np.ndarray) -> np.ndarray:
    """cos(gamma) on the lower hemisphere, exactly 0 at 90 degrees and above."""
    cos = np.cos(np.radians(g_deg))
    return np.where(g_deg < 90.0, np.clip(cos, 0.0, 1.0), 0.0)


def downlight(
    lumens: float,
    n: float = 4.0,
    *,
    watts: float | None = None,
    size_m: tuple[float, float, float] = (0.15, 0.15, 0.0),
    gamma_step_deg: float = 2.5,
    name: str = "",
    catalogue_number: str = "",
) -> Photometry:
    """Rotationally symmetric I = I0 cos^n(gamma) below the luminaire, Phi = ``lumens``
    (lm), I0 = (n + 1) Phi / (2 pi) cd; ``size_m`` = opening (width, length, height), m."""
    _check("lumens", lumens, 1e-6, 1e10)
    _check("n", n, 0.0, 1000.0)
    g = _angles(gamma_step_deg, 90.0)
    i0 = (n + 1.0) * lumens / (2.0 * math.pi)
    cd = i0 * _cos_lower(g)[None, :] ** n
    if n == 0:
        cd = np.full((1, g.size), i0)  # 0**0: the hemisphere uniformly, cos(90) included
    label = name or f"Downlight {lumens:g} lm cos^{n:g}"
    return _photometry(
        np.array([0.0]), g, cd, float(lumens), watts, size_m, label, catalogue_number
    )


def lambertian_panel(
    lumens: float,
    *,
    watts: float | None = None,
    size_m: tuple[float, float, float] = (0.6, 0.6, 0.0),
    gamma_step_deg: float = 2.5,
    name: str = "",
    catalogue_number: str = "",
) -> Photometry:
    """A Lambertian emitter facing down: I = I0 cos(gamma), I0 = Phi / pi cd."""
    label = name or f"Lambertian panel {lumens:g} lm"
    return downlight(
        lumens,
        1.0,
        watts=watts,
        size_m=size_m,
        gamma_step_deg=gamma_step_deg,
        name=label,
        catalogue_number=catalogue_number,
    )


def batwing_coefficient(peak_deg: float) -> float:
    """``a`` of batwing_linear whose C90 plane peaks at ``peak_deg`` (10..40 degrees)."""
    _check("peak_deg", peak_deg, 10.0, 40.0)
    s = math.sin(math.radians(peak_deg)) ** 2
    return 1.0 / (1.0 - 2.0 * s)


def batwing_linear(
    lumens: float,
    *,
    watts: float | None = None,
    size_m: tuple[float, float, float] = (0.15, 1.2, 0.0),
    peak_deg: float = 35.0,
    c_step_deg: float = 15.0,
    gamma_step_deg: float = 2.5,
    name: str = "",
    catalogue_number: str = "",
) -> Photometry:
    """A linear luminaire (length along C0): I = I0 cos^2(gamma) (1 + a sin^2 C sin^2
    gamma), a wide batwing across it peaking at ``peak_deg`` in the C90 plane,
    I0 = 3 Phi / (2 pi (1 + a / 5)) cd (module docstring)."""
    _check("lumens", lumens, 1e-6, 1e10)
    a = batwing_coefficient(peak_deg)
    c = _angles(c_step_deg, 360.0)
    g = _angles(gamma_step_deg, 90.0)
    i0 = 3.0 * lumens / (2.0 * math.pi * (1.0 + a / 5.0))
    # sin^2 C from the angle folded into 0..90, so mirrored planes are bit-identical.
    folded = np.radians(np.minimum.reduce([c % 180.0, 180.0 - c % 180.0]))
    sin2c = np.sin(folded)[:, None] ** 2
    sin2g = np.sin(np.radians(g))[None, :] ** 2
    cd = i0 * _cos_lower(g)[None, :] ** 2 * (1.0 + a * sin2c * sin2g)
    label = name or f"Batwing linear {lumens:g} lm"
    return _photometry(c, g, cd, float(lumens), watts, size_m, label, catalogue_number)


def direct_indirect_linear(
    lumens: float,
    up_share: float = 0.3,
    *,
    watts: float | None = None,
    size_m: tuple[float, float, float] = (0.2, 1.5, 0.0),
    peak_deg: float = 30.0,
    c_step_deg: float = 15.0,
    gamma_step_deg: float = 2.5,
    name: str = "",
    catalogue_number: str = "",
) -> Photometry:
    """A suspended linear direct/indirect luminaire (length along C0): ``batwing_linear``
    below with flux (1 - ``up_share``) Phi and a Lambertian uplight of ``up_share`` Phi
    above, I_up = up_share Phi / pi cd at the zenith (module docstring)."""
    _check("lumens", lumens, 1e-6, 1e10)
    _check("up_share", up_share, 0.0, 1.0)
    down = batwing_linear(
        (1.0 - up_share) * lumens if up_share < 1.0 else 1.0,
        size_m=size_m,
        peak_deg=peak_deg,
        c_step_deg=c_step_deg,
        gamma_step_deg=gamma_step_deg,
    )
    g = _angles(gamma_step_deg, 180.0)
    n_down = down.gamma_angles.size
    cd = np.zeros((down.c_angles.size, g.size))
    if up_share < 1.0:
        cd[:, :n_down] = down.candela
    # Above the horizontal: cos(180 - gamma), exactly 0 at 90 (the batwing is 0 there too).
    up = np.clip(-np.cos(np.radians(g)), 0.0, 1.0)
    up[g <= 90.0] = 0.0
    cd += (up_share * lumens / math.pi) * up[None, :]
    label = name or f"Direct/indirect linear {lumens:g} lm"
    return _photometry(down.c_angles, g, cd, float(lumens), watts, size_m, label, catalogue_number)
