"""One catalogue of bad user input: every case feeds one bad input to the real loading
code and returns what the user gets (an exception, or a warning for input that is
accepted with a caveat). The same catalogue renders docs/bad-input.md; rerun with
LIGHTINV_WRITE_DOCS=1 to regenerate it after a message changes."""

from __future__ import annotations

import copy
import json
import os
import traceback
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest

from lightinv_core.climate.weather import WeatherError
from lightinv_core.design.model import Design, DesignError, Goal, Intention, Rule, Source
from lightinv_core.errors import LightInvError, ObjImportError, PhotometryError, SceneError
from lightinv_core.operator.cache import get_operator
from lightinv_core.operator.settings import OperatorSettings
from lightinv_core.optimize.problem import DesignProblem
from lightinv_core.optimize.search import random_start
from lightinv_core.project import ProjectError, load_project
from lightinv_core.scene.edits import ZoneEdit, apply_zone_edits
from lightinv_core.scene.importers.obj import load_obj
from lightinv_core.scene.loading import load_scene
from lightinv_core.scene.model import Rect, Surface
from lightinv_core.scene.patches import mesh_patches
from lightinv_core.study import prepare
from tests.core.test_obj_import import BOX

ROOT = Path(__file__).resolve().parents[2]
DOC = ROOT / "docs" / "bad-input.md"

# The closed 4 x 3 x 2.5 m room of the OBJ importer's tests.
CEILING = "g ceiling\nf 5 8 7 6\n"

# A valid project on the box: a skylight zone drawn on the ceiling, one free skylight.
PROJECT: dict = {
    "schema": 1,
    "name": "box study",
    "scene": {
        "obj": "room.obj",
        "resolution": 0.5,
        "zones": [{"name": "sky", "kind": "skylight", "surface": "ceiling", "rect": [1, 1, 3, 2]}],
    },
    "operator": {"rank": 8, "rays": 64},
    "sources": [
        {
            "name": "S1",
            "zone": "sky",
            "kind": "skylight",
            "rect": [0.2, 0.2, 1, 0.8],
            "free": ["u0", "v0", "u1", "v1"],
        }
    ],
    "rules": [{"kind": "area", "sources": ["S1"], "min": 0.2, "max": 1}],
    "intentions": [{"name": "floor light", "group": "floor", "average": 100}],
    "goals": [{"kind": "max_light_power"}],
}

WARNING = "warning"


@dataclass(frozen=True)
class Warned:
    """Input accepted with a warning: the warning text."""

    message: str


@dataclass(frozen=True)
class Case:
    id: str
    area: str
    tried: str  # markdown
    expect: type | str  # the exception class, or WARNING
    names: tuple[str, ...]  # what the message must contain: where and what
    run: Callable[[Path], object]


CASES: list[Case] = []


def case(id: str, area: str, tried: str, expect: type | str, *names: str):
    def register(fn):
        CASES.append(Case(id, area, tried, expect, names, fn))
        return fn

    return register


def raised(fn: Callable[[], object]) -> BaseException | None:
    try:
        fn()
    except Exception as exc:
        return exc
    return None


def write(d: Path, text: str, name: str = "room.obj") -> Path:
    path = d / name
    path.write_text(text, encoding="utf-8")
    return path


def obj_error(d: Path, text: str, **kw) -> BaseException | None:
    return raised(lambda: load_obj(write(d, text), resolution=0.5, **kw))


def obj_warning(d: Path, text: str, match: str, **kw) -> Warned | None:
    scene = load_obj(write(d, text), resolution=0.5, **kw)
    found = [w for w in scene.info["warnings"] if match in w]
    return Warned(found[0]) if found else None


def box_scene(d: Path):
    return load_obj(write(d, BOX), resolution=0.5)


def write_project(d: Path, change: Callable[[dict], object] | None = None) -> Path:
    data = copy.deepcopy(PROJECT)
    if change is not None:
        change(data)
    write(d, BOX)
    return write(d, json.dumps(data, indent=2), "project.json")


def project_error(d: Path, change: Callable[[dict], object]) -> BaseException | None:
    path = write_project(d, change)
    return raised(lambda: load_project(path))


def build_problem(d: Path, change: Callable[[dict], object] | None = None) -> DesignProblem:
    project = load_project(write_project(d, change))
    prepared = prepare(project)
    return DesignProblem(project.design, prepared.light)


def problem_error(d: Path, change: Callable[[dict], object]) -> BaseException | None:
    return raised(lambda: build_problem(d, change))


def start_error(d: Path, change: Callable[[dict], object]) -> BaseException | None:
    return raised(lambda: random_start(build_problem(d, change), np.random.default_rng(0)))


def setter(path: str, value) -> Callable[[dict], None]:
    """A change setting the value at a dotted path ("sources.0.rect") of the project."""

    def change(data: dict) -> None:
        *parents, last = path.split(".")
        node = data
        for key in parents:
            node = node[int(key)] if isinstance(node, list) else node[key]
        if isinstance(node, list):
            node[int(last)] = value
        else:
            node[last] = value

    return change


# --- OBJ files ----------------------------------------------------------------------------


@case(
    "obj-bad-vertex",
    "OBJ file",
    "a vertex with a word for a coordinate (`v 4 x 0`)",
    ObjImportError,
    "room.obj line 2",
    "'x' is not a number",
)
def _(d):
    return obj_error(d, BOX.replace("v 4 0 0", "v 4 x 0"))


@case(
    "obj-face-out-of-range",
    "OBJ file",
    "a face referring to vertex 9 of 8",
    ObjImportError,
    "room.obj line 10",
    "vertex 9",
    "only 8 vertices",
)
def _(d):
    return obj_error(d, BOX.replace("f 1 2 3 4", "f 1 2 3 9"))


@case(
    "obj-truncated",
    "OBJ file",
    "a file cut off in the middle of its last face line (`f 4 8`)",
    ObjImportError,
    "room.obj line 17",
    "at least 3 vertices, got 2",
)
def _(d):
    return obj_error(d, BOX[: BOX.rindex("f 4 8") + 5])


@case(
    "obj-nan",
    "OBJ file",
    "a NaN coordinate (`v nan 0 2.5`)",
    ObjImportError,
    "room.obj line 5",
    "'nan' is not finite",
)
def _(d):
    return obj_error(d, BOX.replace("v 0 0 2.5", "v nan 0 2.5"))


@case(
    "obj-inf",
    "OBJ file",
    "an infinite coordinate (`v 4 inf 0`)",
    ObjImportError,
    "room.obj line 3",
    "'inf' is not finite",
)
def _(d):
    return obj_error(d, BOX.replace("v 4 3 0", "v 4 inf 0"))


DEGENERATE = BOX + "v 1 1 1\nv 2 1 1\nv 3 1 1\ng junk\nf 1 1 2\nf 9 10 11\n"


@case(
    "obj-degenerate",
    "OBJ file",
    "a face with a repeated vertex (`f 1 1 2`) and a zero-area face (three collinear vertices)",
    ObjImportError,
    "room.obj",
    "2 degenerate face(s)",
    "lines 22, 23",
    "skip_degenerate=True",
)
def _(d):
    return obj_error(d, DEGENERATE)


@case(
    "obj-degenerate-skipped",
    "OBJ file",
    "the same faces with `skip_degenerate=True`",
    WARNING,
    "room.obj",
    "dropped 2 degenerate face(s)",
    "lines 22, 23",
)
def _(d):
    return obj_warning(d, DEGENERATE, "degenerate", skip_degenerate=True)


@case(
    "obj-all-degenerate-skipped",
    "OBJ file",
    "only degenerate faces, with `skip_degenerate=True`",
    ObjImportError,
    "room.obj",
    "all 2 faces are degenerate",
)
def _(d):
    return obj_error(d, BOX.split("g floor")[0] + "f 1 1 2\nf 1 2 2\n", skip_degenerate=True)


@case(
    "materials-out-of-range",
    "OBJ materials",
    'a materials file with a reflectance of 1.2 (`{"groups": {"floor": 1.2}}`)',
    ObjImportError,
    "materials file 'room-materials.json'",
    '"groups"."floor"',
    "1.2 is outside [0, 1)",
)
def _(d):
    mats = write(d, json.dumps({"groups": {"floor": 1.2}}), "room-materials.json")
    return obj_error(d, BOX, materials=mats)


