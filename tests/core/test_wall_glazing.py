"""Side windows as daylight zones (issue #29, item 8): a window (glazing) zone goes on
any planar face, a wall's included, where a skylight zone goes only overhead; its light
is the sky and ground on its own plane, checked against formulas independent of the
code: the CIE overcast sky's closed form on a vertical plane, and pvlib's own Perez
transposition of the weather year for a vertical south-facing plane."""

from __future__ import annotations

import math

import numpy as np
import pytest

from lightinv_core.editing import DocumentModel
from lightinv_core.editing.project_file import obj_project
from lightinv_core.errors import DesignError
from lightinv_core.scene.edits import ZoneEdit
from lightinv_core.sources.types import ANY_FACE, source_type, surface_class
from tests.core.test_zone_on_cut_surface import write_room

SOUTH = (5.0, 0.0, 1.6)
"""The middle of the window on the south wall (y = 0, facing +y into the room)."""


def nearest(doc: DocumentModel, group: str, point) -> int:
    ids = doc.patches.group_index(group)
    return int(ids[np.argmin(np.linalg.norm(doc.patches.centroid[ids] - point, axis=1))])


@pytest.fixture
def doc(tmp_path) -> DocumentModel:
    d = DocumentModel()
    d.set_project(obj_project(write_room(tmp_path), resolution=0.5))
    return d


def window_on_south_wall(doc: DocumentModel, width=2.0, height=1.2) -> ZoneEdit:
    """A window zone drawn looking at the south wall from the middle of the room."""
    seen = nearest(doc, "walls", SOUTH)
    surface, rect = doc.zone_surface("window", (5.0, 3.5, 1.6), (0.0, -1.0, 0.0), seen)
    eu, ev = rect.u / np.linalg.norm(rect.u), rect.v / np.linalg.norm(rect.v)
    c = np.array(SOUTH) - rect.origin
    # The wall's u, v may run either way: half the size along each, in its own axes.
    hu = 0.5 * (width * abs(eu[0]) + height * abs(eu[2]))
    hv = 0.5 * (width * abs(ev[0]) + height * abs(ev[2]))
    u, v = float(c @ eu), float(c @ ev)
    edit = ZoneEdit("Win", "window", surface, (u - hu, v - hv, u + hu, v + hv))
    doc.set_user_zones((*doc.user_zones, edit))
    return edit


def test_a_window_zone_goes_on_any_face_a_skylight_only_overhead(doc):
    assert source_type("window").placement == ANY_FACE
    assert source_type("window").daylit and not source_type("window").electric
    wall = nearest(doc, "walls", SOUTH)
    look = ((5.0, 3.5, 1.6), (0.0, -1.0, 0.0), wall)
    name, rect = doc.zone_surface("window", *look)
    assert doc.scene.surface(name).group == "walls" and surface_class(rect.normal) == "wall"
    name, _ = doc.zone_surface("luminaire", *look)
    assert doc.scene.surface(name).group == "walls"
    with pytest.raises(DesignError, match="skylight zones are drawn on ceilings and roofs"):
        doc.zone_surface("skylight", *look)
    # From above (Top view) a window, like a skylight, goes on the ceiling it looks
    # through; looking down from inside the room it may go on the floor (any face).
    floor = nearest(doc, "floor", (5.0, 3.5, 0.0))
    name, _ = doc.zone_surface("window", (5.0, 3.5, 20.0), (0.0, 0.0, -1.0), floor)
    assert doc.scene.surface(name).group == "ceiling"
    name, _ = doc.zone_surface("window", (5.0, 3.5, 1.0), (0.0, 0.0, -1.0), floor)
    assert doc.scene.surface(name).group == "floor"


def test_a_window_source_is_named_for_its_kind_and_saved(doc, tmp_path):
    window_on_south_wall(doc)
    zone = doc.scene.surface("Win").rect
    assert sorted(zone.size) == pytest.approx([1.2, 2.0])
    assert zone.origin[1] == pytest.approx(0.0) and zone.normal == pytest.approx((0, 1, 0))
    s = doc.add_source("Win")
    assert (s.name, s.kind, s.filter) == ("W1", "window", 1.0)
    path = doc.save(tmp_path / "side.json")
    again = DocumentModel()
    again.open(path)
    assert {z.name: z.kind for z in again.scene.zones} == {"Win": "window"}
    assert [(x.name, x.kind) for x in again.design.sources] == [("W1", "window")]


@pytest.fixture
def lit(doc):
    """The room with a 2 x 1.2 m window on its south wall, a glazing source filling it,
    and a coarse operator."""
    from lightinv_core.operator.build import build_operator
    from lightinv_core.operator.settings import OperatorSettings

    window_on_south_wall(doc)
    doc.add_source("Win")
    doc.set_operator(build_operator(doc.patches, OperatorSettings(rank=40, rays=256)))
    return doc


