"""Import glTF 2.0 (.gltf, .glb) and PLY room models as LightInv scenes, through trimesh.

trimesh decodes the files (buffers, accessors, node transforms); this module names the
lighting groups, guesses reflectances from the materials' colours, joins coplanar
triangles back into polygons (``facets``) and hands everything to the OBJ importer's
``assemble_scene``, so meshing, size checks, duplicate checks and ``zone:NAME:KIND``
emitter zones work as for OBJ files. The user guide is docs/obj-import.md.

Units: metres (glTF is in metres by its specification; PLY has no unit) times ``scale``.
Up axis: glTF is y-up by its specification, so ``up`` defaults to "y" for glTF and to
"z" for PLY. Faces keep their winding (counter-clockwise seen from the front; a node
whose transform mirrors the model has its faces turned back, as glTF specifies).
"""

from __future__ import annotations

import io
import json
import os
import stat
import struct
from bisect import bisect_right
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from lightinv_core.errors import ObjImportError
from lightinv_core.scene.facets import join_coplanar
from lightinv_core.scene.import_report import ImportItem
from lightinv_core.scene.loading import default_up
from lightinv_core.scene.model import Scene
from lightinv_core.scene.obj_geometry import z_up
from lightinv_core.scene.obj_import import Places, assemble_scene, check_options
from lightinv_core.scene.obj_parse import (
    LISTED,
    MAX_COORD,
    ObjData,
    ObjFace,
    clip,
    load_materials,
)
from lightinv_core.scene.obj_size import ObjCounts, check_counts

GLTF_SUFFIXES = (".gltf", ".glb")
MESH_SUFFIXES = (*GLTF_SUFFIXES, ".ply")
GROUP_BY = ("node", "material")
GLB_MAGIC = b"glTF"
GLB_JSON = 0x4E4F534A  # chunk type "JSON"
TEXTURE_SAMPLES = 256  # a texture's mean colour is taken over 256 x 256 samples
OPAQUE = 0.5  # a base colour alpha below this (alphaMode BLEND) is called transparent


@dataclass
class Part:
    """Triangles of one glTF node primitive (or a PLY colour): world coordinates in model
    units, the lighting group, the material name (None: no material) and where it came from."""

    vertices: np.ndarray
    triangles: np.ndarray
    group: str
    material: str | None
    label: str  # "node 'Wall'" in messages


@dataclass
class Model:
    """What a reader found: parts, material colours as reflectance guesses, warnings."""

    parts: list[Part]
    colours: dict[str, float] = field(default_factory=dict)
    warnings: list[str] = field(default_factory=list)
    colour_source: str = "glTF baseColor"
    left: list[ImportItem] = field(default_factory=list)  # what the reader left out


def load_mesh(
    path: str | os.PathLike,
    materials: dict | str | os.PathLike | None = None,
    resolution: float = 0.25,
    scale: float = 1.0,
    up: str | None = None,
    skip_degenerate: bool = False,
    name: str | None = None,
    group_by: str = "node",
) -> Scene:
    """Import the glTF (.gltf, .glb) or PLY file ``path`` as a Scene (metres, z up).

    Parameters
    ----------
    materials : reflectances by group and material name, as for ``load_obj``.
    resolution : target patch edge length in metres.
    scale : metres per model unit (glTF: 1, its unit is the metre).
    up : "z" or "y", the model's up axis; None: the format's ("y" for glTF, "z" for PLY).
    skip_degenerate : drop zero-area triangles (with a warning) instead of raising.
    name : scene name; default the file name without extension.
    group_by : "node" (glTF node names become lighting groups) or "material"
        (material names do). PLY files have neither: faces are grouped by colour.

    Returns a Scene whose ``info`` holds ``"source"`` and ``"warnings"``. Raises
    ObjImportError for anything wrong with the file, the materials or the options.
    """
    suffix = Path(os.fspath(path)).suffix.lower() if isinstance(path, str | os.PathLike) else ""
    fmt = "PLY" if suffix == ".ply" else "glTF"
    up = default_up(path) if up is None and suffix else up
    path, res, scale = check_options(path, resolution, scale, up, fmt)
    if suffix not in MESH_SUFFIXES:
        raise ObjImportError(
            f"{path.name}: not a glTF or PLY file (the name must end in .gltf, .glb or .ply)"
        )
    if group_by not in GROUP_BY:
        raise ObjImportError(
            f"group_by={group_by!r} is not supported; use 'node' (node names become "
            "lighting groups) or 'material' (material names do)"
        )
    mats = load_materials(materials)
    _check_file(path, f"{fmt} file")
    fname = path.name
    if fmt == "PLY":
        check_counts(ply_counts(path), fname)
        model = read_ply(path)
    else:
        header, binary = read_gltf_header(path)
        check_counts(gltf_counts(header, path), fname)
        model = read_gltf(path, header, binary, group_by)
    data, places = _faces(model, path, scale, up)
    places.item_kind = "PLY colour" if fmt == "PLY" else f"glTF {group_by}"
    return assemble_scene(
        data, places, mats, model.colours, res, scale, skip_degenerate, name, tuple(model.left)
    )


