#!/usr/bin/env python3
"""Writes the triangles of an OBJ (its `v` and `f` statements, polygons fanned) as a binary STL
and a binary little-endian PLY, for load-speed measurements in the formats scanners and CAD write.

Usage: scripts/obj-to-stl-ply.py MODEL.obj OUT_STEM
Writes OUT_STEM.stl (80-byte header, count, 50 bytes a triangle with its face normal) and
OUT_STEM.ply (float x y z, then `list uchar int vertex_indices`), the PLY's vertices as the OBJ
lists them, so both hold the same triangles. Needs numpy.
"""
import sys

import numpy as np


def read_obj(path):
    positions, faces = [], []
    with open(path, "rb") as f:
        for line in f:
            words = line.split()
            if not words:
                continue
            if words[0] == b"v":
                positions.append([float(w) for w in words[1:4]])
            elif words[0] == b"f":
                corners = []
                for w in words[1:]:
                    i = int(w.split(b"/")[0])
                    corners.append(i - 1 if i > 0 else len(positions) + i)
                for k in range(1, len(corners) - 1):
                    faces.append([corners[0], corners[k], corners[k + 1]])
    return np.array(positions, dtype=np.float32), np.array(faces, dtype=np.int32)


def write_stl(path, positions, faces):
    corners = positions[faces]  # (n, 3, 3)
    normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    lengths = np.linalg.norm(normals, axis=1, keepdims=True)
    normals = np.where(lengths > 0, normals / np.maximum(lengths, 1e-30), 0).astype(np.float32)
    record = np.dtype([("normal", "<f4", 3), ("corners", "<f4", (3, 3)), ("attribute", "<u2")])
    data = np.zeros(len(faces), dtype=record)
    data["normal"] = normals
    data["corners"] = corners
    with open(path, "wb") as f:
        f.write(b"binary STL written by scripts/obj-to-stl-ply.py".ljust(80, b" "))
        f.write(np.uint32(len(faces)).tobytes())
        f.write(data.tobytes())


def write_ply(path, positions, faces):
    header = (
        "ply\nformat binary_little_endian 1.0\ncomment written by scripts/obj-to-stl-ply.py\n"
        f"element vertex {len(positions)}\nproperty float x\nproperty float y\nproperty float z\n"
        f"element face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n"
    )
    face = np.dtype([("n", "u1"), ("indices", "<i4", 3)])
    data = np.zeros(len(faces), dtype=face)
    data["n"] = 3
    data["indices"] = faces
    with open(path, "wb") as f:
        f.write(header.encode("ascii"))
        f.write(positions.astype("<f4").tobytes())
        f.write(data.tobytes())


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    positions, faces = read_obj(sys.argv[1])
    write_stl(sys.argv[2] + ".stl", positions, faces)
    write_ply(sys.argv[2] + ".ply", positions, faces)


if __name__ == "__main__":
    main()
