#!/usr/bin/env python3
"""The test preview.window: pathtrace --window under a virtual X display (xvfb-run), with
--window-screenshot saving the window after every pass. Checks that
  - the PNG written with --window is bit for bit the one written without it;
  - the window's image region holds the same pixels as that PNG (within 1/255, at the window's
    zoom, which the program prints);
  - the status bar under the image holds text: light pixels on its dark grey;
  - without a display, --window exits 1 with an error naming DISPLAY.
Usage: check_preview.py PATHTRACE        (exit 77, a skip, when xvfb-run is not installed)"""
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import zlib

# -noreset: see chapters/3.2-opengl/smoke.txt (a resetting server can make xvfb-run exit 5).
XVFB = ["xvfb-run", "-a", "-s", "-screen 0 1280x720x24 -noreset"]


def read_png(path):
    """8-bit RGB or RGBA, not interlaced (what stb_image_write writes): (width, height, rows of bytes)."""
    with open(path, "rb") as f:
        data = f.read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", f"{path} is not a PNG"
    pos, idat, head = 8, b"", None
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            head = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    w, h, depth, colour, _, _, interlace = head
    assert depth == 8 and colour in (2, 6) and interlace == 0, f"{path}: unsupported PNG {head}"
    bpp = 3 if colour == 2 else 4
    raw, stride, rows, prev = zlib.decompress(idat), w * bpp, [], bytearray(w * bpp)
    for y in range(h):
        kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b, c = prev[i], prev[i - bpp] if i >= bpp else 0
            if kind == 1:
                line[i] = (line[i] + a) & 255
            elif kind == 2:
                line[i] = (line[i] + b) & 255
            elif kind == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line) if bpp == 3 else bytes(v for i, v in enumerate(line) if i % 4 != 3))
        prev = line
    return w, h, rows


def run(cmd, cwd):
    r = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, timeout=120)
    return r.returncode, r.stdout + r.stderr


def main():
    program = os.path.abspath(sys.argv[1])
    if not shutil.which("xvfb-run"):
        print("skipped: xvfb-run is not installed (Debian: xvfb)")
        return 77
    failures = []
    with tempfile.TemporaryDirectory() as d:
        scene = ["--scene", "cornell-glass", "--width", "24", "--height", "20", "--seed", "7"]
        code, out = run([program] + scene + ["--spp", "64", "--pfm", os.path.join(d, "ref.pfm"),
                                             "--out", os.path.join(d, "ref.png")], d)
        assert code == 0, out
        common = scene + ["--spp", "16", "--reference", os.path.join(d, "ref.pfm")]
        code, out = run(XVFB + [program] + common + ["--window", "--window-screenshot", os.path.join(d, "shot.png"),
                                                     "--out", os.path.join(d, "win.png")], d)
        print(out)
        assert code == 0, f"--window run: exit {code}"
        m = re.search(r"^window: (\d+)x(\d+), the image at (\d+)/1;", out, re.M)
        assert m, "no 'window: WxH, the image at Z/1' line"
        zoom = int(m.group(3))
        assert len(re.findall(r"^window: wrote .*shot\.png \(\d+ spp\)$", out, re.M)) == 5, "not 5 screenshots (1..16 spp)"
        assert re.search(r"^summary: cornell-glass mis 24x20, 16 spp", out, re.M), "no summary line"
        code, plain = run([program] + common + ["--out", os.path.join(d, "plain.png")], d)
        assert code == 0, plain

        with open(os.path.join(d, "win.png"), "rb") as a, open(os.path.join(d, "plain.png"), "rb") as b:
            if a.read() != b.read():
                failures.append("the PNG written with --window differs from the one without")
        iw, ih, img = read_png(os.path.join(d, "win.png"))
        sw, sh, shot = read_png(os.path.join(d, "shot.png"))
        if (sw, sh) != (int(m.group(1)), int(m.group(2))) or sw < iw * zoom or sh <= ih * zoom:
            failures.append(f"screenshot is {sw}x{sh}, the image {iw}x{ih} at zoom {zoom}")
        worst = 0
        for y in range(ih * zoom):
            for x in range(iw * zoom):
                want = img[y // zoom][3 * (x // zoom):3 * (x // zoom) + 3]
                got = shot[y][3 * x:3 * x + 3]
                worst = max(worst, max(abs(p - q) for p, q in zip(want, got)))
        print(f"image region {iw * zoom}x{ih * zoom}: largest difference from the PNG {worst}/255")
        if worst > 1:
            failures.append(f"the window's image differs from the PNG by {worst}/255")
        bar = [shot[y][3 * x:3 * x + 3] for y in range(ih * zoom, sh) for x in range(sw)]
        light = sum(1 for p in bar if min(p) > 200)
        dark = sum(1 for p in bar if max(p) < 64)
        print(f"status bar: {len(bar)} pixels, {light} light (text), {dark} dark")
        if not (200 < light < len(bar) // 2 and dark > len(bar) // 2):
            failures.append("the status bar holds no text (light pixels on dark)")

        code, out = run(["env", "-u", "DISPLAY", program] + scene + ["--spp", "1", "--window", "--out",
                                                                      os.path.join(d, "none.png")], d)
        if code != 1 or not re.search(r"^error: --window needs an X display, and DISPLAY is not set", out, re.M):
            failures.append(f"without a display: exit {code}, output {out!r}")
        if os.path.exists(os.path.join(d, "none.png")):
            failures.append("without a display, an image was still written")
    for f in failures:
        print("FAILED:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
