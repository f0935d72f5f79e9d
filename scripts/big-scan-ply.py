#!/usr/bin/env python3
"""Writes a binary little-endian PLY shaped like a real scan: a displaced height-field grid
whose vertices are shared by the six triangles around them (about half as many vertices as
triangles), for memory and first-frame measurements at scale.

    scripts/big-scan-ply.py OUT.ply [--triangles N] [--colors]

N (default 10,000,000) is rounded up to a whole grid of two triangles a cell, cols:rows = 5:4.
The surface is a few crossing waves and a bump, about 1 unit across, so a default camera frames
it. With --colors each vertex also gets `red green blue` (uchar), as coloured scans carry.
"""

import argparse
import math
import sys

import numpy as np


def grid_size(triangles):
    """Cells across and down for at least `triangles` triangles, about 5:4."""
    rows = max(1, math.ceil(math.sqrt(triangles / 2 * 4 / 5)))
    cols = max(1, math.ceil(triangles / 2 / rows))
    return cols, rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out")
    parser.add_argument("--triangles", type=int, default=10_000_000)
    parser.add_argument("--colors", action="store_true")
    args = parser.parse_args()
    cols, rows = grid_size(args.triangles)
    nx, ny = cols + 1, rows + 1
    x = np.linspace(-0.625, 0.625, nx, dtype=np.float64)
    y = np.linspace(-0.5, 0.5, ny, dtype=np.float64)
    gx, gy = np.meshgrid(x, y)
    height = (
        0.03 * np.sin(23.0 * gx) * np.cos(17.0 * gy)
        + 0.01 * np.sin(91.0 * gx + 57.0 * gy)
        + 0.15 * np.exp(-((gx - 0.1) ** 2 + (gy + 0.05) ** 2) / 0.05)
    )
    fields = [("x", "<f4"), ("y", "<f4"), ("z", "<f4")]
    if args.colors:
        fields += [("red", "u1"), ("green", "u1"), ("blue", "u1")]
    vertices = np.empty(nx * ny, dtype=fields)
    # A scan lies in the ground plane: x and y across, z up (open it with `--up z`), here y up
    # so that it opens facing the default camera.
    vertices["x"] = gx.ravel()
    vertices["y"] = height.ravel()
    vertices["z"] = gy.ravel()
    if args.colors:
        shade = np.clip((height.ravel() + 0.05) * 4.0, 0.0, 1.0)
        vertices["red"] = (80 + 175 * shade).astype(np.uint8)
        vertices["green"] = (120 + 80 * shade).astype(np.uint8)
        vertices["blue"] = (200 - 150 * shade).astype(np.uint8)
    del gx, gy, height
    row = np.arange(rows, dtype=np.int32)[:, None] * nx
    col = np.arange(cols, dtype=np.int32)[None, :]
    corner = (row + col).ravel()
    faces = np.empty(2 * cols * rows, dtype=[("n", "u1"), ("v", "<i4", (3,))])
    faces["n"] = 3
    # Each cell: (a, c, b) and (b, c, d) with a top-left, b top-right, c bottom-left, d bottom-right,
    # wound counter-clockwise seen from +y.
    a, b, c, d = corner, corner + 1, corner + nx, corner + nx + 1
    faces["v"][0::2] = np.stack([a, c, b], axis=1)
    faces["v"][1::2] = np.stack([b, c, d], axis=1)
    del a, b, c, d, corner
    header = ["ply", "format binary_little_endian 1.0", "comment big-scan-ply.py grid"]
    header += [f"element vertex {len(vertices)}"]
    header += [f"property float {axis}" for axis in "xyz"]
    if args.colors:
        header += [f"property uchar {c}" for c in ("red", "green", "blue")]
    header += [f"element face {len(faces)}", "property list uchar int vertex_indices"]
    header += ["end_header"]
    with open(args.out, "wb") as out:
        out.write(("\n".join(header) + "\n").encode("ascii"))
        vertices.tofile(out)
        faces.tofile(out)
    print(f"{args.out}: {len(vertices)} vertices, {len(faces)} triangles", file=sys.stderr)


if __name__ == "__main__":
    main()