def _check_file(path: Path, what: str) -> None:
    try:
        mode = os.stat(path).st_mode
    except FileNotFoundError:
        raise ObjImportError(f"{what} '{path}' does not exist; check the path") from None
    except (OSError, ValueError) as exc:
        raise ObjImportError(f"cannot read {what} '{path}': {exc}") from None
    if not stat.S_ISREG(mode):
        raise ObjImportError(
            f"{what} '{path}' is not a file (a folder or device); give the path of the file"
        )


# --- glTF ----------------------------------------------------------------------------------


def read_gltf_header(path: Path) -> tuple[dict, bytes | None]:
    """The JSON of a .gltf or .glb file and, for .glb, the rest of the file after the JSON
    chunk (its binary buffer); ObjImportError if it is not glTF 2.0."""
    fname = path.name
    try:
        raw = path.read_bytes()
    except OSError as exc:
        raise ObjImportError(
            f"cannot read glTF file '{path}': {exc.strerror or exc}; check that it is readable"
        ) from None
    binary = None
    if path.suffix.lower() == ".glb" or raw[:4] == GLB_MAGIC:
        if len(raw) < 20 or raw[:4] != GLB_MAGIC:
            raise ObjImportError(
                f"{fname}: not a binary glTF (GLB) file (it does not start with 'glTF'); "
                "export the model as glTF 2.0 binary (.glb)"
            )
        version, _length = struct.unpack_from("<II", raw, 4)
        if version != 2:
            raise ObjImportError(
                f"{fname}: glTF version {version} is not supported; export it as glTF 2.0"
            )
        size, kind = struct.unpack_from("<II", raw, 12)
        if kind != GLB_JSON or 20 + size > len(raw):
            raise ObjImportError(
                f"{fname}: the GLB file is truncated or damaged (no complete JSON chunk); "
                "export it again"
            )
        text, binary = raw[20 : 20 + size], raw[20 + size :]
    else:
        text = raw
    try:
        header = json.loads(text.decode("utf-8-sig"))
    except (UnicodeDecodeError, json.JSONDecodeError, RecursionError) as exc:
        reason = exc.msg if isinstance(exc, json.JSONDecodeError) else type(exc).__name__
        raise ObjImportError(
            f"{fname}: not a glTF file (its JSON cannot be read: {reason}); export the "
            "model as glTF 2.0 (.gltf or .glb)"
        ) from None
    if not isinstance(header, dict) or not isinstance(header.get("asset"), dict):
        raise ObjImportError(
            f'{fname}: not a glTF file (no "asset" object); export the model as glTF 2.0'
        )
    version = str(header["asset"].get("version", "?"))
    if not version.startswith("2"):
        raise ObjImportError(
            f"{fname}: glTF version {clip(version)} is not supported; export it as glTF 2.0"
        )
    required = header.get("extensionsRequired")
    packed = [x for x in COMPRESSED if isinstance(required, list) and x in required]
    if packed:
        raise ObjImportError(
            f"{fname}: its meshes are compressed ({packed[0]}), which LightInv cannot "
            "decode; export the model without mesh compression"
        )
    return header, binary


COMPRESSED = ("KHR_draco_mesh_compression", "EXT_meshopt_compression")
"""Mesh compressions trimesh cannot decode without further packages: refused up front
(decoded as zeros they would turn into a wall of degenerate triangles)."""


