#!/usr/bin/env python3
"""Writes the glTF test models of rastray (standard library only; run from the crate root).

    python3 tests/data/gltf/make_models.py

Outputs (see README.md beside this script for what each one exercises):
  tests/data/gltf/box.glb                 binary glTF, one red box under a rotating parent node
  tests/data/gltf/box.gltf + "box data.bin"  the same box as JSON with an external buffer
  tests/data/gltf/scene.gltf              embedded buffer; node hierarchy, three materials,
                                          strip, fan, mirrored node, lines and points
  scenes/models/suzanne.glb               Blender's Suzanne from tests/data/suzanne.obj, with
                                          its normals and a yellow plastic material
"""

import base64
import json
import math
import os
import struct

FLOAT, UBYTE, USHORT = 5126, 5121, 5123
TRIANGLES, POINTS, LINES, STRIP, FAN = 4, 0, 1, 5, 6


class Builder:
    """Collects accessors over one binary buffer."""

    def __init__(self):
        self.data = bytearray()
        self.views = []
        self.accessors = []

    def _view(self, payload, target=None):
        while len(self.data) % 4:
            self.data.append(0)
        view = {"buffer": 0, "byteOffset": len(self.data), "byteLength": len(payload)}
        if target:
            view["target"] = target
        self.data += payload
        self.views.append(view)
        return len(self.views) - 1

    def vec3(self, points):
        payload = b"".join(struct.pack("<3f", *p) for p in points)
        view = self._view(payload, 34962)
        lo = [min(p[i] for p in points) for i in range(3)]
        hi = [max(p[i] for p in points) for i in range(3)]
        # min/max as the f32 values actually stored
        lo = list(struct.unpack("<3f", struct.pack("<3f", *lo)))
        hi = list(struct.unpack("<3f", struct.pack("<3f", *hi)))
        self.accessors.append({"bufferView": view, "componentType": FLOAT,
                               "count": len(points), "type": "VEC3", "min": lo, "max": hi})
        return len(self.accessors) - 1

    def indices(self, values, component=USHORT):
        fmt = "<%d%s" % (len(values), "B" if component == UBYTE else "H")
        view = self._view(struct.pack(fmt, *values), 34963)
        self.accessors.append({"bufferView": view, "componentType": component,
                               "count": len(values), "type": "SCALAR"})
        return len(self.accessors) - 1

    def document(self, uri=None, **parts):
        buffer = {"byteLength": len(self.data)}
        if uri is not None:
            buffer["uri"] = uri
        doc = {"asset": {"version": "2.0", "generator": "rastray make_models.py"}}
        doc.update(parts)
        doc.update({"buffers": [buffer], "bufferViews": self.views, "accessors": self.accessors})
        return doc


