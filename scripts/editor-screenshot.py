#!/usr/bin/env python3
"""Draws the editor as a terminal shows it, into a PNG: runs `rastray` on a pseudo-terminal,
types keys, then replays what it wrote through a small ANSI interpreter (cursor moves, SGR
colours, half blocks) and paints the cells with DejaVu Sans Mono.

Usage: scripts/editor-screenshot.py BINARY OUT.png KEYS [ARGS...]
  KEYS is typed after the first screen appears (\\e for Escape, \\d for Down arrow).
Needs Python 3 with Pillow."""
import os, pty, re, select, sys, time, struct, fcntl, termios, glob
from PIL import Image, ImageDraw, ImageFont

COLS, ROWS = 120, 34
CELL_W, CELL_H = 9, 18
BASIC = [(0, 0, 0), (205, 49, 49), (13, 188, 121), (229, 229, 16), (36, 114, 200),
         (188, 63, 188), (17, 168, 205), (229, 229, 229), (102, 102, 102), (241, 76, 76),
         (35, 209, 139), (245, 245, 67), (59, 142, 234), (214, 112, 214), (41, 184, 219),
         (255, 255, 255)]
DEFAULT_FG, DEFAULT_BG = (204, 204, 204), (24, 24, 28)


def run(binary, keys, args):
    pid, fd = pty.fork()
    if pid == 0:
        os.environ.update(TERM="xterm-256color", COLORTERM="truecolor")
        os.execv(binary, [binary] + args)
    fcntl.ioctl(fd, termios.TIOCSWINSZ, struct.pack("HHHH", ROWS, COLS, 0, 0))
    out = bytearray()

    def pump(seconds):
        end = time.time() + seconds
        while time.time() < end:
            r, _, _ = select.select([fd], [], [], 0.05)
            if r:
                try:
                    out.extend(os.read(fd, 65536))
                except OSError:
                    return

    pump(3.0)
    for k in keys.replace("\\e", "\x1b").replace("\\d", "\x1b[B"):
        os.write(fd, k.encode())
        pump(0.6)
    pump(3.0)
    os.write(fd, b"q")
    pump(1.0)
    return bytes(out)


def sgr(params, state):
    p = [int(x) if x else 0 for x in params.split(";")] if params else [0]
    i = 0
    while i < len(p):
        c = p[i]
        if c == 0:
            state.update(fg=None, bg=None, dim=False)
        elif c == 2:
            state["dim"] = True
        elif c == 22:
            state["dim"] = False
        elif c in (38, 48) and i + 1 < len(p) and p[i + 1] == 2:
            state["fg" if c == 38 else "bg"] = tuple(p[i + 2:i + 5])
            i += 4
        elif c in (38, 48) and i + 1 < len(p) and p[i + 1] == 5:
            n = p[i + 2]
            if n < 16:
                rgb = BASIC[n]
            elif n < 232:
                n -= 16
                rgb = tuple((0, 95, 135, 175, 215, 255)[v] for v in (n // 36, n // 6 % 6, n % 6))
            else:
                rgb = (8 + 10 * (n - 232),) * 3
            state["fg" if c == 38 else "bg"] = rgb
            i += 2
        elif 30 <= c <= 37:
            state["fg"] = BASIC[c - 30]
        elif 90 <= c <= 97:
            state["fg"] = BASIC[c - 90 + 8]
        elif 40 <= c <= 47:
            state["bg"] = BASIC[c - 40]
        elif 100 <= c <= 107:
            state["bg"] = BASIC[c - 100 + 8]
        elif c == 39:
            state["fg"] = None
        elif c == 49:
            state["bg"] = None
        i += 1


def screen(data):
    cells = [[(" ", None, None, False) for _ in range(COLS)] for _ in range(ROWS)]
    state = dict(fg=None, bg=None, dim=False)
    x = y = 0
    text = data.decode("utf-8", "replace")
    token = re.compile(r"\x1b\[([?>=]?)([0-9;]*)([ -/]*)([@-~])|\x1b[P\]_^][^\x1b\x07]*(?:\x07|\x1b\\)|\x1b[()][A-Za-z0-9]|\x1b.|[\r\n\b]|[^\x1b\r\n\b]")
    for m in token.finditer(text):
        s = m.group(0)
        if m.group(4) is not None:
            priv, params, final = m.group(1), m.group(2), m.group(4)
            if priv:
                continue
            nums = [int(v) if v else 0 for v in params.split(";")] if params else []
            if final == "H":
                y = (nums[0] if nums and nums[0] else 1) - 1
                x = (nums[1] if len(nums) > 1 and nums[1] else 1) - 1
            elif final == "m":
                sgr(params, state)
            elif final == "J" and (nums[:1] == [2]):
                cells = [[(" ", None, None, False) for _ in range(COLS)] for _ in range(ROWS)]
            elif final == "C":
                x += nums[0] if nums else 1
            elif final == "G":
                x = (nums[0] if nums else 1) - 1
        elif s == "\r":
            x = 0
        elif s == "\n":
            y += 1
        elif s.startswith("\x1b") or s == "\b":
            continue
        else:
            if 0 <= y < ROWS and 0 <= x < COLS:
                cells[y][x] = (s, state["fg"], state["bg"], state["dim"])
            x += 1
    return cells


def paint(cells, path):
    font_path = glob.glob(os.path.expanduser(
        "~/.cargo/registry/src/*/dejavu-*/assets/*/ttf/DejaVuSansMono.ttf"))[0]
    font = ImageFont.truetype(font_path, 14)
    image = Image.new("RGB", (COLS * CELL_W, ROWS * CELL_H), DEFAULT_BG)
    draw = ImageDraw.Draw(image)
    for y, row in enumerate(cells):
        for x, (ch, fg, bg, dim) in enumerate(row):
            fg = fg or DEFAULT_FG
            if dim:
                fg = tuple(v * 2 // 3 for v in fg)
            x0, y0 = x * CELL_W, y * CELL_H
            draw.rectangle([x0, y0, x0 + CELL_W - 1, y0 + CELL_H - 1], fill=bg or DEFAULT_BG)
            if ch == "▀":
                draw.rectangle([x0, y0, x0 + CELL_W - 1, y0 + CELL_H // 2 - 1], fill=fg)
            elif ch == "▄":
                draw.rectangle([x0, y0 + CELL_H // 2, x0 + CELL_W - 1, y0 + CELL_H - 1], fill=fg)
            elif ch == "█":
                draw.rectangle([x0, y0, x0 + CELL_W - 1, y0 + CELL_H - 1], fill=fg)
            elif ch != " ":
                draw.text((x0, y0 + 1), ch, font=font, fill=fg)
    image.save(path)


if __name__ == "__main__":
    binary, out, keys = sys.argv[1], sys.argv[2], sys.argv[3]
    paint(screen(run(binary, keys, sys.argv[4:])), out)
