#!/usr/bin/env python3
"""Writes examples/3d/gltf-scene/scene.gltf, the glTF scene example (docs/GLTF.md, "Scenes (3-D)").

A cushion (a box 80 x 40 x 80 mm) on a floor (a plane 300 x 300 mm), in glTF's frame and units
(metres, y up, z toward the user). The cushion's glTF material binds a Sandpaper library entry by
name, `extras.sandpaper.material` = "corduroy", its UVs one unit per 100 mm of surface
(`extras.sandpaper.uv_size_m`), so the corduroy keeps its own scale on every face. The floor's mesh
names an MPEG_haptic_material (ISO/IEC 23090-14) as another tool would write one: 8-bit stiffness
and friction textures, read by Sandpaper as 0.6 of 2,000 N/m and a coefficient of 0.35.

Python 3 standard library only. Run from anywhere: python3 tools/make_gltf_scene_example.py
"""
import base64
import json
import pathlib
import struct
import zlib

ROOT = pathlib.Path(__file__).resolve().parent.parent
OUT = ROOT / "examples" / "3d" / "gltf-scene" / "scene.gltf"
UV_UNIT_M = 0.1  # metres of surface per unit of u and v on the cushion


def png8(width, height, value):
    """An 8-bit greyscale PNG of one value: a texture of values as any tool writes one."""
    raw = b"".join(b"\x00" + bytes([value]) * width for _ in range(height))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    header = struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")


def face(centre, u_axis, v_axis, half_u, half_v):
    """Four corners counter-clockwise seen from outside (normal = u x v), with UVs laid as a patch's
    glTF export lays them: u = a / unit + 0.5, v = 0.5 - b / unit for a point a along u, b along v."""
    corners, uvs = [], []
    for a, b in ((-half_u, -half_v), (half_u, -half_v), (half_u, half_v), (-half_u, half_v)):
        corners.append([centre[i] + a * u_axis[i] + b * v_axis[i] for i in range(3)])
        uvs.append([a / UV_UNIT_M + 0.5, 0.5 - b / UV_UNIT_M])
    return corners, uvs


def box(centre, size):
    """Six faces, each its own four vertices (so each has its own UVs)."""
    w, h, d = (s / 2 for s in size)
    x, y, z = centre
    faces = [  # (face centre, u axis, v axis, half u, half v)
        ((x, y + h, z), (1, 0, 0), (0, 0, -1), w, d),   # top, +y
        ((x, y - h, z), (1, 0, 0), (0, 0, 1), w, d),    # bottom, -y
        ((x + w, y, z), (0, 0, -1), (0, 1, 0), d, h),   # right, +x
        ((x - w, y, z), (0, 0, 1), (0, 1, 0), d, h),    # left, -x
        ((x, y, z + d), (1, 0, 0), (0, 1, 0), w, h),    # front, +z
        ((x, y, z - d), (-1, 0, 0), (0, 1, 0), w, h),   # back, -z
    ]
    positions, uvs, indices = [], [], []
    for f in faces:
        corners, face_uvs = face(*f)
        base = len(positions)
        positions += corners
        uvs += face_uvs
        indices += [base, base + 1, base + 2, base, base + 2, base + 3]
    return positions, uvs, indices


class Buffer:
    def __init__(self):
        self.data = bytearray()
        self.views, self.accessors = [], []

    def view(self, data):
        while len(self.data) % 4:
            self.data += b"\x00"
        self.views.append({"buffer": 0, "byteOffset": len(self.data), "byteLength": len(data)})
        self.data += data
        return len(self.views) - 1

    def floats(self, rows, kind):
        flat = [c for row in rows for c in row]
        accessor = {"bufferView": self.view(struct.pack("<%df" % len(flat), *flat)), "componentType": 5126,
                    "count": len(rows), "type": kind}
        if kind == "VEC3":  # glTF requires POSITION's bounds
            accessor["min"] = [min(r[i] for r in rows) for i in range(3)]
            accessor["max"] = [max(r[i] for r in rows) for i in range(3)]
        self.accessors.append(accessor)
        return len(self.accessors) - 1

    def indices(self, values):
        self.accessors.append({"bufferView": self.view(struct.pack("<%dH" % len(values), *values)),
                               "componentType": 5123, "count": len(values), "type": "SCALAR"})
        return len(self.accessors) - 1


def main():
    buf = Buffer()
    meshes, materials = [], []

    # The cushion: corduroy by name, its UVs one unit per 100 mm.
    positions, uvs, indices = box((0.0, 0.02, 0.0), (0.08, 0.04, 0.08))
    materials.append({"name": "fabric", "pbrMetallicRoughness": {"baseColorFactor": [0.45, 0.3, 0.2, 1]},
                      "extras": {"sandpaper": {"material": "corduroy", "uv_size_m": [UV_UNIT_M, UV_UNIT_M]}}})
    meshes.append({"name": "cushion", "primitives": [{
        "attributes": {"POSITION": buf.floats(positions, "VEC3"), "TEXCOORD_0": buf.floats(uvs, "VEC2")},
        "indices": buf.indices(indices), "material": 0}]})

    # The floor: an MPEG_haptic_material with stiffness and friction textures, as another tool writes.
    corners, floor_uvs = face((0.0, 0.0, 0.0), (1, 0, 0), (0, 0, -1), 0.15, 0.15)
    materials.append({"name": "rubber floor", "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.2, 0.22, 1]}})
    meshes.append({"name": "floor", "primitives": [{
        "attributes": {"POSITION": buf.floats(corners, "VEC3"), "TEXCOORD_0": buf.floats(floor_uvs, "VEC2")},
        "indices": buf.indices([0, 1, 2, 0, 2, 3]), "material": 1}],
        "extensions": {"MPEG_haptic_material": {"hapticMaterialIndex": 0}}})
    images = [{"bufferView": buf.view(png8(4, 4, 153)), "mimeType": "image/png", "name": "floor stiffness"},
              {"bufferView": buf.view(png8(4, 4, 89)), "mimeType": "image/png", "name": "floor friction"}]

    asset = {
        "asset": {"version": "2.0", "generator": "tools/make_gltf_scene_example.py (Sandpaper)"},
        "extensionsUsed": ["MPEG_haptic_material"],
        "extensions": {"MPEG_haptic_material": {"materials": [{
            "name": "rubber floor",
            "stiffness": [{"texture": {"index": 0}, "type": "High_Resolution"}],
            "friction": [{"texture": {"index": 1}, "type": "High_Resolution"}]}]}},
        "scene": 0,
        "scenes": [{"name": "cushion on a floor", "nodes": [0, 1]}],
        "nodes": [{"name": "cushion", "mesh": 0, "translation": [0.0, 0.0, 0.02]},
                  {"name": "floor", "mesh": 1}],
        "meshes": meshes,
        "materials": materials,
        "samplers": [{"magFilter": 9728, "minFilter": 9728}],
        "textures": [{"source": 0, "sampler": 0}, {"source": 1, "sampler": 0}],
        "images": images,
        "accessors": buf.accessors,
        "bufferViews": buf.views,
        "buffers": [{"byteLength": len(buf.data),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(buf.data)).decode()}],
    }
    OUT.parent.mkdir(parents=True, exist_ok=True)
    OUT.write_text(json.dumps(asset, indent=1) + "\n")
    print("wrote %s (%d bytes)" % (OUT.relative_to(ROOT), OUT.stat().st_size))


if __name__ == "__main__":
    main()
