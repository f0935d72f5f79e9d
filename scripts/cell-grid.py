#!/usr/bin/env python3
# usage: scripts/cell-grid.py target/release/rastray SCENE_OR_MODEL ...  (needs Pillow and numpy)
"""Editor preview for the finer cell sets: which render resolution makes the most faithful cells?
Candidates per cell (1:2 cells): 'now' 2x4 square pixels (the editor today), 'grid' the set's own sub-cell grid
(2x2 quadrant, 2x3 sextant, 2x4 braille; non-square pixels, emulated by point-sampling a 18x36-per-cell render at
the grid's pixel centres, averaging the two rows either side where a centre falls between rows), 'view' 6x12 (what
`view` renders). Each image is upsampled (nearest) to 6x12 per cell, encoded by least squares (best glyph and two mean
colours per cell, as rastray's encoder), decoded, and compared with a 6x12 render (PSNR)."""
import itertools, subprocess, sys, os
import numpy as np
from PIL import Image
BIN = sys.argv[1]; COLS, ROWS = 80, 23; CW, CH = 6, 12
GRIDS = {"quadrant": 2, "sextant": 3, "braille": 4}

def render(scene, w, h, path):
    r = subprocess.run([BIN, "render", scene, "-s", "%dx%d" % (w, h), "-o", path], capture_output=True, check=True)
    return np.asarray(Image.open(path).convert("RGB")).astype(np.float64)

def upsample(img, fx, fy):
    return np.repeat(np.repeat(img, fy, axis=0), fx, axis=1)

def encode(img, gy):
    """Least-squares cells on a 2 x gy grid -> decoded image."""
    K = 2 * gy; sh, sw = CH // gy, CW // 2
    c = img.reshape(ROWS, gy, sh, COLS, 2, sw, 3).transpose(0, 3, 1, 4, 2, 5, 6).reshape(ROWS * COLS, K, sh * sw, 3)
    S = c.sum(axis=2); n = sh * sw
    P = np.array(list(itertools.product([0, 1], repeat=K)), np.float64)  # M x K
    nf = P.sum(1) * n; nb = K * n - nf
    Sf = np.einsum("mk,ckd->cmd", P, S); Sb = S.sum(1)[:, None, :] - Sf
    with np.errstate(divide="ignore", invalid="ignore"):
        gain = np.where(nf[None] > 0, (Sf ** 2).sum(-1) / nf[None], 0) + np.where(nb[None] > 0, (Sb ** 2).sum(-1) / nb[None], 0)
    best = gain.argmax(1)
    idx = np.arange(len(best))
    fg = np.where(nf[best][:, None] > 0, Sf[idx, best] / np.maximum(nf[best], 1)[:, None], 0)
    bg = np.where(nb[best][:, None] > 0, Sb[idx, best] / np.maximum(nb[best], 1)[:, None], 0)
    fg, bg = np.round(fg), np.round(bg)
    mask = P[best]  # cells x K
    out = np.where(mask[:, :, None, None] > 0, fg[:, None, None, :], bg[:, None, None, :])  # cells,K,1,3
    out = np.broadcast_to(out, (ROWS * COLS, K, sh * sw, 3)).reshape(ROWS, COLS, gy, 2, sh, sw, 3)
    return out.transpose(0, 2, 4, 1, 3, 5, 6).reshape(ROWS * CH, COLS * CW, 3)

def psnr(a, b):
    mse = np.mean((a - b) ** 2)
    return 10 * np.log10(255 ** 2 / mse)

import tempfile
tmp = tempfile.mkdtemp()
print("| scene | set | now 2x4 dB | grid dB | view 6x12 dB |")
print("|---|---|---|---|---|")
for scene in sys.argv[2:]:
    ref = render(scene, COLS * CW, ROWS * CH, tmp + "/ref.png")
    now = render(scene, COLS * 2, ROWS * 4, tmp + "/now.png")
    hi = render(scene, COLS * 18, ROWS * 36, tmp + "/hi.png")
    row = []
    for name, gy in GRIDS.items():
        xs = 9 * np.arange(COLS * 2) + 4
        centre = 36 * (np.arange(ROWS * gy) + 0.5) / gy - 0.5
        lo = np.floor(centre).astype(int); hi_i = np.ceil(centre).astype(int)
        grid = 0.5 * (hi[lo][:, xs] + hi[hi_i][:, xs])
        cand = {"now": upsample(now, 3, 3), "grid": upsample(grid, 3, CH // gy), "view": ref}
        dbs = [psnr(encode(cand[k], gy), ref) for k in ("now", "grid", "view")]
        print("| %s | %s | %.2f | %.2f | %.2f |" % (os.path.basename(scene), name, *dbs), flush=True)