def test_a_wall_window_sees_half_the_overcast_sky_and_the_ground(lit):
    from lightinv_core.light.daylight_year import sky_groups

    groups = sky_groups(lit.light, lit.design)
    assert groups.zones == (("Win",),)
    assert groups.outward[0] == pytest.approx((0.0, -1.0, 0.0), abs=1e-9)
    # CIE overcast sky on a vertical plane, in closed form: the sky part
    # (pi / 6 + 4 / 9) / (7 pi / 9) of the horizontal illuminance, the ground's
    # rho_g / 2 (it fills half the window's view).
    rho_g = lit.design.daylight.ground_reflectance
    vertical = (math.pi / 6 + 4 / 9) / (7 * math.pi / 9) + rho_g / 2
    assert groups.overcast[0] == pytest.approx(vertical, rel=1e-4)
    # The room's daylight factor comes through the window: highest near it (means, as
    # a small window's direct light on a floor patch is a few of its rays).
    day = lit.layout_daylight()
    df = day.patches.overcast_daylight()[:, 0]
    floor = lit.patches.group_index("floor")
    y = lit.patches.centroid[floor, 1]
    assert df[floor].max() > 0
    assert df[floor][y < 2].mean() > 2 * df[floor][y > 5].mean()


def test_the_year_on_a_wall_window_is_pvlibs_perez_on_a_vertical_south_plane(lit):
    pvlib = pytest.importorskip("pvlib")
    from lightinv_core.climate.transposition import sun_and_sky
    from lightinv_core.climate.weather import load_weather
    from lightinv_core.light.daylight_year import daylight_year, sky_groups, weather_path

    d = lit.design.daylight
    year = daylight_year(sky_groups(lit.light, lit.design), d)
    weather = load_weather(weather_path(d))
    sky = sun_and_sky(weather)
    # pvlib's own transposition of the same hours onto a vertical plane facing south
    # (the window's outward normal is -y; +y is north, north_deg 0).
    assert d.north_deg == 0
    poa = pvlib.irradiance.get_total_irradiance(
        90.0,
        180.0,
        sky.zenith,
        sky.azimuth,
        weather.dni,
        weather.ghi,
        weather.dhi,
        dni_extra=sky.dni_extra,
        airmass=sky.airmass,
        albedo=d.ground_reflectance,
        model="perez",
    )
    direct = np.nan_to_num(np.asarray(poa["poa_direct"], float))
    diffuse = np.maximum(np.nan_to_num(np.asarray(poa["poa_sky_diffuse"], float)), 0.0)
    ground = np.asarray(poa["poa_ground_diffuse"], float)
    # A vertical plane sees half the ground: the isotropic ground term rho_g GHI / 2.
    assert ground == pytest.approx(d.ground_reflectance * weather.ghi / 2, abs=1e-6)
    lux = sky.k_beam * direct + sky.k_diffuse * diffuse + sky.k_global * ground
    assert year.every[0] == pytest.approx(lux, rel=1e-6, abs=1e-3)
    # And the window gets less than a skylight would over the year, more than none.
    assert 0 < year.every[0].sum() < (weather.gh_lux).sum()


def test_from_the_front_view_a_window_goes_on_the_wall_seen_not_the_ceiling_grazed(doc):
    # Front view: the camera south of the room and above it, looking north down a
    # little; the south wall is culled and the north wall seen. The ray crosses the
    # ceiling's plane just inside its south edge: that ceiling is grazed, not meant.
    eye, target = np.array([5.0, -16.0, 6.4]), np.array([4.5, 7.0, 1.6])
    north = nearest(doc, "walls", target)
    name, rect = doc.zone_surface("window", eye, target - eye, north)
    assert doc.scene.surface(name).group == "walls" and rect.normal[1] == pytest.approx(-1)
    # A skylight has only the ceiling; a luminaire, like the window, the wall.
    name, _ = doc.zone_surface("skylight", eye, target - eye, north)
    assert doc.scene.surface(name).group == "ceiling"
    name, _ = doc.zone_surface("luminaire", eye, target - eye, north)
    assert doc.scene.surface(name).group == "walls"


def test_a_picked_face_becomes_a_zone_in_its_surfaces_metres(doc):
    from lightinv_core.editing.zones import surface_label, zone_size

    window_on_south_wall(doc)
    # A piece the window left of the south wall: the zone covers that piece, given in
    # the wall's own metres.
    piece = nearest(doc, "walls", (5.0, 0.0, 0.3))
    name = doc.patches.surface_names[doc.patches.surface_id[piece]]
    assert "~" in name
    was = doc.scene.surface(name).rect
    surface, rect = doc.face_zone(piece)
    assert surface == doc.user_zones[0].surface and "~" not in surface
    w, h, area = zone_size(rect)
    assert area == pytest.approx(w * h) == pytest.approx(doc.scene.surface(name).area)
    doc.add_user_zone("Low", "window", surface, rect)
    low = doc.scene.surface("Low").rect
    assert low.origin + 0.5 * (low.u + low.v) == pytest.approx(was.origin + 0.5 * (was.u + was.v))
    assert sorted(low.size) == pytest.approx(sorted(was.size))
    with pytest.raises(DesignError, match="cannot become a zone"):
        doc.face_zone(nearest(doc, "walls", (5.0, 0.0, 1.6)))  # the window zone itself
    assert surface_label("walls.rect2~3") == "walls, face 2"
    assert surface_label("ceiling~3") == "ceiling" and surface_label("IfcWall:N") == "IfcWall:N"
    assert zone_size(outline=[(0, 0), (2, 0), (2, 1), (1, 2), (0, 1)]) == pytest.approx(
        (2.0, 2.0, 3.0)
    )
