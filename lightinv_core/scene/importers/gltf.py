"""Import a glTF 2.0 (.gltf, .glb) room model as a LightInv scene, through trimesh.

trimesh decodes the file (buffers, accessors, node transforms); this module names the
lighting groups (node or material names) and guesses reflectances from the materials'
colours; ``meshes.import_mesh`` does the rest, as for PLY files. The user guide is
docs/obj-import.md.

Units: metres (by glTF's specification) times ``scale``. Up axis: glTF is y-up by its
specification, so ``up`` defaults to "y". Faces keep their winding (counter-clockwise
seen from the front; a node whose transform mirrors the model has its faces turned
back, as glTF specifies).
"""

from __future__ import annotations

import io
import json
import os
import struct
from pathlib import Path

import numpy as np

from lightinv_core.errors import ObjImportError
from lightinv_core.scene.importers.faces import LISTED, clip
from lightinv_core.scene.importers.meshes import Model, Part, import_mesh, short, srgb_to_linear
from lightinv_core.scene.importers.report import ImportItem
from lightinv_core.scene.importers.size import ModelCounts, check_counts
from lightinv_core.scene.model import Scene

SUFFIXES = (".gltf", ".glb")
GROUP_BY = ("node", "material")
GLB_MAGIC = b"glTF"
GLB_JSON = 0x4E4F534A  # chunk type "JSON"
TEXTURE_SAMPLES = 256  # a texture's mean colour is taken over 256 x 256 samples
OPAQUE = 0.5  # a base colour alpha below this (alphaMode BLEND) is called transparent


def load_gltf(
    path: str | os.PathLike,
    materials: dict | str | os.PathLike | None = None,
    resolution: float = 0.25,
    scale: float = 1.0,
    up: str = "y",
    skip_degenerate: bool = False,
    name: str | None = None,
    group_by: str = "node",
) -> Scene:
    """Import the glTF file ``path`` (.gltf or .glb) as a Scene (metres, z up).

    Parameters
    ----------
    materials : reflectances by group and material name, as for ``load_obj``.
    resolution : target patch edge length in metres.
    scale : metres per model unit (1: glTF's unit is the metre).
    up : "y" (glTF's specification) or "z", the model's up axis.
    skip_degenerate : drop zero-area triangles (with a warning) instead of raising.
    name : scene name; default the file name without extension.
    group_by : "node" (glTF node names become lighting groups) or "material"
        (material names do).

    Returns a Scene whose ``info`` holds ``"source"`` and ``"warnings"``. Raises
    ObjImportError for anything wrong with the file, the materials or the options.
    """
    if group_by not in GROUP_BY:
        raise ObjImportError(
            f"group_by={group_by!r} is not supported; use 'node' (node names become "
            "lighting groups) or 'material' (material names do)"
        )

    def read(path: Path) -> Model:
        header, binary = read_gltf_header(path)
        check_counts(gltf_counts(header, path), path.name)
        return read_gltf(path, header, binary, group_by)

    return import_mesh(
        path,
        "glTF",
        SUFFIXES,
        read,
        f"glTF {group_by}",
        materials,
        resolution,
        scale,
        up,
        skip_degenerate,
        name,
    )


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


def gltf_counts(header: dict, path: Path) -> ModelCounts:
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
    return ModelCounts(vertices, triangles, path.stat().st_size)


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
            f"{fname}: cannot decode the glTF file ({type(exc).__name__}: {short(exc)}); "
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