def _items(header: dict, key: str) -> list:
    value = header.get(key, [])
    return value if isinstance(value, list) else []


def gltf_counts(header: dict, path: Path) -> ObjCounts:
    """Vertices and triangles the file's scene holds (from its accessors, per use of
    each mesh by a node), for the size check before decoding."""
    accessors, uses = _items(header, "accessors"), {}
    for node in _items(header, "nodes"):
        if isinstance(node, dict) and isinstance(node.get("mesh"), int):
            uses[node["mesh"]] = uses.get(node["mesh"], 0) + 1
    meshes = _items(header, "meshes")
    vertices = triangles = 0
    for m, n in uses.items():
        if not 0 <= m < len(meshes) or not isinstance(meshes[m], dict):
            continue
        for prim in _items(meshes[m], "primitives"):
            if not isinstance(prim, dict):
                continue
            pos = _count(accessors, (prim.get("attributes") or {}).get("POSITION"))
            idx = _count(accessors, prim.get("indices"))
            vertices += n * pos
            triangles += n * ((idx if "indices" in prim else pos) // 3)
    return ObjCounts(vertices, triangles, path.stat().st_size)


def _count(accessors: list, k) -> int:
    if isinstance(k, int) and 0 <= k < len(accessors) and isinstance(accessors[k], dict):
        c = accessors[k].get("count", 0)
        return c if isinstance(c, int) and c > 0 else 0
    return 0


def _renamed(header: dict) -> dict:
    """A copy of the header whose nodes, meshes and materials are named by their index
    (n3, m0, k2): trimesh makes names unique in its own way, and these map back."""
    out = dict(header)
    for key, tag in (("nodes", "n"), ("meshes", "m"), ("materials", "k")):
        out[key] = [
            {**item, "name": f"{tag}{i}"} if isinstance(item, dict) else item
            for i, item in enumerate(_items(header, key))
        ]
    return out


def _glb(header: dict, binary: bytes) -> bytes:
    text = json.dumps(header).encode()
    text += b" " * (-len(text) % 4)
    body = struct.pack("<II", len(text), GLB_JSON) + text + binary
    return GLB_MAGIC + struct.pack("<II", 2, 12 + len(body)) + body


def read_gltf(path: Path, header: dict, binary: bytes | None, group_by: str) -> Model:
    """Decode the glTF scene with trimesh: one Part per node primitive, in world
    coordinates (node transforms applied), with lighting group and material."""
    import trimesh

    fname = path.name
    renamed = _renamed(header)
    if binary is None:
        data, kind = json.dumps(renamed).encode(), "gltf"
    else:
        data, kind = _glb(renamed, binary), "glb"
    try:
        scene = trimesh.load_scene(
            io.BytesIO(data),
            file_type=kind,
            resolver=trimesh.resolvers.FilePathResolver(str(path)),
        )
    except Exception as exc:  # trimesh raises many kinds on a damaged file
        raise ObjImportError(
            f"{fname}: cannot decode the glTF file ({type(exc).__name__}: {_short(exc)}); "
            "export it again as glTF 2.0"
        ) from None
    nodes, meshes = _items(header, "nodes"), _items(header, "meshes")
    names = _material_names(_items(header, "materials"))
    model = Model([])
    skipped = 0
    for frame in sorted(scene.graph.nodes_geometry, key=lambda f: _order(scene, f)):
        transform, gname = scene.graph[frame]
        geom = scene.geometry[gname]
        if not isinstance(geom, trimesh.Trimesh):
            skipped += 1
            i = _order(scene, frame)[0]
            node = nodes[i] if 0 <= i < len(nodes) and isinstance(nodes[i], dict) else {}
            why = "lines or points: LightInv reads triangles only"
            label = _node_label(node, meshes, i)
            model.left.append(ImportItem("glTF primitive", label, "dropped", None, why))
            continue
        if len(geom.faces) == 0:
            continue
        i = _order(scene, frame)[0]
        mat = _material_index(geom)
        node = nodes[i] if 0 <= i < len(nodes) and isinstance(nodes[i], dict) else {}
        label = _node_label(node, meshes, i)
        material = names.get(mat) if mat is not None else None
        group = label if group_by == "node" else (material or "default")
        v = np.asarray(geom.vertices, float) @ transform[:3, :3].T + transform[:3, 3]
        tri = np.asarray(geom.faces, np.int64)
        if np.linalg.det(transform[:3, :3]) < 0:  # a mirroring node turns faces around
            tri = tri[:, ::-1]
        model.parts.append(Part(v, tri, group, material, f"node {clip(label)}"))
    if skipped:
        model.warnings.append(
            f"{fname}: ignored {skipped} primitive(s) of lines or points; LightInv reads "
            "triangles only"
        )
    if not model.parts:
        raise ObjImportError(
            f"{fname}: no triangles found in its scene; export the model's meshes (not only "
            "lines, points, cameras or lights)"
        )
    used = {p.material for p in model.parts}
    model.colours = _colours(header, scene, names, used, fname, model.warnings)
    return model


def _order(scene, frame: str) -> tuple[int, int]:
    """(node index, primitive index) of a trimesh frame, from our renaming: frames are
    'n3' (or 'n3_ab12f0', a random tag, for each primitive of a node with several) and
    geometries 'm0', 'm0_1', 'm0_2' for a mesh's primitives in file order."""
    head = frame.split("_", 1)[0]
    node = int(head[1:]) if head[1:].isdigit() else 1 << 30
    tail = scene.graph[frame][1].rpartition("_")[2]
    return node, int(tail) if "_" in scene.graph[frame][1] and tail.isdigit() else 0


def _material_index(geom) -> int | None:
    mat = getattr(getattr(geom, "visual", None), "material", None)
    name = getattr(mat, "name", None)
    if isinstance(name, str) and name.startswith("k") and name[1:].isdigit():
        return int(name[1:])
    return None


def _node_label(node: dict, meshes: list, i: int) -> str:
    """A node's name; an unnamed node takes its mesh's name, else 'node N'."""
    name = node.get("name")
    if isinstance(name, str) and name.strip():
        return name.strip()
    m = node.get("mesh")
    if isinstance(m, int) and 0 <= m < len(meshes) and isinstance(meshes[m], dict):
        mname = meshes[m].get("name")
        if isinstance(mname, str) and mname.strip():
            return mname.strip()
    return f"node {i}"


def _material_names(materials: list) -> dict[int, str]:
    """Material index -> its name, made unique ('Paint', 'Paint #3'); unnamed ones
    'material N'."""
    out: dict[int, str] = {}
    taken: set[str] = set()
    for k, m in enumerate(materials):
        name = m.get("name") if isinstance(m, dict) else None
        name = name.strip() if isinstance(name, str) and name.strip() else f"material {k}"
        if name in taken:
            name = f"{name} #{k}"
        taken.add(name)
        out[k] = name
    return out


def _colours(header, scene, names, used, fname, warnings) -> dict[str, float]:
    """Reflectance guess per used material: the luminance 0.2126 R + 0.7152 G + 0.0722 B
    of its linear baseColorFactor times the mean linear colour of its baseColorTexture."""
    materials = _items(header, "materials")
    textures = _textures(scene)
    out: dict[str, float] = {}
    transparent = []
    for k, name in names.items():
        if name not in used:
            continue
        m = materials[k] if isinstance(materials[k], dict) else {}
        pbr = m.get("pbrMetallicRoughness") or {}
        factor = pbr.get("baseColorFactor", [1.0, 1.0, 1.0, 1.0])
        try:
            rgba = np.array(factor, dtype=float).reshape(4)
        except (TypeError, ValueError):
            warnings.append(
                f"{fname}: material {clip(name)} has an unreadable baseColorFactor "
                f"{clip(str(factor))}; it gets the default reflectance"
            )
            continue
        if not np.all(np.isfinite(rgba)) or np.any(rgba < 0):
            continue
        rgb = rgba[:3]
        if "baseColorTexture" in pbr and k in textures:
            rgb = rgb * textures[k]
        out[name] = float(0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2])
        ext = m.get("extensions") or {}
        see_through = m.get("alphaMode") == "BLEND" and rgba[3] < OPAQUE
        if see_through or "KHR_materials_transmission" in ext:
            transparent.append(name)
    if transparent:
        shown = ", ".join(clip(n) for n in transparent[:LISTED])
        warnings.append(
            f"{fname}: material(s) {shown} are transparent; LightInv treats every surface as "
            "opaque, so model glass as an emitter zone (zone:NAME:skylight) or give it a "
            "reflectance in the materials mapping"
        )
    return out


