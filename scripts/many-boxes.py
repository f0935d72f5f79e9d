#!/usr/bin/env python3
"""Writes the many-objects test scene: N unit boxes on a cubic grid (spacing 2) as one scene TOML
with one object per box, and the same boxes as one OBJ mesh with a scene that loads it, so the
two render the same triangles. The default N = 313,713 boxes (3,764,556 triangles) keeps the TOML
under the 16 MiB scene cap (about 14 MB); the OBJ is about 150 MB.

Usage: scripts/many-boxes.py OUT_DIR [N]
Writes OUT_DIR/boxes.toml, OUT_DIR/one-mesh.toml and OUT_DIR/boxes.obj. The camera stands inside
the grid, in the gap between boxes four layers in from one side, looking into the grid along z
and a little aside, so the first layers lie behind it (each box a warning that `info` and
`render` summarise).
"""
import math
import os
import sys


def main():
    out = sys.argv[1]
    count = int(sys.argv[2]) if len(sys.argv) > 2 else 313_713
    side = math.ceil(round(count ** (1 / 3), 9))
    os.makedirs(out, exist_ok=True)
    centres = []
    for k in range(side):
        for j in range(side):
            for i in range(side):
                if len(centres) < count:
                    centres.append((2 * i, 2 * j, 2 * k))
    far = 2 * (side - 1)
    # Odd coordinates lie in the gaps between boxes: the eye looks down a corridor along z,
    # from the middle of the grid's side, a few layers in.
    mid = 2 * (side // 2) + 1
    eye = 2 * (side // 16) + 1
    top = (
        "# %d unit boxes on a grid of spacing 2, written by scripts/many-boxes.py\n"
        "ambient = 0.1\nbackground = [0.04, 0.05, 0.08]\nmax_depth = 2\n" % count
    )
    tables = (
        "\n[camera]\nposition = [%g, %g, %g]\ntarget = [%g, %g, %g]\nup = [0.0, 1.0, 0.0]\nfov = 60.0\n\n"
        "[[light]]\nposition = [%g, %g, %g]\nintensity = 0.9\ncolor = [1.0, 1.0, 1.0]\n\n"
        % (mid, mid, eye, mid + 13, mid + 8, far, far + 10, far + 40, -10)
    )
    with open(os.path.join(out, "boxes.toml"), "w") as f:
        # The objects as one array of inline tables (far fewer bytes than [[object]] tables),
        # which must come before the first table header.
        f.write(top)
        f.write("object = [\n")
        for x, y, z in centres:
            f.write('{type="box",center=[%d,%d,%d],size=[1,1,1]},\n' % (x, y, z))
        f.write("]\n")
        f.write(tables)
    with open(os.path.join(out, "one-mesh.toml"), "w") as f:
        f.write(top)
        f.write(tables)
        # The OBJ's bounding-box centre goes to `position`: the middle of the grid's extent.
        lo = [min(c[a] for c in centres) - 0.5 for a in range(3)]
        hi = [max(c[a] for c in centres) + 0.5 for a in range(3)]
        mid = [(lo[a] + hi[a]) / 2 for a in range(3)]
        f.write(
            '[[object]]\ntype = "mesh"\npath = "boxes.obj"\nsmooth = false\n'
            "position = [%g, %g, %g]\n" % tuple(mid)
        )
    # Corners and faces as the box shape makes them does not matter for timing; the same
    # 12 triangles a box, outward-facing.
    faces = [
        (0, 2, 1), (0, 3, 2), (4, 5, 6), (4, 6, 7), (0, 1, 5), (0, 5, 4),
        (3, 7, 6), (3, 6, 2), (0, 4, 7), (0, 7, 3), (1, 2, 6), (1, 6, 5),
    ]
    with open(os.path.join(out, "boxes.obj"), "w") as f:
        for n, (x, y, z) in enumerate(centres):
            for dz in (-0.5, 0.5):
                for dx, dy in ((-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)):
                    f.write("v %g %g %g\n" % (x + dx, y + dy, z + dz))
            base = 8 * n + 1
            for a, b, c in faces:
                f.write("f %d %d %d\n" % (base + a, base + b, base + c))


if __name__ == "__main__":
    main()