@case(
    "materials-negative",
    "OBJ materials",
    'a materials file with a negative default reflectance (`{"default": -0.1}`)',
    ObjImportError,
    "materials file 'room-materials.json'",
    '"default"',
    "-0.1 is outside [0, 1)",
)
def _(d):
    mats = write(d, json.dumps({"default": -0.1}), "room-materials.json")
    return obj_error(d, BOX, materials=mats)


@case(
    "mtl-white",
    "OBJ materials",
    "an MTL material with `Kd 1 1 1` (reflectance 1)",
    WARNING,
    "material 'paint'",
    "capped at 0.95",
)
def _(d):
    write(d, "newmtl paint\nKd 1 1 1\n", "room.mtl")
    return obj_warning(d, "mtllib room.mtl\nusemtl paint\n" + BOX, "capped")


@case(
    "mtl-negative",
    "OBJ materials",
    "an MTL material with a negative colour (`Kd -0.5 0.5 0.5`)",
    WARNING,
    "room.mtl line 2",
    "Kd '-0.5 0.5 0.5'",
    "default reflectance",
)
def _(d):
    write(d, "newmtl paint\nKd -0.5 0.5 0.5\n", "room.mtl")
    return obj_warning(d, "mtllib room.mtl\nusemtl paint\n" + BOX, "cannot use Kd")


@case(
    "zone-not-planar",
    "OBJ emitter zone",
    "a zone group `zone:sky:skylight` whose corner is lifted 0.2 m",
    ObjImportError,
    "zone group 'zone:sky:skylight' (line 23)",
    "not planar",
    "up to 0.0495 m",
)
def _(d):
    zone = "v 1 1 2.4\nv 1 2 2.4\nv 2 2 2.6\nv 2 1 2.4\ng zone:sky:skylight\nf 9 10 11 12\n"
    return obj_error(d, BOX + zone)


@case(
    "zone-not-rectangle",
    "OBJ emitter zone",
    "a zone group made of one triangle",
    ObjImportError,
    "zone group 'zone:sky:skylight' (line 22)",
    "not a rectangle",
)
def _(d):
    return obj_error(d, BOX + "v 1 1 2.4\nv 1 2 2.4\nv 2 2 2.4\ng zone:sky:skylight\nf 9 10 11\n")


@case(
    "open-room",
    "lost light",
    "a box without its ceiling (the operator is built, and light escapes)",
    WARNING,
    "% of the light leaving the surfaces escapes the model",
    "the room is open",
)
def _(d):
    scene = load_obj(write(d, BOX.replace(CEILING, "")), resolution=0.5)
    got: list[str] = []
    get_operator(
        mesh_patches(scene), OperatorSettings(rank=8, rays=64), use_cache=False, warn=got.append
    )
    return Warned(got[0]) if got else None


@case(
    "operator-memory",
    "resources",
    "an operator whose build would not fit in the memory available (8 MiB free)",
    LightInvError,
    "needs about",
    "MiB is available (a build may use at most 80% of it); use a coarser --resolution",
)
def _(d):
    from unittest import mock

    scene = load_obj(write(d, BOX), resolution=0.1)
    free = 8 * 2**20
    with mock.patch("lightinv_core.operator.build.available_memory_bytes", return_value=free):
        return raised(
            lambda: get_operator(mesh_patches(scene), OperatorSettings(rank=400, rays=1024))
        )


@case(
    "obj-too-many-faces",
    "resources",
    "an OBJ file of 2,000,001 triangles (16 MB): more faces than patches allowed",
    ObjImportError,
    "room.obj: the model has 2,000,001 faces",
    "simplify it in the modeller",
)
def _(d):
    path = d / "room.obj"
    path.write_bytes(b"v 0 0 0\nv 1 0 0\nv 0 1 0\n" + b"f 1 2 3\n" * 2_000_001)
    return raised(lambda: load_obj(path, resolution=0.5))


@case(
    "obj-import-memory",
    "resources",
    "an OBJ file whose import would not fit in the memory available (16 KiB free; the "
    "container's cgroup limit counts)",
    ObjImportError,
    "room.obj: importing",
    "8 vertices, 6 faces",
    "16 KiB is available (an import may use at most 80% of it)",
)
def _(d):
    from unittest import mock

    path = write(d, BOX)
    with mock.patch(
        "lightinv_core.scene.importers.size.available_memory_bytes", return_value=2**14
    ):
        return raised(lambda: load_obj(path, resolution=0.5))


@case(
    "obj-millimetres",
    "resources",
    "the box drawn in millimetres (4000 x 3000 x 2500) imported without a scale",
    SceneError,
    "would make",
    "use a resolution of at least",
    "if it was drawn in millimetres import it with scale 0.001",
)
def _(d):
    mm = "".join(
        "v " + " ".join(str(1000 * float(x)) for x in line.split()[1:]) + "\n"
        for line in BOX.splitlines()
        if line.startswith("v ")
    )
    faces = "".join(line + "\n" for line in BOX.splitlines() if not line.startswith("v "))
    return raised(lambda: mesh_patches(load_obj(write(d, mm + faces), resolution=0.5)))