def _textures(scene) -> dict[int, np.ndarray]:
    """Mean linear RGB of each material's baseColorTexture (material index -> (3,))."""
    out = {}
    for geom in scene.geometry.values():
        k = _material_index(geom)
        if k is None or k in out:
            continue
        image = getattr(geom.visual.material, "baseColorTexture", None)
        if image is None:
            continue
        try:
            from PIL import Image

            small = image.convert("RGB").resize(
                (TEXTURE_SAMPLES, TEXTURE_SAMPLES), Image.Resampling.NEAREST
            )
        except Exception:  # no Pillow, or an image it cannot convert: the factor alone
            continue
        out[k] = srgb_to_linear(np.asarray(small, float) / 255.0).reshape(-1, 3).mean(axis=0)
    return out


def srgb_to_linear(c: np.ndarray) -> np.ndarray:
    """sRGB-encoded values in [0, 1] to linear light (IEC 61966-2-1)."""
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def _short(exc: Exception, n: int = 80) -> str:
    text = " ".join(str(exc).split()) or "no details"
    return text if len(text) <= n else text[:n] + "..."


# --- PLY -----------------------------------------------------------------------------------


def ply_counts(path: Path) -> ObjCounts:
    """Vertices and faces a PLY file declares in its header (``element vertex N``,
    ``element face M``); ObjImportError if it has no PLY header."""
    fname = path.name
    with open(path, "rb") as fh:
        head = fh.read(1 << 16)
    if not head.startswith(b"ply"):
        raise ObjImportError(
            f"{fname}: not a PLY file (it does not start with 'ply'); export the model as "
            "Stanford PLY"
        )
    end = head.find(b"end_header")
    if end < 0:
        raise ObjImportError(f"{fname}: the PLY header has no end_header line; export it again")
    counts = {}
    for line in head[:end].decode("latin-1").splitlines():
        words = line.split()
        if len(words) == 3 and words[0] == "element" and words[2].isdigit():
            counts[words[1]] = int(words[2])
    return ObjCounts(counts.get("vertex", 0), counts.get("face", 0), path.stat().st_size)


