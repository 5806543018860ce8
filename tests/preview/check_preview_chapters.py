#!/usr/bin/env python3
"""The test preview.chapters: --window in the 6.x chapters that compare methods run after run
(6.1 media, 6.2 bdpt, 6.4 metropolis), under a virtual X display (xvfb-run). For each program:
  - with --window --window-screenshot, one screenshot per run it shows (each doubling of the
    samples; 6.1: each image of its table);
  - the PNG written with --window is bit for bit the one written without it;
  - 6.2 and 6.4 show their methods side by side, as the left part of the PNG they write (whose
    last tile is the reference): the last screenshot's image region holds those pixels (1/255).
Usage: check_preview_chapters.py MEDIA BDPT METROPOLIS   (exit 77, a skip, without xvfb-run)"""
import os
import re
import shutil
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from check_preview import XVFB, read_png, run  # noqa: E402


def check(program, args, shots, unit, tiles, d, failures):
    name = os.path.basename(program)
    code, out = run(XVFB + [program] + args + ["--window", "--window-screenshot", os.path.join(d, "shot.png"),
                                                "--out", os.path.join(d, "win.png")], d)
    print(out)
    if code != 0:
        failures.append(f"{name} --window: exit {code}")
        return
    m = re.search(r"^window: (\d+)x(\d+), the image at (\d+)/1;", out, re.M)
    wrote = re.findall(r"^window: wrote .*shot\.png \(\d+ " + unit + r"\)$", out, re.M)
    if not m or len(wrote) != shots:
        failures.append(f"{name}: {len(wrote)} screenshots, expected {shots}")
        return
    code, plain = run([program] + args + ["--out", os.path.join(d, "plain.png")], d)
    if code != 0:
        failures.append(f"{name} without --window: exit {code}: {plain}")
        return
    with open(os.path.join(d, "win.png"), "rb") as a, open(os.path.join(d, "plain.png"), "rb") as b:
        if a.read() != b.read():
            failures.append(f"{name}: the PNG written with --window differs from the one without")
    if not tiles:
        return
    zoom = int(m.group(3))
    pw, ph, png = read_png(os.path.join(d, "win.png"))
    sw, sh, shot = read_png(os.path.join(d, "shot.png"))
    tile = (pw - 2 * (tiles - 1)) // tiles  # side_by_side: tiles of equal width, 2-pixel gaps
    shown = (tiles - 1) * tile + 2 * (tiles - 2)  # every tile but the reference
    if sw < shown * zoom or sh <= ph * zoom:
        failures.append(f"{name}: screenshot {sw}x{sh} cannot hold {shown}x{ph} at zoom {zoom}")
        return
    worst = max(abs(p - q) for y in range(ph * zoom) for x in range(shown * zoom)
                for p, q in zip(png[y // zoom][3 * (x // zoom):3 * (x // zoom) + 3], shot[y][3 * x:3 * x + 3]))
    print(f"{name}: last screenshot against the PNG's first {tiles - 1} tiles: largest difference {worst}/255")
    if worst > 1:
        failures.append(f"{name}: the window's last image differs from the PNG by {worst}/255")


def main():
    media, bdpt, metropolis = (os.path.abspath(p) for p in sys.argv[1:4])
    if not shutil.which("xvfb-run"):
        print("skipped: xvfb-run is not installed (Debian: xvfb)")
        return 77
    failures = []
    with tempfile.TemporaryDirectory() as d:
        # 6.1: table 2 has delta and two march steps at 1 and 4 spp: 6 images.
        check(media, ["--width", "12", "--height", "12", "--spp", "4", "--ref-spp", "8", "--steps", "0.5,0.2"],
              6, "spp", 0, d, failures)
        # 6.2: 1, 2, 4 spp; bdpt | mis | reference.
        check(bdpt, ["--width", "16", "--height", "16", "--spp", "4", "--ref-spp", "32"], 3, "spp", 3, d, failures)
        # 6.4 on the ajar door: 1, 2 mutations per pixel; mlt | bdpt | mis | reference.
        check(metropolis, ["--width", "16", "--height", "12", "--spp", "2", "--ref-spp", "32"], 2, "per pixel", 4,
              d, failures)
    for f in failures:
        print("FAILED:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