@case(
    "mesh-faces-over-limit",
    "resources",
    "a scene of 2,000,001 faces at any resolution (each face is at least one patch)",
    SceneError,
    "the model itself has 2,000,001 faces",
    "no resolution can help",
)
def _(d):
    tri = np.zeros((2_000_001, 3, 3))
    i = np.arange(len(tri))
    tri[:, :, 0] = (i % 1000)[:, None] * 0.01  # 1000 x 2000 small triangles, 10 x 20 m
    tri[:, :, 1] = (i // 1000)[:, None] * 0.01
    tri[:, 1, 0] += 0.01
    tri[:, 2, 1] += 0.01
    from lightinv_core.scene.model import Scene

    return raised(lambda: mesh_patches(Scene("many", (Surface("t", "t", 0.5, triangles=tri),))))


@case(
    "reference-memory",
    "resources",
    "`simulate --method reference` whose form factors would not fit (1 MiB free)",
    LightInvError,
    "the form factors of",
    "use the low-rank method (--method lrr)",
)
def _(d):
    from unittest import mock

    from lightinv_core.transport.formfactors import check_formfactor_memory

    p = mesh_patches(box_scene(d))
    with mock.patch(
        "lightinv_core.transport.formfactors.available_memory_bytes", return_value=2**20
    ):
        return raised(lambda: check_formfactor_memory(p, 65_536))


@case(
    "obj-duplicate-face",
    "OBJ file",
    "the floor face written twice (the area would count twice)",
    WARNING,
    "room.obj: dropped 1 duplicated face(s) at line 19",
    "count its area twice",
)
def _(d):
    return obj_warning(d, BOX + "g floor\nf 2 3 4 1\n", "duplicated")


@case(
    "obj-repeat-other-group",
    "OBJ file",
    "a desk face drawn exactly on the floor (another group)",
    WARNING,
    "room.obj: 1 face(s) at line 19 repeat a face of another group",
    "both are kept",
)
def _(d):
    return obj_warning(d, BOX + "g desk\nf 2 3 4 1\n", "repeat")


@case(
    "obj-inverted",
    "OBJ file",
    "the box with every face turned outwards, simulated (all light escapes, 0 lux)",
    WARNING,
    "100.0% of the light leaving the surfaces escapes the model",
    "face away",
)
def _(d):
    from lightinv_core.transport.formfactors import (
        escape_warning,
        form_factor_matrix,
        lost_fraction,
    )

    flipped = "".join(
        "f " + " ".join(reversed(line.split()[1:])) + "\n" if line.startswith("f ") else line + "\n"
        for line in BOX.splitlines()
    )
    p = mesh_patches(load_obj(write(d, flipped), resolution=0.5))
    msg = escape_warning(lost_fraction(form_factor_matrix(p, 64), p))
    return Warned(msg) if msg else None


@case(
    "emit-absurd",
    "resources",
    "a group emitting 1e300 lm (`--emit light=1e300`)",
    LightInvError,
    "flux for group 'floor' must be between 0 and 1e+10 lumens",
)
def _(d):
    from lightinv_core.transport.solver import group_emission

    return raised(lambda: group_emission(mesh_patches(box_scene(d)), {"floor": 1e300}))


@case(
    "cache-poisoned",
    "resources",
    "an operator cache file whose header claims a 1 PB payload",
    WARNING,
    "truncated or padded payload",
    "rebuilding",
)
def _(d):
    import lightinv_core.operator.cache as oc

    os.environ["LIGHTINV_CACHE_DIR"] = str(d / "cache")
    try:
        p = mesh_patches(box_scene(d))
        first = get_operator(p, OperatorSettings(rank=8, rays=64))
        raw = first.path.read_bytes()
        start = len(oc.MAGIC) + 8
        size = int.from_bytes(raw[len(oc.MAGIC) : start], "little")
        header = json.loads(raw[start : start + size])
        header["payload_bytes"] = 10**15
        new = json.dumps(header).encode()
        first.path.write_bytes(
            oc.MAGIC + len(new).to_bytes(8, "little") + new + raw[start + size :]
        )
        got: list[str] = []
        get_operator(p, OperatorSettings(rank=8, rays=64), warn=got.append)
    finally:
        del os.environ["LIGHTINV_CACHE_DIR"]
    return Warned(got[0]) if got else None


LUMINAIRE_HEADER = "name,x,y,z,ies,aim_x,aim_y,aim_z,c0_x,c0_y,c0_z\n"


def schedule_error(d: Path, rows: str) -> BaseException | None:
    from lightinv_core.luminaires.analytic import downlight
    from lightinv_core.luminaires.formats import write_photometry
    from lightinv_core.sources.luminaire_csv import read_luminaire_csv

    write_photometry(downlight(2000.0, watts=20.0), d / "down.ldt")
    (d / "lums.csv").write_text(rows)
    return raised(lambda: read_luminaire_csv(d / "lums.csv"))


@case(
    "schedule-missing-column",
    "luminaire schedule",
    "a schedule CSV without the aim and c0 columns",
    PhotometryError,
    "lums.csv line 1: missing column(s) aim_x",
)
def _(d):
    return schedule_error(d, "name,x,y,z,ies\nD1,1,1,2.9,down.ldt\n")


@case(
    "schedule-bad-number",
    "luminaire schedule",
    "a position written with a word (`x = left`)",
    PhotometryError,
    "lums.csv line 2: x 'left' is not a number",
)
def _(d):
    return schedule_error(d, LUMINAIRE_HEADER + "D1,left,1,2.9,down.ldt,0,0,-1,1,0,0\n")


@case(
    "schedule-c0-along-aim",
    "luminaire schedule",
    "a C0 direction parallel to the aim (`c0 = 0,0,1`)",
    PhotometryError,
    "lums.csv line 2: luminaire 'D1': c0 [0.0, 0.0, 1.0] is parallel to the aim",
)
def _(d):
    return schedule_error(d, LUMINAIRE_HEADER + "D1,1,1,2.9,down.ldt,0,0,-1,0,0,1\n")


@case(
    "schedule-missing-file",
    "luminaire schedule",
    "a photometric file that does not exist",
    PhotometryError,
    "lums.csv line 2:",
    "nowhere.ies",
)
def _(d):
    return schedule_error(d, LUMINAIRE_HEADER + "D1,1,1,2.9,nowhere.ies,0,0,-1,1,0,0\n")


@case(
    "weather-missing",
    "weather file",
    "a weather file that does not exist (`--weather nowhere.epw`)",
    WeatherError,
    "weather file",
    "does not exist",
)
def _(d):
    from lightinv_core.climate.weather import read_weather

    return raised(lambda: read_weather(d / "nowhere.epw"))


@case(
    "weather-garbage",
    "weather file",
    "a text file that is not an EPW (`--weather notes.epw`)",
    WeatherError,
    "notes.epw: an EPW file starts with a LOCATION line; this one does not",
)
def _(d):
    from lightinv_core.climate.weather import read_weather

    (d / "notes.epw").write_text("meeting notes\nnothing hourly here\n")
    return raised(lambda: read_weather(d / "notes.epw"))


def weather_error(d: Path, lines: list[str], name: str = "year.csv") -> BaseException | None:
    from lightinv_core.climate.weather import read_weather

    (d / name).write_text("\n".join(lines) + "\n")
    return raised(lambda: read_weather(d / name))


def tmy3() -> list[str]:
    from lightinv_core.climate.weather import BUILTIN

    return BUILTIN.read_text().splitlines()


def with_field(lines: list[str], row: int, col: int, value: str) -> list[str]:
    f = lines[row].split(",")
    f[col] = value
    return [*lines[:row], ",".join(f), *lines[row + 1 :]]


@case(
    "weather-half-year",
    "weather file",
    "half a TMY3 year (January to June)",
    WeatherError,
    "year.csv: 4380 hourly records where a year has 8760: 4380 hours are missing",
    "annual figures need the whole year",
)
def _(d):
    return weather_error(d, tmy3()[: 2 + 4380])


@case(
    "weather-repeated",
    "weather file",
    "a TMY3 year with January appended again (9,504 records)",
    WeatherError,
    "year.csv: 744 records repeat an hour already given (first: line 8763, 01-01 01:00)",
)
def _(d):
    lines = tmy3()
    return weather_error(d, lines + lines[2 : 2 + 744])


@case(
    "weather-cut",
    "weather file",
    "a TMY3 file cut in the middle of a line",
    WeatherError,
    "year.csv: line 4382 has 12 fields where the column line has 71",
    "the file may be cut short",
)
def _(d):
    lines = tmy3()
    return weather_error(d, [*lines[:4381], ",".join(lines[4381].split(",")[:12])])


@case(
    "weather-not-a-number",
    "weather file",
    "a GHI value `abc` in a TMY3 file",
    WeatherError,
    "year.csv: line 4095: GHI (W/m^2) 'abc' is not a number",
)
def _(d):
    return weather_error(d, with_field(tmy3(), 4094, 4, "abc"))


@case(
    "weather-absurd",
    "weather file",
    "a GHI of 1e9 W/m² in a TMY3 file",
    WeatherError,
    "year.csv: line 4095: GHI 1e+09 W/m² is beyond any sunlight (at most 1500)",
)
def _(d):
    return weather_error(d, with_field(tmy3(), 4094, 4, "1e9"))


@case(
    "weather-gaps",
    "weather file",
    "GHI missing (empty) at every noon of a TMY3 year",
    WeatherError,
    "year.csv: GHI is missing in 365 daylight hours (first: line 15); at most 47 can be filled",
)
def _(d):
    lines = tmy3()
    for r in range(2 + 12, len(lines), 24):
        lines = with_field(lines, r, 4, "")
    return weather_error(d, lines)


@case(
    "weather-gap-filled",
    "weather file",
    "GHI `NaN` in one daylight hour of a TMY3 year",
    WARNING,
    "GHI was missing in 1 daylight hours: filled from the neighbouring hours",
)
def _(d):
    from lightinv_core.climate.weather import read_weather

    (d / "year.csv").write_text("\n".join(with_field(tmy3(), 4094, 4, "NaN")) + "\n")
    notes = read_weather(d / "year.csv").notes
    return Warned(notes[0]) if notes else None


@case(
    "weather-latitude",
    "weather file",
    "a latitude of 136.1 in a TMY3 header",
    WeatherError,
    "year.csv: latitude 136.1 is not within -90 to 90 degrees",
)
def _(d):
    lines = tmy3()
    return weather_error(d, [lines[0].replace(",36.100,", ",136.100,"), *lines[1:]])


@case(
    "weather-clock",
    "weather file",
    "a TMY3 file whose header gives UTC+3 for North Carolina",
    WARNING,
    "1854 hours have direct sun (DNI > 50 W/m²) while the sun is below the horizon",
    "every record 8 h later than its time stamp",
)
def _(d):
    from lightinv_core.climate.weather import read_weather

    lines = tmy3()
    (d / "year.csv").write_text("\n".join([lines[0].replace(",-5.0,", ",+3.0,"), *lines[1:]]))
    notes = [n for n in read_weather(d / "year.csv").notes if "horizon" in n]
    return Warned(notes[0]) if notes else None


@case(
    "weather-subhourly",
    "weather file",
    "an EPW file with 4 records an hour",
    WeatherError,
    "sub.epw: 4 records an hour: only hourly EPW files are read",
)
def _(d):
    head = ["LOCATION,X,-,-,-,0,50,8,1,100"] + [f"H{i}" for i in range(6)]
    return weather_error(d, [*head, "DATA PERIODS,1,4,Data,Sunday, 1/ 1,12/31"], "sub.epw")


@case(
    "weather-occupancy",
    "weather file",
    "an occupancy schedule ending before it starts (18 to 8 h)",
    WeatherError,
    "occupancy must be 0 <= start < end <= 24 h",
)
def _(d):
    from lightinv_core.climate.weather import read_weather

    return raised(lambda: read_weather("builtin").occupied(18, 8))


def photometry_warning(d: Path, name: str, text: str) -> Warned | None:
    from lightinv_core.luminaires import read_photometry

    (d / name).write_text(text, encoding="latin-1")
    warnings = read_photometry(d / name).warnings
    return Warned(warnings[0]) if warnings else None


@case(
    "ies-tilt-include",
    "photometric file",
    "an IES file with `TILT=INCLUDE` (a lamp-tilt table)",
    WARNING,
    "TILT=INCLUDE: the lamp-tilt factors (3 angles, 0.9 to 1) are not applied",
)
def _(d):
    from tests.core.test_photometry import IES_OK, _sub

    text = _sub(IES_OK, "TILT=NONE\n", "TILT=INCLUDE\n1\n3\n0 45\n90\n1.0 0.95 0.9\n")
    return photometry_warning(d, "tilt.ies", text)


@case(
    "ies-lor-above-100",
    "photometric file",
    "a relative IES table that integrates to more than its lamps (a real file given 5,000 lm)",
    WARNING,
    "light output ratio 116.4%: the table integrates to 5,820 lm, more than the 5,000 lm",
)
def _(d):
    from tests.core.test_photometry import _relative

    return photometry_warning(d, "rel.ies", _relative(5000.0))


# --- glTF, PLY and IFC files ------------------------------------------------------------


def mesh_error(d: Path, name: str, data: bytes, **kw) -> BaseException | None:
    (d / name).write_bytes(data)
    return raised(lambda: load_scene(str(d / name), resolution=0.5, **kw))


@case(
    "gltf-not-gltf",
    "glTF/PLY file",
    "a `.glb` file that holds text (an STL file renamed)",
    ObjImportError,
    "room.glb: not a binary glTF (GLB) file",
    "export the model as glTF 2.0 binary",
)
def _(d):
    return mesh_error(d, "room.glb", b"solid cube\nendsolid cube\n")


@case(
    "gltf-truncated",
    "glTF/PLY file",
    "a `.glb` file cut off inside its JSON chunk",
    ObjImportError,
    "room.glb: the GLB file is truncated or damaged",
)
def _(d):
    from tests.core.test_mesh_import import box_gltf

    whole = box_gltf(d / "whole.glb").read_bytes()
    return mesh_error(d, "room.glb", whole[:200])


@case(
    "gltf-no-triangles",
    "glTF/PLY file",
    "a glTF file whose only mesh is a cloud of points",
    ObjImportError,
    "room.glb: no triangles found in its scene",
)
def _(d):
    from tests.core.test_mesh_import import Gltf

    g = Gltf()
    g.node("points", g.mesh([(np.zeros((1, 3, 3)), None)]))
    g.doc["meshes"][0]["primitives"][0]["mode"] = 0  # POINTS
    return raised(lambda: load_scene(str(g.save(d / "room.glb"))))


@case(
    "gltf-transparent",
    "glTF/PLY file",
    "a glTF material with alpha 0.2 (`alphaMode` BLEND): glass",
    WARNING,
    "room.glb: material(s) 'Glass' are transparent",
    "treats every surface as opaque",
)
def _(d):
    from tests.core.test_mesh_import import Gltf, box_polygons

    g = Gltf()
    glass = g.material("Glass", [0.9, 0.9, 0.9, 0.2], alphaMode="BLEND")
    for name, polys in box_polygons().items():
        g.part(name, polys, glass if name == "ceiling" else None)
    scene = load_scene(str(g.save(d / "room.glb")), 0.5)
    found = [w for w in scene.info["warnings"] if "transparent" in w]
    return Warned(found[0]) if found else None


@case(
    "ply-point-cloud",
    "glTF/PLY file",
    "a PLY file of points only (a scan)",
    ObjImportError,
    "room.ply: no faces found (3 vertices)",
    "not a point cloud",
)
def _(d):
    head = "ply\nformat ascii 1.0\nelement vertex 3\n"
    head += "property float x\nproperty float y\nproperty float z\nend_header\n"
    return mesh_error(d, "room.ply", (head + "0 0 0\n1 0 0\n0 1 0\n").encode())


@case(
    "ifc-missing-extra",
    "IFC file",
    "an IFC file where ifcopenshell is not installed",
    ObjImportError,
    "IFC import needs the optional extra: pip install 'lightinv[ifc]'",
)
def _(d):
    import builtins
    from unittest import mock

    real = builtins.__import__

    def no_ifc(name, *args, **kwargs):
        if name.startswith("ifcopenshell"):
            raise ImportError(name)
        return real(name, *args, **kwargs)

    (d / "room.ifc").write_text("ISO-10303-21;\n")
    with mock.patch.object(builtins, "__import__", no_ifc):
        return raised(lambda: load_scene(str(d / "room.ifc")))


@case(
    "ifc-unreadable",
    "IFC file",
    "a `.ifc` file that is not STEP text",
    ObjImportError,
    "room.ifc: cannot read it as IFC",
    "export the model as IFC2X3 or IFC4",
)
def _(d):
    (d / "room.ifc").write_text("<html>not a model</html>\n")
    return raised(lambda: load_scene(str(d / "room.ifc")))


@case(
    "ifc-cut-short",
    "IFC file",
    "a real IFC4 model (IfcOpenHouse) cut at half its length",
    ObjImportError,
    "cut.ifc: the file is cut short",
    "holds only part of the model",
)
def _(d):
    import gzip

    data = gzip.decompress(
        (Path(__file__).parents[1] / "data/ifc/IfcOpenHouse_IFC4.ifc.gz").read_bytes()
    )
    (d / "cut.ifc").write_bytes(data[: len(data) // 2])
    return raised(lambda: load_scene(str(d / "cut.ifc")))


@case(
    "ply-missing-vertex",
    "glTF/PLY file",
    "an ASCII PLY whose face names vertex 99,999,999 of 3",
    ObjImportError,
    "bad.ply: face 1 names vertex 99,999,999, but the file has 3 vertices",
)
def _(d):
    head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
    head += "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
    return mesh_error(d, "bad.ply", (head + "0 0 0\n1 0 0\n0 1 0\n3 0 1 99999999\n").encode())


@case(
    "ifc-odd-ceiling",
    "IFC file",
    "a ceiling covering with a hole cut in it (not a rectangle: no luminaire zone)",
    WARNING,
    "1 window(s) or ceiling(s) ('IfcCovering:Holed') have no rectangular face",
    "plain surfaces and not emitter zones",
)
def _(d):
    import ifcopenshell.api.feature

    from tests.core.test_ifc_import import ifc_room

    def extra(box, f):
        panel = box("IfcCovering", "Holed", 0.0, 0.0, 2.5, 2.0, 2.0, 0.02, predefined="CEILING")
        hole = box("IfcOpeningElement", "hole", 0.5, 0.5, 2.4, 0.5, 0.5, 0.3, contained=False)
        ifcopenshell.api.feature.add_feature(f, feature=hole, element=panel)

    scene = load_scene(str(ifc_room(d / "room.ifc", extra=extra)), 0.5)
    return Warned(scene.info["warnings"][0]) if scene.info["warnings"] else None


@case(
    "luminaire-outside-room",
    "scene",
    "a luminaire 5 m up in the 2.5 m box (`simulate --luminaires`: `UP,2,1.5,5,...`)",
    WARNING,
    "luminaire 'UP' at (2.00, 1.50, 5.00) m: 100% of its light leaves the model",
    "outside the room, inside a solid or behind a surface facing away",
)
def _(d):
    from lightinv_core.luminaires.analytic import downlight
    from lightinv_core.transport.escape import luminaire_escape_warnings
    from lightinv_core.transport.luminaires import PlacedLuminaire
    from lightinv_core.transport.raycast import RayCaster

    lum = PlacedLuminaire("UP", (2.0, 1.5, 5.0), downlight(2000.0, watts=20.0))
    got = luminaire_escape_warnings([lum], RayCaster(mesh_patches(box_scene(d))))
    return Warned(got[0]) if got else None


# --- scenes and drawn zones ---------------------------------------------------------------


@case(
    "scene-unknown",
    "scene",
    "a scene that is neither built in nor a model file (`room.dae`)",
    SceneError,
    "'room.dae'",
    "neither a built-in scene",
)
def _(d):
    return raised(lambda: load_scene("room.dae"))


@case(
    "scene-missing-obj",
    "scene",
    "an OBJ path that does not exist",
    ObjImportError,
    "'<dir>/gone.obj' does not exist",
)
def _(d):
    return raised(lambda: load_scene(str(d / "gone.obj")))


@case(
    "surface-reflectance",
    "scene",
    "a surface with reflectance 1 (`Surface('floor', 'floor', 1.0, rect=...)`)",
    SceneError,
    "surface 'floor'",
    "1.0 is outside [0, 1)",
)
def _(d):
    rect = Rect((0, 0, 0), (1, 0, 0), (0, 1, 0))
    return raised(lambda: Surface("floor", "floor", 1.0, rect=rect))


@case(
    "zone-unknown-surface",
    "drawn zone",
    "a zone drawn on a surface that does not exist (`ceilng`)",
    SceneError,
    "new emitter zone 'Z1' on surface 'ceilng'",
    "has no surface 'ceilng'",
    "did you mean 'ceiling'",
)
def _(d):
    edit = ZoneEdit("Z1", "luminaire", "ceilng", (1, 1, 2, 2))
    return raised(lambda: apply_zone_edits(box_scene(d), [edit]))


@case(
    "zone-outside-surface",
    "drawn zone",
    "a zone running past the edge of the ceiling (`(3, 1)-(5, 2)` on its 3 x 4 m)",
    SceneError,
    "new emitter zone 'Z1' on surface 'ceiling'",
    "(3, 1)-(5, 2)",
    "outside the surface",
)
def _(d):
    edit = ZoneEdit("Z1", "luminaire", "ceiling", (3, 1, 5, 2))
    return raised(lambda: apply_zone_edits(box_scene(d), [edit]))


@case(
    "zone-empty",
    "drawn zone",
    "a zone of zero width (`(1, 1)-(1, 2)`)",
    SceneError,
    "new emitter zone 'Z1' on surface 'ceiling'",
    "zero width or height",
)
def _(d):
    return raised(lambda: ZoneEdit("Z1", "luminaire", "ceiling", (1, 1, 1, 2)))


@case(
    "zone-outline-crossing",
    "drawn zone",
    "a polygon zone whose corners are given out of order (a bow tie)",
    SceneError,
    "new emitter zone 'Z1' on surface 'ceiling'",
    "crosses itself (edges 1 and 3)",
)
def _(d):
    outline = ((0.5, 0.5), (2.5, 3.5), (2.5, 0.5), (0.5, 3.5))
    return raised(lambda: ZoneEdit("Z1", "luminaire", "ceiling", outline=outline))


@case(
    "zone-outline-outside",
    "drawn zone",
    "a triangle zone whose bounding rectangle runs past the ceiling's edge",
    SceneError,
    "new emitter zone 'Z1' on surface 'ceiling'",
    "(0.5, 1)-(4, 3)",
    "outside the surface",
)
def _(d):
    edit = ZoneEdit("Z1", "luminaire", "ceiling", outline=((0.5, 1), (4, 1), (0.5, 3)))
    return raised(lambda: apply_zone_edits(box_scene(d), [edit]))


# --- project files: when loaded -----------------------------------------------------------


@case(
    "project-schema",
    "project file",
    'an unknown schema version (`"schema": 2`)',
    ProjectError,
    "project.json",
    "unknown project schema 2",
)
def _(d):
    return project_error(d, setter("schema", 2))


@case(
    "project-missing-field",
    "project file",
    "no `goals`",
    ProjectError,
    "project.json",
    "goals",
)
def _(d):
    return project_error(d, lambda data: data.pop("goals"))


@case(
    "project-wrong-type",
    "project file",
    'a rectangle given as text (`"rect": "0 0 1 1"`)',
    ProjectError,
    "project.json: sources[0].rect",
    "expected a list of 4 numbers",
)
def _(d):
    return project_error(d, setter("sources.0.rect", "0 0 1 1"))


@case(
    "project-negative-resolution",
    "project file",
    'a negative resolution (`"resolution": -0.5`)',
    ProjectError,
    "project.json: scene.resolution",
    "-0.5",
)
def _(d):
    return project_error(d, setter("scene.resolution", -0.5))


@case(
    "project-flux-range-huge",
    "project file",
    'a free flux of up to 1e308 lm (`"flux_range": [0, 1e308]`)',
    ProjectError,
    "project.json: sources[0].flux_range[1]",
    "expected a number >= 0 and <= 10000000000, got 1e+308",
)
def _(d):
    return project_error(d, setter("sources.0.flux_range", [0, 1e308]))


@case(
    "project-exterior-lux-huge",
    "project file",
    'an exterior illuminance of 1e300 lux (`"exterior_lux": 1e300`)',
    ProjectError,
    "project.json: daylight.exterior_lux",
    "expected a number >= 0 and <= 1000000, got 1e+300",
)
def _(d):
    return project_error(d, setter("daylight", {"exterior_lux": 1e300}))


@case(
    "project-tol",
    "project file",
    'an operator tolerance of 100% (`"tol": 1`)',
    ProjectError,
    "project.json: operator.tol",
    "< 1",
)
def _(d):
    return project_error(d, setter("operator.tol", 1))


def duplicate_objective(d: Path) -> BaseException | None:
    """A project whose saved solution gives the objective max_light_power twice."""
    data = copy.deepcopy(PROJECT)
    best = {"sources": data["sources"], "objectives": {"max_light_power": 1.0}, "penalty": 0}
    data["results"] = {"solutions": [best]}
    text = json.dumps(data, indent=2).replace(
        '"max_light_power": 1.0', '"max_light_power": 1.0, "max_light_power": 2.0'
    )
    write(d, BOX)
    return raised(lambda: load_project(write(d, text, "project.json")))


@case(
    "project-objective-twice",
    "project file",
    'a saved solution giving an objective twice (`"max_light_power": 1.0, "max_light_power": 2.0`)',
    ProjectError,
    "project.json: results.solutions[0].objectives",
    "objective 'max_light_power' is given twice",
)
def _(d):
    return duplicate_objective(d)


@case(
    "project-run-twice",
    "project file",
    'a run of the results\' history listed twice (two runs `"number": 1`)',
    ProjectError,
    "project.json: results.runs[1].number",
    "run 1 is listed twice",
)
def _(d):
    run = {"number": 1, "method": "vns"}
    return project_error(d, lambda data: data.update(results={"runs": [run, run]}))


@case(
    "project-invalid-json",
    "project file",
    "invalid JSON (a missing comma)",
    ProjectError,
    "project.json",
    "invalid JSON at line 4, column 3",
)
def _(d):
    path = write_project(d)
    text = path.read_text(encoding="utf-8").replace('"box study",', '"box study"', 1)
    return raised(lambda: load_project(write(d, text, "project.json")))


@case(
    "project-truncated",
    "project file",
    "a file cut off halfway",
    ProjectError,
    "project.json",
    "invalid JSON at line",
)
def _(d):
    path = write_project(d)
    text = path.read_text(encoding="utf-8")
    return raised(lambda: load_project(write(d, text[: len(text) // 2], "project.json")))


@case(
    "project-unknown-source",
    "project file",
    "a rule naming a source that does not exist (`S9`)",
    ProjectError,
    "project.json: rules[0].sources[0]",
    "no source 'S9'",
)
def _(d):
    return project_error(d, setter("rules.0.sources", ["S9"]))


@case(
    "project-unknown-scene",
    "project file",
    'a misspelt built-in scene (`"builtin": "ofice"`)',
    ProjectError,
    "project.json: scene.builtin",
    "ofice",
)
def _(d):
    return project_error(d, setter("scene", {"builtin": "ofice"}))


def with_array(**fields) -> Callable[[dict], None]:
    """A project change: a luminaire zone on the box's ceiling and an array in it (with
    ``fields`` over its defaults), and a work plane over the floor."""

    def change(data: dict) -> None:
        data["scene"]["zones"].append(
            {"name": "lamps", "kind": "luminaire", "surface": "ceiling", "rect": [0, 2, 3, 3]}
        )
        array = {"name": "A1", "zone": "lamps", "product": "Downlight 2000 lm 20 W"}
        data["arrays"] = [{**array, "rect": [0, 0, 3, 1], "rows": 1, "columns": 2, **fields}]
        data["workplanes"] = [{"name": "wp"}]

    return change


@case(
    "project-array-rows",
    "project file",
    'a luminaire array of no rows (`"rows": 0`)',
    ProjectError,
    "project.json: arrays[0].rows",
    "expected an integer >= 1, got 0",
)
def _(d):
    return project_error(d, with_array(rows=0))


@case(
    "project-array-rule-on-source",
    "project file",
    "a spacing-to-height rule naming a source, not an array",
    ProjectError,
    "project.json: rules[1].sources[0]",
    "no luminaire array 'S1' (luminaire arrays: A1)",
)
def _(d):
    def change(data):
        with_array()(data)
        data["rules"].append({"kind": "shr", "sources": ["S1"], "max": 1.5})

    return project_error(d, change)


@case(
    "project-grid-unknown",
    "project file",
    'an intention on a work plane that does not exist (`"grid": "desk"`)',
    ProjectError,
    "intention 'office': no work plane 'desk' (work planes: ['wp'])",
)
def _(d):
    def change(data):
        with_array()(data)
        data["intentions"].append({"name": "office", "grid": "desk", "average": 500})

    return project_error(d, change)


@case(
    "project-occupancy-empty",
    "project file",
    "a daylight occupancy from 8:36 to 9:24 (`[8.6, 9.4]`), which holds no hour's middle",
    ProjectError,
    "holds no hour",
)
def _(d):
    return project_error(d, setter("daylight", {"occupancy": [8.6, 9.4]}))


@case(
    "project-annual-lux",
    "project file",
    'an illuminance intention in the annual scenario (`"scenario": "annual"`)',
    ProjectError,
    "the annual scenario bounds a daylight metric",
)
def _(d):
    return project_error(d, setter("intentions.0.scenario", "annual"))


@case(
    "project-annual-goal-no-plane",
    "project file",
    "the goal least annual energy in a design without a work plane",
    ProjectError,
    "are measured on a work plane",
)
def _(d):
    return project_error(d, setter("goals", [{"kind": "min_annual_energy"}]))


# --- project files: when the scene is loaded and the problem built ------------------------


@case(
    "project-array-product",
    "project scene",
    'a luminaire array of a product the catalogue lacks (`"product": "Downlite"`)',
    DesignError,
    "product 'Downlite' is neither a catalogue luminaire",
    "nor an .ies/.ldt/.gldf file",
)
def _(d):
    return problem_error(d, with_array(product="Downlite"))


@case(
    "project-array-product-file",
    "project scene",
    'a luminaire array whose photometric file is missing (`"product": "gone.ies"`)',
    DesignError,
    "product '<dir>/gone.ies': no such photometric file",
)
def _(d):
    return problem_error(d, with_array(product="gone.ies"))


@case(
    "project-workplane-not-floor",
    "project scene",
    'a work plane over the walls (`"group": "walls"`)',
    LightInvError,
    "group 'walls' is not a horizontal floor facing up; a work plane lies over a floor",
)
def _(d):
    def change(data):
        with_array()(data)
        data["workplanes"] = [{"name": "wp", "group": "walls"}]

    return problem_error(d, change)


@case(
    "project-workplane-above-room",
    "project scene",
    'a work plane 5 m above the floor of the 2.5 m box (`"height": 5`)',
    SceneError,
    "work plane 'wp' 5.0 m above 'floor'",
    "is not inside its room, which spans z = 0.00 to 2.50 m",
)
def _(d):
    def change(data):
        with_array()(data)
        data["workplanes"] = [{"name": "wp", "height": 5}]

    return problem_error(d, change)


@case(
    "project-obj-missing",
    "project scene",
    "a project whose OBJ file is missing (`project.scene.load()`)",
    ObjImportError,
    "'<dir>/gone.obj' does not exist",
)
def _(d):
    return problem_error(d, setter("scene.obj", "gone.obj"))


@case(
    "project-zone-surface",
    "project scene",
    "a drawn zone on a surface the scene lacks (`project.scene.load()`)",
    SceneError,
    "new emitter zone 'sky' on surface 'roof'",
    "has no surface 'roof'",
)
def _(d):
    return problem_error(d, setter("scene.zones.0.surface", "roof"))


@case(
    "problem-unknown-group",
    "problem built",
    "an intention on a group the scene does not have (`desks`)",
    DesignError,
    "intention 'floor light': no group 'desks'",
    "groups: floor, ceiling, walls",
)
def _(d):
    return problem_error(d, setter("intentions.0.group", "desks"))


@case(
    "problem-unknown-zone",
    "problem built",
    "a source in an emitter zone the scene does not have (`roof`)",
    DesignError,
    "source 'S1'",
    "no emitter zone 'roof'",
    "zones: sky",
)
def _(d):
    return problem_error(d, setter("sources.0.zone", "roof"))


@case(
    "problem-zone-kind",
    "problem built",
    "a luminaire placed in a skylight zone",
    DesignError,
    "source 'L1' is a luminaire",
    "zone 'sky' takes skylights",
)
def _(d):
    lum = {"name": "L1", "zone": "sky", "kind": "luminaire", "rect": [0, 0, 1, 1], "flux": 1}
    return problem_error(d, lambda data: data["sources"].append(lum))


@case(
    "problem-patch-id",
    "problem built",
    "an intention on patch 99999 of a scene with fewer patches",
    DesignError,
    "intention 'floor light'",
    "patch id 99999 is not in the scene",
)
def _(d):
    return problem_error(
        d, setter("intentions.0", {"name": "floor light", "patches": [99999], "min": 1})
    )


@case(
    "project-weather-missing",
    "project scene",
    "a DA300 intention with a weather file that is not there (`nowhere.epw`)",
    WeatherError,
    "nowhere.epw",
    "does not exist; check the path",
)
def _(d):
    def change(data):
        data["daylight"] = {"weather": "nowhere.epw"}
        data["intentions"] = [{"name": "da", "group": "floor", "quantity": "da", "average": 0.5}]

    problem = build_problem(d, change)
    return raised(lambda: problem.evaluate(problem.vars.initial()[None]))


# --- constraints infeasible on their face ------------------------------------------------


@case(
    "rule-area-min-max",
    "constraints",
    "an area rule with min 2 m² > max 1 m²",
    ProjectError,
    "project.json: rules[0]",
    "min 2.0 is larger than max 1.0",
)
def _(d):
    return project_error(
        d, setter("rules.0", {"kind": "area", "sources": ["S1"], "min": 2, "max": 1})
    )


@case(
    "intention-min-max",
    "constraints",
    "an intention with min 500 lux > max 300 lux",
    ProjectError,
    "project.json: intentions[0]",
    "intention 'floor light'",
    "min 500.0 is above max 300.0",
)
def _(d):
    return project_error(
        d, setter("intentions.0", {"name": "floor light", "group": "floor", "min": 500, "max": 300})
    )


@case(
    "intention-out-of-range",
    "constraints",
    'a daylight autonomy intention of average 1.5 (`"quantity": "da"`, a fraction 0-1)',
    ProjectError,
    "project.json: intentions[0]",
    "intention 'da': average 1.5 is outside the range of da",
    "0 to 1; it could never be met",
)
def _(d):
    it = {"name": "da", "group": "floor", "quantity": "da", "average": 1.5}
    return project_error(d, setter("intentions.0", it))


@case(
    "intention-average-max",
    "constraints",
    "an intention with average 500 lux > max 300 lux",
    ProjectError,
    "project.json: intentions[0]",
    "average 500.0 is above max 300.0",
)
def _(d):
    it = {"name": "floor light", "group": "floor", "average": 500, "max": 300}
    return project_error(d, setter("intentions.0", it))


@case(
    "rule-aspect",
    "constraints",
    "an aspect rule with max 0.5 (< 1)",
    ProjectError,
    "project.json: rules[0]",
    "max aspect ratio must be at least 1, got 0.5",
)
def _(d):
    return project_error(d, setter("rules.0", {"kind": "aspect", "sources": ["S1"], "max": 0.5}))


@case(
    "fixed-source-degenerate",
    "run start",
    "a fixed source (nothing free) whose rect has zero width",
    DesignError,
    "source 'S1': its fixed rect (0.3, 0.3, 0.3, 0.8) is 0 x 0.5 m, a line or a point",
)
def _(d):
    def change(p):
        p["sources"][0].update(rect=[0.3, 0.3, 0.3, 0.8], free=[])
        p["rules"] = []

    return start_error(d, change)


@case(
    "fixed-source-outside",
    "run start",
    "a fixed source whose rect lies partly outside its 2 x 1 m zone",
    DesignError,
    "source 'S1': its fixed rect (1.5, 0.2, 2.5, 0.8) lies outside its zone 'sky'",
    "spans 0 to 2 m by 0 to 1 m",
)
def _(d):
    def change(p):
        p["sources"][0].update(rect=[1.5, 0.2, 2.5, 0.8], free=[])
        p["rules"] = []

    return start_error(d, change)


@case(
    "rule-area-too-large",
    "run start",
    "an area rule asking for at least 5 m² in a 2 x 1 m zone",
    DesignError,
    "no random layout",
    "meets the geometric rules",
)
def _(d):
    return start_error(d, setter("rules.0", {"kind": "area", "sources": ["S1"], "min": 5}))


@case(
    "rule-spacing-too-large",
    "run start",
    "two sources 3 m apart in a 2 x 1 m zone (spacing rule)",
    DesignError,
    "no random layout",
    "meets the geometric rules",
)
def _(d):
    def change(data):
        s2 = dict(data["sources"][0], name="S2")
        data["sources"].append(s2)
        data["rules"] = [{"kind": "spacing", "sources": ["S1", "S2"], "min": 3}]

    return start_error(d, change)


@case(
    "scheduler-address",
    "run start",
    "`--scheduler localhost:8786` (a Dask scheduler address without its `tcp://`)",
    LightInvError,
    "scheduler address 'localhost:8786'",
    "not of the form tcp://host:port",
)
def _(d):
    from lightinv_core.operator.build import build_operator

    patches = mesh_patches(box_scene(d))
    return raised(
        lambda: build_operator(
            patches, OperatorSettings(rank=8, rays=16), scheduler="localhost:8786"
        )
    )


def export_error(d: Path, *options: str) -> BaseException | None:
    """``lightinv-cli export`` of the base project (which holds no results) with
    ``options``, run as the command line does up to its first error."""
    from lightinv_core.cli.parser import build_parser

    args = build_parser().parse_args(["export", str(write_project(d)), *options])
    return raised(lambda: args.func(args))


@case(
    "export-no-solution",
    "export",
    "`lightinv-cli export project.json --ifc out.ifc` on a project that was never solved",
    LightInvError,
    "holds no solution to export",
    "lightinv-cli solve project.json -o RESULT.json",
)
def _(d):
    return export_error(d, "--ifc", str(d / "out.ifc"))


@case(
    "export-wrong-suffix",
    "export",
    "`--gltf out.gltf` (the exporter writes binary glTF only)",
    LightInvError,
    "--gltf",
    "must end with .glb",
)
def _(d):
    return export_error(d, "--gltf", str(d / "out.gltf"))


@case(
    "export-ifc-missing-extra",
    "export",
    "`--ifc` where ifcopenshell is not installed",
    LightInvError,
    "IFC export needs the optional extra: pip install 'lightinv[ifc]'",
)
def _(d):
    import builtins
    from unittest import mock

    from lightinv_core.export import ifc_writer

    real = builtins.__import__

    def no_ifc(name, *args, **kwargs):
        if name.startswith("ifcopenshell"):
            raise ImportError(name)
        return real(name, *args, **kwargs)

    with mock.patch.object(builtins, "__import__", no_ifc):
        return raised(ifc_writer.libraries)


# --- values of the wrong type given to the model classes in code ------------------------
# Not in the docs table (no file can produce them: the readers check types first), but
# each used to escape as a TypeError, ValueError or OverflowError instead of a
# LightInvError naming the value.

SQUARE = Rect((0, 0, 0), (1, 0, 0), (0, 1, 0))
LUM = {"name": "L", "zone": "z", "kind": "luminaire", "rect": (0, 0, 1, 1), "flux": 1.0}
GOALS = (Goal("min_electric_power"),)
WRONG_TYPES = {
    "source rect not a list": lambda: Source(**{**LUM, "rect": 5}),
    "source rect None": lambda: Source(**{**LUM, "rect": None}),
    "source free not a list": lambda: Source(**{**LUM, "free": 3}),
    "source flux_range not a list": lambda: Source(**{**LUM, "flux_range": 5}),
    "source flux too large for a float": lambda: Source(**{**LUM, "flux": 10**400}),
    "source name not a string": lambda: Source(**{**LUM, "name": ["L"]}),
    "rule sources not a list": lambda: Rule("area", 5, min=1),
    "rule source names not strings": lambda: Rule("area", [["a"]], min=1),
    "intention patches not a list": lambda: Intention("i", patches=5, min=1),
    "intention patch id too large": lambda: Intention("i", patches=[1e300], min=1),
    "goal kinds not a list": lambda: Goal("max_light_power", kinds=5),
    "design sources not a list": lambda: Design(5, GOALS),
    "design goals None": lambda: Design((), None),
    "design sources of strings": lambda: Design(("a",), GOALS),
    "design penalty power a string": lambda: Design((), GOALS, penalty_power="2"),
    "rect origin a string": lambda: Rect("abc", (1, 0, 0), (0, 1, 0)),
    "surface triangles a string": lambda: Surface("a", "g", 0.5, triangles="abc"),
    "surface grid a string": lambda: Surface("a", "g", 0.5, rect=SQUARE, grid="ab"),
    "surface grid not whole": lambda: Surface("a", "g", 0.5, rect=SQUARE, grid=(2.5, 2)),
    "surface name not a string": lambda: Surface(5, "g", 0.5, rect=SQUARE),
}


@pytest.mark.parametrize("make", WRONG_TYPES.values(), ids=WRONG_TYPES.keys())
def test_wrong_types_in_code_raise_light_inv_errors(make):
    with pytest.raises(LightInvError):
        make()


# --- running the catalogue ----------------------------------------------------------------


def run_case(c: Case, d: Path) -> object:
    try:
        return c.run(d)
    except Exception as exc:  # a crash while setting the case up is reported by its test
        return exc


@pytest.fixture(scope="module")
def outcomes(tmp_path_factory) -> dict[str, tuple[object, str]]:
    """Every case run once: id -> (result, message with the case's folder shown as <dir>)."""
    out = {}
    for c in CASES:
        d = tmp_path_factory.mktemp(c.id, numbered=True)
        result = run_case(c, d)
        text = result.message if isinstance(result, Warned) else str(result)
        out[c.id] = (result, text.replace(str(d), "<dir>"))
    return out


def describe(result: object) -> str:
    if result is None:
        return "nothing was raised or warned"
    if isinstance(result, BaseException):
        return "".join(traceback.format_exception(result))
    return repr(result)


def test_the_base_project_is_valid(tmp_path):
    """Each project case changes one thing of a project that loads and can start a run."""
    problem = build_problem(tmp_path)
    assert problem.vars.n == 4
    random_start(problem, np.random.default_rng(0))


def test_case_ids_are_unique():
    assert len({c.id for c in CASES}) == len(CASES)


@pytest.mark.parametrize("c", CASES, ids=lambda c: c.id)
def test_bad_input(c: Case, outcomes, tmp_path_factory):
    result, text = outcomes[c.id]
    if c.expect == WARNING:
        assert isinstance(result, Warned), describe(result)
    else:
        assert type(result) is c.expect, describe(result)
        assert isinstance(result, LightInvError)
    for name in c.names:
        assert name in text, f"{name!r} not in {text!r}"
    assert str(tmp_path_factory.getbasetemp()) not in text
    assert "\n" not in text and "Traceback" not in text


def code(text: str) -> str:
    """``text`` as a markdown code span inside a table cell."""
    text = text.replace("|", "\\|")
    fence = "``" if "`" in text else "`"
    pad = " " if fence == "``" else ""
    return f"{fence}{pad}{text}{pad}{fence}"


HEADER = """\
# What LightInv says about bad input

<!-- Generated by tests/core/test_bad_input.py: do not edit by hand. -->

Generated by `tests/core/test_bad_input.py` from the messages the engine actually gives:
each row is one case of its catalogue, fed to the real loading code. After changing a
message, regenerate this file with

```bash
LIGHTINV_WRITE_DOCS=1 .venv/bin/python -m pytest tests/core/test_bad_input.py
```

(without the variable the test fails while this file differs from the messages).

Every error a user can cause is a `LightInvError` (a `ValueError`): `SceneError` for
scenes, surfaces and drawn zones, `ObjImportError` (a `SceneError`) for model files
(OBJ, glTF, PLY, IFC), MTL and materials files, `ProjectError` for project files (its
message starts with the file name and the JSON path), `DesignError` for designs that
cannot work on the scene or whose rules cannot be met. The window shows the message
exactly as below in an error dialog (`str(exc)` in a message box, never a traceback);
`lightinv-cli` prints it as one line, `lightinv-cli: error: MESSAGE`, and exits with
status 2.

A *warning* does not stop the work: the import or build goes on and the text is
returned (`scene.info["warnings"]`, the `warn` callback of `get_operator` and
`prepare`); `lightinv-cli` prints it on stderr and the window in its status bar.

`<dir>` stands for the folder of the file. The area also says which step finds the
problem: *project file* when it is loaded (`load_project`), *project scene* when its
scene is loaded (`project.scene.load()`), *problem built* when the design meets the
scene (`DesignProblem`), *run start* when a run looks for a first layout meeting the
geometric rules; *constraints* contradictory on their face are found when loading.

| area | input tried | raises | what the user sees |
|---|---|---|---|
"""


OUTPUT_CASES = (
    (
        "output path is a regular file or a new name",
        "written to a temporary beside it, then renamed over it: all or nothing, "
        "the old file kept on any failure",
    ),
    (
        "output path is a symbolic link",
        "the file it points to is replaced the same way; the link stays a link (a"
        " dangling link gets its target created)",
    ),
    (
        "output is a pipe, FIFO, terminal or device (`-o /dev/stdout`, "
        "`--patches-csv /dev/stdout`, `/dev/null`)",
        "written through in order; the device or pipe is never replaced by a file",
    ),
    (
        "the program is killed (`kill -9`) while writing",
        "the old file stays; the writer's hidden `.NAME.tmp-*` file is removed by"
        " the next write to that folder, and the operator cache and autosave "
        "folders are swept when opened (a leftover is recognised by its released "
        "lock, so a reused process id cannot keep it). `tests/core/test_kill_writes.py`"
        " kills a writer 6 times at random moments for each kind (project file and"
        " saved results, autosave, operator cache, patch CSV, PDF report): the file is"
        " always one whole version",
    ),
    (
        "`--seed -1` or above 2**63 - 1 (`solve`, `simulate`, `precompute`)",
        "`lightinv-cli: error: lightinv-cli solve: argument --seed: expected an "
        "integer seed from 0 to 2**63 - 1, got -1 (see --help)`, status 2",
    ),
    (
        "`--max-evals 0` or negative",
        "`... argument --max-evals: expected an integer >= 1, got 0 (see --help)`, status 2",
    ),
    (
        "`--rays 0`, `--rays 2**70` (`simulate`, `precompute`)",
        "`... argument --rays: expected an integer from 1 to 65,536 rays per patch, got 0 "
        "(see --help)`, status 2 (before, `simulate` with 2**70 rays gave a traceback)",
    ),
    (
        "Ctrl-C at any moment, the start-up imports included",
        "`lightinv-cli: cancelled` on stderr, status 130, no traceback",
    ),
    (
        "any mix of subcommand, option and value (hypothesis, 120 cases per run; 1,500 tried once)",
        "`tests/core/test_cli.py`: status 0 or 2 with one `lightinv-cli: error:` line or"
        " usage, never a traceback",
    ),
    (
        "the operator cache folder cannot be created or written, or the disk is full",
        "(`tests/core/test_operator.py`): the operator is built and used; one warning,"
        " `could not write the operator cache PATH: REASON`; no temporary left",
    ),
    (
        "`-o`, `--patches-csv` or `--png-dir` in a folder that cannot be written (read-only,"
        " missing parent that cannot be made), or naming a folder",
        "refused before any work: `lightinv-cli: error: cannot write PATH: Read-only file"
        " system in FOLDER; choose another path`, status 2",
    ),
    (
        "the final write fails after the work (disk full, folder removed meanwhile)",
        "nothing computed is lost: the result goes beside the asked path as"
        " `NAME.unsaved-TIME.EXT` (else the user data folder `lightinv/unsaved`, else the"
        " temporary folder), the summary is printed, and `could not write the project PATH:"
        " REASON; it was written to OTHER instead`, status 2",
    ),
    (
        "the window restarted in a container after a crash, with the crashed session's process id",
        "the crashed session's autosave is offered for recovery; sessions are told apart"
        " by a lock each holds while it lives, not by process id (before, the new session"
        " took the autosave for its own and deleted it; `tests/app/test_recovery.py`)",
    ),
    (
        "two processes build the same operator at once",
        "both finish; the cache holds one whole file (the last rename wins) and the next"
        " run loads it",
    ),
)
"""(case, what happens) for outputs and command-line arguments: tested in
tests/core/test_atomic.py and tests/core/test_cli.py."""

FOOTER = (
    "\n## Outputs and the command line\n\n"
    "Tested in `tests/core/test_atomic.py` and `tests/core/test_cli.py`:\n\n"
    "| case | what happens |\n|---|---|\n"
    + "".join(f"| {case} | {what} |\n" for case, what in OUTPUT_CASES)
)


def photometry_rows(folder: Path) -> str:
    """The photometric-file section: every case of ``BAD_PHOTOMETRY_CASES``
    (tests/core/test_photometry.py) read once, its message as the user sees it."""
    from lightinv_core.luminaires import read_photometry
    from tests.core.test_photometry import BAD_PHOTOMETRY_CASES

    rows = []
    for description, text, _ in BAD_PHOTOMETRY_CASES:
        kind, _, what = description.partition(": ")
        path = folder / ("case.ldt" if kind == "LDT" else "case.ies")
        path.write_bytes(text.encode("utf-8"))
        got = raised(lambda path=path: read_photometry(path))
        message = str(got).replace(str(folder), "<dir>")
        rows.append(f"| {kind} | {what} | `{type(got).__name__}` | {code(message)} |\n")
    return (
        "\n## Photometric files\n\n"
        "IES LM-63 and EULUMDAT files (`lightinv_core/luminaires`, docs/photometry.md), from"
        " `BAD_PHOTOMETRY_CASES` in `tests/core/test_photometry.py`, which also fuzzes"
        " mutated files (400 per run; 20,000 tried once): only `PhotometryError` or a valid"
        " table, never another exception. A luminaire schedule naming a bad file gives the"
        " same message after the schedule's own file and line.\n\n"
        "| format | input tried | raises | what the user sees |\n|---|---|---|---|\n"
        + "".join(rows)
    )


def render(outcomes, photometry: str = "") -> str:
    rows = []
    for c in CASES:
        result, text = outcomes[c.id]
        kind = "warning" if c.expect == WARNING else f"`{type(result).__name__}`"
        rows.append(f"| {c.area} | {c.tried} | {kind} | {code(text)} |\n")
    return HEADER + "".join(rows) + photometry + FOOTER


def test_docs_table_matches_the_messages(outcomes, tmp_path):
    text = render(outcomes, photometry_rows(tmp_path))
    if os.environ.get("LIGHTINV_WRITE_DOCS") == "1":
        DOC.write_text(text, encoding="utf-8")
        return
    assert DOC.exists() and DOC.read_text(encoding="utf-8") == text, (
        f"{DOC.relative_to(ROOT)} is out of date with the messages of the catalogue; "
        "regenerate it with LIGHTINV_WRITE_DOCS=1 .venv/bin/python -m pytest "
        "tests/core/test_bad_input.py"
    )