def read_ply(path: Path) -> Model:
    """Decode a PLY file with trimesh: one Part per face colour (group ``colour #RRGGBB``,
    reflectance guess the colour's linear luminance), or one Part named after the file."""
    import trimesh

    fname = path.name
    try:
        scene = trimesh.load_scene(str(path), file_type="ply", process=False)
    except Exception as exc:  # trimesh raises many kinds on a damaged file
        raise ObjImportError(
            f"{fname}: cannot decode the PLY file ({type(exc).__name__}: {_short(exc)}); "
            "export it again"
        ) from None
    geometry = list(scene.geometry.values())
    mesh = geometry[0] if len(geometry) == 1 else None
    faces = getattr(mesh, "faces", None)
    if faces is None or len(faces) == 0:
        raise ObjImportError(
            f"{fname}: no faces found ({len(getattr(mesh, 'vertices', []))} vertices); "
            "export the model as a polygon mesh, not a point cloud"
        )
    v = np.asarray(mesh.vertices, float)
    tri = np.asarray(faces, np.int64)
    _check_vertex_numbers(tri, len(v), path)
    if getattr(mesh.visual, "kind", None) != "face":
        return Model([Part(v, tri, path.stem, None, f"{clip(path.stem)}")], {}, [], "PLY colour")
    rgb = np.asarray(mesh.visual.face_colors)[:, :3]
    colours, which = np.unique(rgb, axis=0, return_inverse=True)
    model = Model([], {}, [], "PLY colour")
    for c, colour in enumerate(colours):
        group = "colour #{:02X}{:02X}{:02X}".format(*colour.tolist())
        model.parts.append(Part(v, tri[which.ravel() == c], group, group, clip(group)))
        lin = srgb_to_linear(colour / 255.0)
        model.colours[group] = float(0.2126 * lin[0] + 0.7152 * lin[1] + 0.0722 * lin[2])
    return model


