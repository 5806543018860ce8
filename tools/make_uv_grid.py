#!/usr/bin/env python3
"""Writes scenes/uv-grid.png: a test image for texture coordinates (book 2.2, textures).

    python3 tools/make_uv_grid.py [OUT.png] [SIZE]

An 8 x 8 grid of cells whose red grows with u (left to right) and green with v (bottom to top),
so that a student sees at once where (0, 0) lies and which way each coordinate runs; dark lines
between the cells, and a white mark in the cell at u, v near 0. Written as an 8-bit sRGB PNG with
Python's own zlib, so nothing is downloaded or installed.
"""
import struct
import sys
import zlib

CELLS = 8


def texel(x, y, size):
    u, v = (x + 0.5) / size, 1 - (y + 0.5) / size  # row 0 is the top, v = 1
    cu, cv = min(CELLS - 1, int(u * CELLS)), min(CELLS - 1, int(v * CELLS))
    fu, fv = u * CELLS - cu, v * CELLS - cv
    if min(fu, fv, 1 - fu, 1 - fv) < 0.04:  # the grid lines
        return (30, 30, 36)
    if cu == 0 and cv == 0 and 0.3 < fu < 0.7 and 0.3 < fv < 0.7:  # the origin
        return (250, 250, 250)
    r = 50 + 200 * cu // (CELLS - 1)
    g = 50 + 200 * cv // (CELLS - 1)
    b = 200 if (cu + cv) % 2 else 110
    return (r, g, b)


def png(width, height, rows):
    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)
    raw = b"".join(b"\0" + bytes(row) for row in rows)  # filter 0 on every row
    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)  # 8-bit RGB
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "scenes/uv-grid.png"
    size = int(sys.argv[2]) if len(sys.argv) > 2 else 256
    rows = [[c for x in range(size) for c in texel(x, y, size)] for y in range(size)]
    data = png(size, size, rows)
    with open(out, "wb") as f:
        f.write(data)
    print(f"wrote {out}: {size} x {size}, {len(data)} bytes")


if __name__ == "__main__":
    main()
