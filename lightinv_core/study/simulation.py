"""A forward simulation of a scene: ``simulate(spec) -> SimulationResult``.

Groups emit given fluxes, photometric luminaires shine, the CIE overcast design sky
lights the glazing groups, and a weather year gives annual daylight and the dimming
energy on a work plane. Everything goes through the reference solver (exact sparse
form factors, ``transport``), except plain group emission on a large scene, which the
low-rank operator (``light.LightModel``) evaluates (``method="lrr"``, or ``"auto"``
above ``AUTO_LRR_PATCHES``). The annual year and its statistics are the optimiser's
(``study.annual``).
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np
import scipy.sparse as sp

from lightinv_core.design.model import Daylight
from lightinv_core.errors import LightInvError
from lightinv_core.kinds import Edition
from lightinv_core.light.model import LightModel
from lightinv_core.luminaires.photometry import light_warnings
from lightinv_core.operator.cache import get_operator
from lightinv_core.operator.settings import OperatorSettings
from lightinv_core.scene.model import Scene
from lightinv_core.scene.patches import Patches, mesh_patches
from lightinv_core.study.annual import GridYear, grid_year, with_dimming
from lightinv_core.study.clear_light import (
    clear_annual,
    clear_dimming,
    clear_moment,
    moment_sky,
    outside_lux,
    split_glazing,
)
from lightinv_core.study.clear_metrics import blinds
from lightinv_core.study.control_groups import DEFAULT_GROUP, group_dimming
from lightinv_core.transport.annual import orientation_coefficients, orientations
from lightinv_core.transport.clear_glazing import clear_glass, clear_glass_warnings
from lightinv_core.transport.daylight_coefficients import ClearDaylight
from lightinv_core.transport.escape import luminaire_escape_warnings
from lightinv_core.transport.formfactors import (
    DEFAULT_RAYS,
    check_formfactor_memory,
    escape_warning,
    form_factor_matrix,
    lost_fraction,
)
from lightinv_core.transport.glazing import black_inside, glazing_emission
from lightinv_core.transport.luminaires import PlacedLuminaire, direct_at_points
from lightinv_core.transport.photometry import group_illuminance
from lightinv_core.transport.point_sets import PointSet
from lightinv_core.transport.raycast import RayCaster
from lightinv_core.transport.receivers import receiver_factors
from lightinv_core.transport.scene_light import SceneLight, light_grid, light_scene
from lightinv_core.transport.solver import group_emission
from lightinv_core.transport.workplane import (
    GRID_RULES,
    Grid,
    WorkPlane,
    grid_statistics,
    work_plane_grid,
)

AUTO_LRR_PATCHES = 3000
"""Above this many patches, ``method="auto"`` evaluates plain group emission with the
low-rank operator instead of the reference solver."""

DESIGN_SKY = "cie-overcast"


def luminaire_watts(lum: PlacedLuminaire) -> float | None:
    """Electric power (W) of a luminaire at its set dimming, power taken proportional to
    output (a linear-dimming driver, as the optimiser's); None when its file gives no
    input watts."""
    rated = lum.photometry.input_watts
    return None if rated is None else rated * lum.dimming


def installed_watts(luminaires) -> float:
    """Electric power (W) of luminaires at their set dimming (unknown watts count 0)."""
    return float(sum(luminaire_watts(x) or 0.0 for x in luminaires))


@dataclass(frozen=True)
class SimulationSpec:
    """What to simulate.

    ``emit``: group -> luminous flux (lm) emitted uniformly over its area;
    ``luminaires``: photometric luminaires; ``glazing``: group -> visible transmittance
    of glazing, diffusing unless ``glazing_kinds`` names it ``"clear"``, lit by ``sky``
    (``"cie-overcast"``: ``exterior_lux`` horizontal outside; ``"cie-clear"``: the
    sky's diffuse ``exterior_lux`` and the ``sun`` at (altitude, compass azimuth) deg
    giving ``sun_lux`` at normal incidence) or by ``hour`` (0-based) of the weather
    year, the scene's +y at compass ``north_deg``, and/or by the weather year
    (``annual.weather``; through clear glazing with glare at ``views`` (x, y, z, dx,
    dy, dz) and EN 17037 sunlight exposure at ``sunlight_point`` on
    ``sunlight_date`` (month, day), the sun counted above ``sunlight_min_altitude``
    deg; the sky in Reinhart MF:``sky_mf`` patches); ``workplane``: an
    EN 12464-1 grid read-out by the grid rule of ``edition``; ``points``: free receiver
    points (a ``PointSet``: a CSV's rows, ``--points``); ``annual``: the weather file,
    north bearing, occupancy and ground reflectance of the year and the luminaires'
    daylight-linked dimming (target lux, lowest level, standby watts): a ``Daylight``.
    ``rays`` per patch and ``seed`` of the form factors; ``method`` "auto",
    "reference" or "lrr";
    ``operator``, ``use_cache`` and ``scheduler`` for the low-rank operator.
    """

    scene: Scene
    emit: dict[str, float] = field(default_factory=dict)
    luminaires: tuple[PlacedLuminaire, ...] = ()
    glazing: dict[str, float] = field(default_factory=dict)
    sky: str | None = None
    exterior_lux: float = 10000.0
    glazing_kinds: dict[str, str] = field(default_factory=dict)
    sun: tuple[float, float] | None = None
    sun_lux: float = 80000.0
    hour: int | None = None
    north_deg: float = 0.0
    views: tuple[tuple[float, ...], ...] = ()
    sunlight_point: tuple[float, float, float] | None = None
    sunlight_date: tuple[int, int] = (3, 21)
    sunlight_min_altitude: float | None = None
    sky_mf: int = 1
    sensors: dict[str, tuple[float, float, float, float]] = field(default_factory=dict)
    group_modes: dict[str, str] = field(default_factory=dict)
    group_targets: dict[str, float] = field(default_factory=dict)
    group_bands: dict[str, float] = field(default_factory=dict)
    ground_reflectance: float = 0.2
    workplane: WorkPlane | None = None
    edition: str = Edition.EN12464_2011
    points: PointSet | None = None
    annual: Daylight | None = None
    rays: int = DEFAULT_RAYS
    seed: int = 0
    method: str = "auto"
    operator: OperatorSettings | None = None
    use_cache: bool = True
    scheduler: str | None = None

    @property
    def plain(self) -> bool:
        """Only groups emit and nothing reads a work plane: the operator can do it."""
        return (
            not self.luminaires
            and self.workplane is None
            and self.points is None
            and not self.daylit
        )

    @property
    def daylit_now(self) -> bool:
        """A moment's sky (``sky`` or ``hour``) lights the glazing in the static result."""
        return bool(self.sky) or self.hour is not None

    @property
    def daylit(self) -> bool:
        """A sky or a weather year lights the glazing."""
        return bool(self.sky) or self.annual is not None or self.hour is not None


@dataclass
class SimulationResult:
    """What a simulation found.

    ``patches`` as meshed and ``lit`` as lit (glazing black inside), emission ``E``
    (lm/m²), radiosity ``B`` and illuminance ``H`` per patch; ``groups``: per group
    min / average / max lux (and ``avg_df`` %, under a design sky); ``light``: the
    reference solve's flux budget (None with the operator); ``grid``, ``grid_lux`` and
    ``grid_stats`` the work plane's; ``df_grid`` and ``df_patches`` the daylight factor
    (%) under a design sky; ``annual`` the weather year on the grid (``clear_year``
    its hours through clear glazing, ``study.clear_year``); ``sky_label`` names the
    moment's sky. ``warnings`` about
    the result (light escaping), ``photometry_warnings`` about the luminaires' files,
    ``weather_notes`` about the weather file, ``timings`` in seconds;
    ``operator`` the low-rank operator's facts (method "lrr").
    """

    scene: Scene
    patches: Patches
    lit: Patches
    method: str
    E: np.ndarray
    B: np.ndarray
    H: np.ndarray
    groups: list[dict]
    light: SceneLight | None = None
    lost_fraction: float | None = None
    grid: Grid | None = None
    grid_lux: np.ndarray | None = None
    grid_stats: dict | None = None
    points_lux: np.ndarray | None = None
    df_grid: np.ndarray | None = None
    df_patches: np.ndarray | None = None
    annual: GridYear | None = None
    sky_label: str | None = None
    clear_year: object = None
    clear_annual: dict | None = None
    clear_columns: dict | None = None
    clear_dimming: tuple | None = None  # (climate.metrics.Dimming, mean electric lux)
    control_groups: list | None = None
    control_total: dict | None = None
    warnings: list[str] = field(default_factory=list)
    photometry_warnings: list[str] = field(default_factory=list)
    weather_notes: list[str] = field(default_factory=list)
    timings: dict[str, float] = field(default_factory=dict)
    operator: dict = field(default_factory=dict)


Progress = Callable[[float], None] | None


def simulate(
    spec: SimulationSpec,
    formfactor_progress: Progress = None,
    operator_progress: Progress = None,
    warn: Callable[[str], None] | None = None,
) -> SimulationResult:
    """Simulate ``spec`` (see the module); ``*_progress(fraction)`` report the form
    factors or the operator's build, ``warn`` the operator cache's notes."""
    p = mesh_patches(spec.scene)
    E = group_emission(p, dict(spec.emit))
    method = spec.method
    if method == "lrr" and not spec.plain:
        raise LightInvError(
            "luminaires, skies and work planes are simulated with the reference solver; "
            "leave out --method lrr (or use --method reference)"
        )
    if method == "auto":
        method = "lrr" if spec.plain and p.n > AUTO_LRR_PATCHES else "reference"
    if method == "lrr":
        return _simulate_lrr(spec, p, E, operator_progress, warn)
    return _simulate_reference(spec, p, E, formfactor_progress)


def _simulate_reference(spec: SimulationSpec, p: Patches, E, progress) -> SimulationResult:
    check_formfactor_memory(p, spec.rays)
    luminaires = list(spec.luminaires)
    diffusing, clear = split_glazing(dict(spec.glazing), dict(spec.glazing_kinds))
    # The overcast sky of diffusing glazing alone is the closed-form one (transport.glazing).
    plain = not clear and spec.sky in (None, "cie-overcast") and spec.hour is None
    sky = None if plain else moment_sky(spec)
    north = spec.annual.north_deg if spec.annual is not None else spec.north_deg
    t0 = time.perf_counter()
    caster = RayCaster(p)
    F = form_factor_matrix(p, spec.rays, seed=spec.seed, progress=progress, caster=caster)
    t1 = time.perf_counter()
    lit = p
    if diffusing:  # black inside; it emits only under a moment's sky
        overcast = spec.sky == "cie-overcast"
        lux = spec.exterior_lux if overcast else 0.0
        outside = None if overcast or sky is None else outside_lux(sky, north)
        glass, lit = glazing_emission(p, diffusing, lux, spec.ground_reflectance, outside)
        E = E + glass
    lit = black_inside(lit, clear)
    light = light_scene(lit, F, caster, E, luminaires, seed=spec.seed)
    grid = factors = clear_light = None
    if spec.workplane is not None:
        grid = work_plane_grid(p, caster, spec.workplane, GRID_RULES[spec.edition])
        factors = receiver_factors(grid.points, grid.normals, caster, p.n, spec.rays, spec.seed)
    if clear:
        pts = np.zeros((0, 3)) if grid is None else grid.points
        nrm = np.zeros((0, 3)) if grid is None else grid.normals
        fac = sp.csr_matrix((0, p.n)) if factors is None else factors
        clear_light = ClearDaylight(lit, F, caster, clear_glass(lit, clear), pts, nrm, fac)
    clear_points = None
    if clear_light is not None and sky is not None:
        first, room, clear_points = clear_moment(clear_light, sky, north)
        # The light through the clear glass enters the flux budget as emitted light.
        light = replace(
            light,
            H=light.H + room,
            B=light.B + lit.rho * room,
            emitted_lm=light.emitted_lm + float(first @ lit.area),
            absorbed_lm=light.absorbed_lm + float(((1.0 - lit.rho) * room) @ lit.area),
        )
    t2 = time.perf_counter()
    lost = lost_fraction(F, p)
    warnings = [w for w in [escape_warning(lost)] if w]
    warnings += clear_glass_warnings(clear)
    warnings += luminaire_escape_warnings(luminaires, caster)
    # Daylight factor (%): illuminance over the unobstructed exterior horizontal one.
    df = spec.sky == "cie-overcast" and spec.exterior_lux > 0
    result = SimulationResult(
        spec.scene, p, lit, "reference", E, light.B, light.H, group_illuminance(p, light.H)
    )
    result.light, result.lost_fraction, result.warnings = light, lost, warnings
    result.sky_label = None if sky is None else sky.label
    result.timings = {"formfactor_seconds": t1 - t0, "solve_seconds": t2 - t1}
    if df:
        result.df_patches = 100.0 * light.H / spec.exterior_lux
        for s in result.groups:
            s["avg_df"] = 100.0 * s["avg_lux"] / spec.exterior_lux
    if spec.points is not None:
        result.points_lux = points_light(spec, p, caster, light)
    if grid is not None:
        moment = (grid, factors, clear_points, clear_light, diffusing)
        _read_workplane(spec, result, F, caster, light, df, moment)
    result.photometry_warnings = list(light_warnings(x.photometry for x in luminaires))
    return result


def points_light(spec: SimulationSpec, p: Patches, caster, light) -> np.ndarray:
    """Illuminance (lux) at the spec's free points: each luminaire's photometry plus the
    patches' light by the exact point factors."""
    ps = spec.points
    factors = receiver_factors(ps.points, ps.normals, caster, p.n, spec.rays, spec.seed)
    direct = direct_at_points(ps.points, ps.normals, list(spec.luminaires), caster)
    return ps.values(direct + factors @ light.B)


def _read_workplane(spec, result: SimulationResult, F, caster, light, df: bool, moment) -> None:
    """The work plane's light, daylight factor and annual year."""
    grid, factors, clear_points, clear_light, diffusing = moment
    lit, luminaires = result.lit, list(spec.luminaires)
    grid_light = light_grid(grid, light, caster, luminaires, spec.rays, factors=factors)
    lux = grid_light.lux if clear_points is None else grid_light.lux + clear_points
    result.grid, result.grid_lux = grid, lux
    result.grid_stats = grid_statistics(lux)
    if df:
        result.df_grid = 100.0 * lux / spec.exterior_lux
    if spec.annual is None:
        return
    orients = orientations(lit, diffusing)
    year = None
    if orients or clear_light is None:
        coefficients = orientation_coefficients(lit, F, caster, orients, grid, factors)
        year = grid_year(spec.annual, orients, coefficients)
    if clear_light is not None:
        got = clear_annual(spec, clear_light, orients, year)
        result.clear_year, result.clear_annual, result.clear_columns = got
    days = year.year if clear_light is None else result.clear_year.year
    source = Path(days.source).name
    result.weather_notes = [f"weather {source}: {n}" for n in days.weather.get("notes", [])]
    if luminaires:
        if not spec.emit and not spec.daylit_now:
            electric = grid_light.lux  # the grid's light is the luminaires' alone
        else:
            alone = light_scene(lit, F, caster, np.zeros(lit.n), luminaires, seed=spec.seed)
            electric = light_grid(grid, alone, caster, luminaires, spec.rays, factors=factors).lux
        plane = spec.workplane
        floor = float(lit.area[lit.group_index(plane.group)].sum())
        watts = installed_watts(luminaires)
        if clear_light is None:
            year = with_dimming(year, electric, watts, floor, spec.annual)
        else:
            dim = clear_dimming(result.clear_year, electric, watts, floor, spec.annual)
            result.clear_dimming = (dim, float(np.mean(electric)))
        groups = {x.control or DEFAULT_GROUP for x in luminaires}
        if spec.sensors or spec.group_modes or len(groups) > 1:
            scene = (lit, F, caster, grid, factors)
            _control_groups(spec, result, scene, year, days, floor)
    # With clear glazing the year's figures are the clear year's (diffusing groups
    # included); the diffusing groups' own GridYear would tell only part of the light.
    result.annual = year if clear_light is None else None


def _control_groups(spec, result: SimulationResult, scene, year, days, floor: float) -> None:
    """Each control group's dimming on its own sensor region (``study.control_groups``):
    the daylight of the diffusing ``year`` (a ``GridYear``) or of the clear year, over
    the hours of ``days`` (a ``DaylightYear``)."""
    lit, F, caster, grid, factors = scene
    by_group: dict[str, list] = {}
    for x in spec.luminaires:
        by_group.setdefault(x.control or DEFAULT_GROUP, []).append(x)
    electric, watts, counts = {}, {}, {}
    for name, members in by_group.items():
        alone = light_scene(lit, F, caster, np.zeros(lit.n), members, seed=spec.seed)
        electric[name] = light_grid(grid, alone, caster, members, spec.rays, factors=factors).lux
        watts[name], counts[name] = installed_watts(members), len(members)
    if result.clear_year is not None:
        cy = result.clear_year
        daylight = cy.total(blinds(cy))[:, cy.occupied]
    else:
        daylight = year.lux
    groups, total = group_dimming(
        daylight,
        grid.points,
        electric,
        watts,
        counts,
        dict(spec.sensors),
        spec.annual,
        floor,
        days.every.shape[1],
        modes=dict(spec.group_modes),
        targets=dict(spec.group_targets),
        bands=dict(spec.group_bands),
        starts=days.day_starts,
    )
    result.control_groups, result.control_total = groups, total


def _simulate_lrr(spec: SimulationSpec, p: Patches, E, progress, warn) -> SimulationResult:
    settings = spec.operator or OperatorSettings(rays=spec.rays, seed=spec.seed)
    t0 = time.perf_counter()
    got = get_operator(
        p,
        settings,
        use_cache=spec.use_cache,
        progress=progress,
        warn=warn,
        scheduler=spec.scheduler,
    )
    t1 = time.perf_counter()
    lit_field = LightModel(spec.scene, p, got.operator).emission_field(E)
    t2 = time.perf_counter()
    H, B = lit_field.illuminance, lit_field.radiosity
    zone = got.operator.zone_patches
    emitted = float(E @ p.area)
    result = SimulationResult(spec.scene, p, p, "lrr", E, B, H, group_illuminance(p, H))
    result.timings = {"precompute_seconds": t1 - t0, "solve_seconds": t2 - t1}
    result.operator = {
        "k": got.operator.k,
        "from_cache": got.from_cache,
        "cache_path": str(got.path) if got.path else None,
        "estimated_rel_error": got.operator.info["estimated_rel_error"],
        "emitted_lm": emitted,
        "emitted_outside_zones_lm": emitted - float(E[zone] @ p.area[zone]),
    }
    return result