def _check_vertex_numbers(tri: np.ndarray, nv: int, path: Path) -> None:
    """ObjImportError naming the first face whose vertex numbers are not those of a
    vertex of the file (0 to nv - 1; trimesh passes them through unchecked)."""
    bad = np.flatnonzero(((tri < 0) | (tri >= nv)).any(axis=1))
    if len(bad) == 0:
        return
    k = int(bad[0])
    number = int(tri[k][(tri[k] < 0) | (tri[k] >= nv)][0])
    # trimesh splits polygons into triangles: the triangle is the face when the file
    # declares as many faces as there are triangles.
    declared = ply_counts(path).faces
    where = f"face {k + 1:,}"
    if declared != len(tri):
        where = f"triangle {k + 1:,} (of its faces split)"
    has = f"{nv:,} vertices (numbered 0 to {nv - 1:,})" if nv else "no vertices"
    raise ObjImportError(
        f"{path.name}: {where} names vertex {number:,}, but the file has {has}; the file "
        "is damaged, export it again"
    )


# --- to the OBJ importer's faces -------------------------------------------------------------


class FacePlaces(Places):
    """Messages about triangles of a mesh file: numbered within their node (or colour)."""

    what = "model"

    def __init__(
        self, path: Path, starts: list[int], labels: list[str], colour: str, noun="triangle"
    ):
        super().__init__(path)
        self.starts, self.labels, self.colour, self.noun = starts, labels, colour, noun

    def at(self, line: int) -> str:
        return ""

    def within(self, line: int) -> str:
        return ""

    def many(self, lines: list[int]) -> str:
        by_part: dict[int, list[int]] = {}
        for n in lines:
            k = bisect_right(self.starts, n) - 1
            by_part.setdefault(k, []).append(n - self.starts[k] + 1)
        out = []
        for k, nums in list(by_part.items())[:LISTED]:
            shown = ", ".join(str(n) for n in nums[:LISTED])
            more = f" and {len(nums) - LISTED} more" if len(nums) > LISTED else ""
            noun = self.noun if len(nums) == 1 else self.noun + "s"
            out.append(f"{noun} {shown}{more} of {self.labels[k]}")
        if len(by_part) > LISTED:
            out.append(f"{len(by_part) - LISTED} more parts")
        return "; ".join(out)


def _faces(model: Model, path: Path, scale: float, up: str) -> tuple[ObjData, FacePlaces]:
    """The parts as the OBJ importer's faces: coordinates in metres, z up; coplanar
    triangles of one group and material joined into polygons."""
    fname = path.name
    verts, tris, keys, starts, labels = [], [], [], [], []
    offset = count = 0
    kinds: dict[tuple[str, str | None], int] = {}
    for part in model.parts:
        v = z_up(part.vertices * scale, up)
        big = ~(np.abs(v) <= MAX_COORD).all(axis=1)
        if big.any():
            what = "not finite" if not np.all(np.isfinite(v)) else f"larger than {MAX_COORD:g} m"
            raise ObjImportError(
                f"{fname}: {part.label} has a coordinate that is {what} after scaling by "
                f"{scale:g}; check the model's units and the scale"
            )
        verts.append(v)
        tris.append(part.triangles + offset)
        keys.append(
            np.full(len(part.triangles), kinds.setdefault((part.group, part.material), len(kinds)))
        )
        starts.append(count + 1)
        labels.append(part.label)
        offset += len(v)
        count += len(part.triangles)
    tri = np.concatenate(tris)
    key = np.concatenate(keys)
    facets = join_coplanar(np.concatenate(verts), tri, key)
    part_of = np.repeat(np.arange(len(model.parts)), [len(p.triangles) for p in model.parts])
    faces = []
    joined = sorted(
        [
            (int(f), tuple(int(i) for i in poly))
            for f, poly in zip(facets.first, facets.polygons, strict=True)
        ]
        + [(int(f), tuple(int(i) for i in facets.triangles[f])) for f in facets.left]
    )
    for first, index in joined:
        part = model.parts[part_of[first]]
        faces.append(ObjFace(index, first + 1, part.group, part.material))
    data = ObjData(facets.vertices, faces, [], list(model.warnings))
    return data, FacePlaces(path, starts, labels, model.colour_source)
