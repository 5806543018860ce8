#!/usr/bin/env python3
"""pathtrace --export and tools/mitsuba_reference.py on a Lambertian quad seen from its front and
from its back (issue 46): zraka's Lambertian reflects on both sides, so the two renders are the
same; Mitsuba's `diffuse` alone is black from behind, so the converter must wrap it in
`twosided`. Checks (1) that the exported quads keep their orientation (the normal cross(u, v)
points to the camera in one, away in the other), (2) that zraka renders both alike, (3) that the
converter gives both a two-sided BSDF, and (4) when Mitsuba is installed (tools/mitsuba-setup.sh,
build/mitsuba-venv; else said and skipped) that Mitsuba renders both alike and like zraka.

    check_export_sides.py PATHTRACE [MITSUBA_PYTHON]
"""
import json
import os
import struct
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "tools"))
from mitsuba_reference import bsdf_of  # noqa: E402

SCENE = """settings: {{width: 24, height: 24, spp: 16, max_depth: 2}}
camera: {{position: [0, 0, 3], look_at: [0, 0, 0], vfov: 40}}
materials:
  grey: {{albedo: 0.5}}
lights:
  - {{type: point, position: [0.5, 0.5, 2], intensity: 4}}
objects:
  - {{type: quad, corner: [-1, -1, 0], u: {u}, v: {v}, material: grey}}
"""


def mean_of_pfm(path):
    with open(path, "rb") as f:
        kind = f.readline().strip()
        w, h = map(int, f.readline().split())
        scale = float(f.readline())
        data = f.read()
    n = w * h * (3 if kind == b"PF" else 1)
    vals = struct.unpack(("<" if scale < 0 else ">") + f"{n}f", data[:4 * n])
    return sum(vals) / n


def main():
    pathtrace = os.path.abspath(sys.argv[1])
    mitsuba_python = os.path.abspath(sys.argv[2]) if len(sys.argv) > 2 else ""
    failures = []
    with tempfile.TemporaryDirectory(prefix="zraka-sides-") as work:
        means, exports = {}, {}
        for side, (u, v) in {"front": ("[2, 0, 0]", "[0, 2, 0]"), "back": ("[0, 2, 0]", "[2, 0, 0]")}.items():
            scene = os.path.join(work, side + ".yaml")
            with open(scene, "w") as f:
                f.write(SCENE.format(u=u, v=v))
            js = os.path.join(work, side + ".json")
            subprocess.run([pathtrace, "--scene", scene, "--export", js], cwd=work, check=True,
                           stdout=subprocess.DEVNULL)
            exports[side] = js
            pfm = os.path.join(work, side + ".pfm")
            subprocess.run([pathtrace, "--scene", scene, "--integrator", "nee", "--pfm", pfm,
                            "--out", os.path.join(work, side + ".png")], cwd=work, check=True,
                           stdout=subprocess.DEVNULL)
            means[side] = mean_of_pfm(pfm)
            with open(js) as f:
                d = json.load(f)
            q = d["quads"][0]
            qu, qv = q["u"], q["v"]
            nz = qu[0] * qv[1] - qu[1] * qv[0]  # the normal's z: the camera is on +z
            if (nz > 0) != (side == "front"):
                failures.append(f"{side}: the exported quad's normal z is {nz}, not {'+' if side == 'front' else '-'}")
            for i, m in enumerate(d["materials"]):
                b = bsdf_of(m, i)
                if m["type"] == "lambertian" and not (b["type"] == "twosided" and b["bsdf"]["type"] == "diffuse"):
                    failures.append(f"{side}: lambertian material {i} converts to {b}, not a twosided diffuse")
        print(f"zraka: mean front {means['front']:.5f}, back {means['back']:.5f}")
        if not means["front"] > 0 or abs(means["front"] - means["back"]) > 0.02 * means["front"]:
            failures.append(f"zraka renders the quad's two sides differently: {means}")
        if mitsuba_python and os.path.exists(mitsuba_python) and subprocess.run(
                [mitsuba_python, "-c", "import mitsuba"], capture_output=True).returncode == 0:
            mm = {}
            for side, js in exports.items():
                out = os.path.join(work, side + "-mitsuba.pfm")
                subprocess.run([mitsuba_python, os.path.join(ROOT, "tools", "mitsuba_reference.py"), js,
                                "--spp", "64", "-o", out], cwd=work, check=True, stdout=subprocess.DEVNULL)
                mm[side] = mean_of_pfm(out)
            print(f"mitsuba: mean front {mm['front']:.5f}, back {mm['back']:.5f}")
            for side in mm:
                if abs(mm[side] - means["front"]) > 0.05 * means["front"]:
                    failures.append(f"Mitsuba's {side} ({mm[side]:.5f}) is not zraka's ({means['front']:.5f})")
        else:
            print("Mitsuba is not installed (bash tools/mitsuba-setup.sh): its renders are not compared")
    for f in failures:
        print("FAILED:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