def write_glb(path, doc, blob):
    text = json.dumps(doc, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    blob = bytes(blob) + b"\0" * (-len(blob) % 4)
    total = 12 + 8 + len(text) + 8 + len(blob)
    with open(path, "wb") as f:
        f.write(struct.pack("<4sII", b"glTF", 2, total))
        f.write(struct.pack("<I4s", len(text), b"JSON") + text)
        f.write(struct.pack("<I4s", len(blob), b"BIN\0") + blob)


def write_json(path, doc):
    with open(path, "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")


def box():
    """A 1×2×3 box (x, y, z) of 24 vertices with face normals, like the Khronos Box sample: its
    mesh hangs under a parent node whose matrix turns it −90° about X."""
    b = Builder()
    positions, normals, index = [], [], []
    half = (0.5, 1.0, 1.5)
    for axis in range(3):
        for sign in (1.0, -1.0):
            n = [0.0, 0.0, 0.0]
            n[axis] = sign
            u, v = (axis + 1) % 3, (axis + 2) % 3
            base = len(positions)
            for du, dv in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                p = [0.0, 0.0, 0.0]
                p[axis] = sign * half[axis]
                p[u] = du * half[u]
                p[v] = dv * half[v] * sign  # keep counter-clockwise seen from outside
                positions.append(p)
                normals.append(n)
            index += [base, base + 1, base + 2, base, base + 2, base + 3]
    pos = b.vec3(positions)
    nor = b.vec3(normals)
    ind = b.indices(index)
    parts = dict(
        scene=0,
        scenes=[{"nodes": [0]}],
        nodes=[
            {"name": "Turn", "children": [1],
             "matrix": [1, 0, 0, 0, 0, 0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1]},
            {"name": "Box", "mesh": 0},
        ],
        meshes=[{"name": "Box", "primitives": [
            {"attributes": {"POSITION": pos, "NORMAL": nor}, "indices": ind, "material": 0}]}],
        materials=[{"name": "Red", "pbrMetallicRoughness": {
            "baseColorFactor": [0.8, 0.0, 0.0, 1.0], "metallicFactor": 0.0}}],
    )
    return b, parts


def scene():
    """Several nodes, meshes and materials in one file with an embedded buffer."""
    b = Builder()
    tri = b.vec3([(0, 0, 0), (1, 0, 0), (0, 1, 0)])
    tri_ind = b.indices([0, 1, 2], UBYTE)
    quad = b.vec3([(0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0)])
    quad_n = b.vec3([(0, 0, 1)] * 4)
    rim = [(math.cos(k * math.pi / 3), math.sin(k * math.pi / 3), 0.0) for k in range(6)]
    fan = b.vec3([(0.0, 0.0, 0.0)] + rim + [rim[0]])
    line = b.vec3([(0, 0, 0), (0, 0, 1)])
    tex_tri = b.vec3([(0, 0, 0), (1, 0, 0), (0, 1, 0)])
    c, s = 0.0, 1.0  # 90° about Z, then 1 along X (column-major)
    parts = dict(
        scene=0,
        scenes=[{"name": "Main", "nodes": [0, 3, 4, 5, 7]}, {"name": "Other", "nodes": [6]}],
        nodes=[
            {"name": "Root", "translation": [0, 1, 0], "scale": [2, 2, 2], "children": [1, 2]},
            {"name": "Left", "translation": [-1, 0, 0], "mesh": 0},
            {"name": "Right", "mesh": 1,
             "matrix": [c, s, 0, 0, -s, c, 0, 0, 0, 0, 1, 0, 1, 0, 0, 1]},
            {"name": "Mirror", "scale": [-1, 1, 1], "mesh": 0},
            {"name": "Fan", "translation": [0, 0, -2], "mesh": 2},
            {"name": "Wire", "mesh": 3},
            {"name": "Elsewhere", "mesh": 4},
            {"name": "Textured", "translation": [0, -3, 0], "mesh": 4},
        ],
        meshes=[
            {"name": "Tri", "primitives": [
                {"attributes": {"POSITION": tri}, "indices": tri_ind, "material": 0}]},
            {"name": "Strip", "primitives": [
                {"attributes": {"POSITION": quad, "NORMAL": quad_n}, "mode": STRIP,
                 "material": 1}]},
            {"name": "Fan", "primitives": [{"attributes": {"POSITION": fan}, "mode": FAN}]},
            {"name": "Wire", "primitives": [
                {"attributes": {"POSITION": line}, "mode": LINES},
                {"attributes": {"POSITION": line}, "mode": POINTS}]},
            {"name": "Textured", "primitives": [
                {"attributes": {"POSITION": tex_tri}, "material": 2}]},
        ],
        materials=[
            {"name": "Green", "pbrMetallicRoughness": {
                "baseColorFactor": [0.1, 0.6, 0.2, 1.0], "metallicFactor": 0.0,
                "roughnessFactor": 0.5}},
            {"name": "Chrome", "pbrMetallicRoughness": {
                "baseColorFactor": [0.9, 0.9, 0.9, 1.0], "metallicFactor": 1.0,
                "roughnessFactor": 0.0}},
            {"name": "Painted", "pbrMetallicRoughness": {
                "baseColorFactor": [0.5, 0.5, 1.0, 1.0], "baseColorTexture": {"index": 0}}},
        ],
        textures=[{"source": 0}],
        images=[{"uri": "paint.png"}],
    )
    return b, parts


def suzanne(obj_path):
    """Suzanne from the OBJ: the same vertices, normals and fan triangulation as the OBJ
    importer (polygon (0, i, i+1)), so both files give the same mesh."""
    positions, normals, index = [], [], []
    for line in open(obj_path):
        f = line.split()
        if not f:
            continue
        if f[0] == "v":
            positions.append([float(x) for x in f[1:4]])
        elif f[0] == "vn":
            n = [float(x) for x in f[1:4]]
            length = math.sqrt(sum(x * x for x in n))
            normals.append([x / length for x in n])
        elif f[0] == "f":
            corners = [c.split("/") for c in f[1:]]
            # This OBJ pairs every position with the normal of the same number.
            assert all(c[0] == c[2] for c in corners)
            ids = [int(c[0]) - 1 for c in corners]
            for i in range(1, len(ids) - 1):
                index += [ids[0], ids[i], ids[i + 1]]
    b = Builder()
    pos = b.vec3(positions)
    nor = b.vec3(normals)
    ind = b.indices(index)
    parts = dict(
        scene=0,
        scenes=[{"nodes": [0]}],
        nodes=[{"name": "Suzanne", "mesh": 0}],
        meshes=[{"name": "Suzanne", "primitives": [
            {"attributes": {"POSITION": pos, "NORMAL": nor}, "indices": ind, "material": 0}]}],
        materials=[{"name": "Yellow plastic", "pbrMetallicRoughness": {
            "baseColorFactor": [0.95, 0.64, 0.05, 1.0], "metallicFactor": 0.0,
            "roughnessFactor": 0.4}}],
    )
    return b, parts


def main():
    here = "tests/data/gltf"
    b, parts = box()
    write_glb(os.path.join(here, "box.glb"), b.document(**parts), b.data)
    write_json(os.path.join(here, "box.gltf"), b.document(uri="box%20data.bin", **parts))
    with open(os.path.join(here, "box data.bin"), "wb") as f:
        f.write(b.data)

    b, parts = scene()
    uri = "data:application/octet-stream;base64," + base64.b64encode(b.data).decode()
    write_json(os.path.join(here, "scene.gltf"), b.document(uri=uri, **parts))

    b, parts = suzanne("tests/data/suzanne.obj")
    write_glb("scenes/models/suzanne.glb", b.document(**parts), b.data)


if __name__ == "__main__":
    main()
