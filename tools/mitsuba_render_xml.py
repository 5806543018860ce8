#!/usr/bin/env python3
"""Renders a Mitsuba 3 XML scene with Mitsuba itself (scalar_rgb), from the file as it is (book 4.1).

    build/mitsuba-venv/bin/python tools/mitsuba_render_xml.py scenes/mitsuba/cornell-box.xml \
        --spp 1024 -o cb-mitsuba.pfm [--png cb-mitsuba.png] [--seed 1] [--compare cb-zraka.pfm] [--floor cb-mitsuba-seed2.pfm]

zraka reads the same file (`pathtrace --scene scenes/mitsuba/cornell-box.xml --pfm cb-zraka.pfm`,
include/zraka/io/mitsuba_xml.hpp): the two renderers see one scene description and nothing is
converted on Mitsuba's side. --spp overrides the file's sample count, as zraka's --spp does.
--compare prints the RMSE and per-channel means against a zraka PFM (tools/mitsuba_reference.py's
compare); --floor, a second Mitsuba image of another seed, prints the RMSE between Mitsuba's two
renders: the noise floor that zraka's RMSE is to be read against.
Not part of the tests: Mitsuba is a few hundred MB from PyPI (tools/mitsuba-setup.sh).
"""
import argparse
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mitsuba_reference import compare, read_pfm, write_pfm  # noqa: E402  (one PFM reader and one comparison)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scene", help="a Mitsuba 3 XML scene file")
    ap.add_argument("-o", "--out", required=True, help="PFM file to write")
    ap.add_argument("--spp", type=int, default=0, help="samples per pixel (default 0: the file's)")
    ap.add_argument("--seed", type=int, default=0, help="Mitsuba's sampler seed")
    ap.add_argument("--compare", help="a zraka PFM of the same file: print RMSE and channel means")
    ap.add_argument("--png", help="also write the image as an sRGB PNG, to look at")
    ap.add_argument("--floor", help="a Mitsuba PFM of the same file at another seed: print their RMSE")
    a = ap.parse_args()
    if a.spp < 0:
        sys.exit("error: --spp must not be negative")
    if not os.path.isfile(a.scene):
        sys.exit(f"error: {a.scene}: no such file")

    import mitsuba as mi
    import numpy as np

    mi.set_variant("scalar_rgb")
    try:
        scene = mi.load_file(a.scene)
    except Exception as e:  # Mitsuba's own parser: its message names the file and the element
        sys.exit(f"error: {e}")
    start = time.time()
    img = np.array(mi.render(scene, spp=a.spp, seed=a.seed), dtype=np.float64)[:, :, :3]
    secs = time.time() - start
    if not np.all(np.isfinite(img)):
        sys.exit("error: Mitsuba's image has NaN or infinite pixels")
    write_pfm(a.out, img)
    if a.png:
        import matplotlib.image

        c = np.clip(img, 0, 1)
        srgb = np.where(c <= 0.0031308, 12.92 * c, 1.055 * c ** (1 / 2.4) - 0.055)
        matplotlib.image.imsave(a.png, srgb)
    spp = a.spp or scene.sensors()[0].sampler().sample_count()
    print(f"Mitsuba {mi.__version__} scalar_rgb: {a.scene}, {img.shape[1]}x{img.shape[0]}, {spp} spp, "
          f"seed {a.seed}, in {secs:.1f} s; wrote {a.out}")
    if a.floor:
        other = read_pfm(a.floor)
        if other.shape != img.shape:
            sys.exit(f"error: {a.floor} is not {img.shape[1]}x{img.shape[0]}")
        d = other - img
        print(f"noise floor: RMSE between Mitsuba's two seeds {float(np.sqrt(np.mean(d * d))):.5f}")
    if a.compare:
        compare(a.compare, img)


if __name__ == "__main__":
    main()
