#!/usr/bin/env python3
"""Renders a zraka scene with Mitsuba 3 (scalar_rgb), as an independent reference (book 4.2).
(`--variant llvm_ad_rgb` renders with Mitsuba's JIT-compiled SIMD variant instead, for speed
comparisons: bench/time_to_error's --mitsuba-variants.)

    bash tools/mitsuba-setup.sh                          # once: build/mitsuba-venv with mitsuba
    build/bin/pathtrace --scene cornell-glass --export cg.json
    build/mitsuba-venv/bin/python tools/mitsuba_reference.py cg.json --spp 1024 -o cg-mitsuba.pfm \
        [--compare cg-zraka.pfm]

The scene comes as the JSON that `pathtrace --export` writes: spheres, quads (boxes are six
quads), triangles (meshes are flattened into them), point lights, materials, a pinhole camera,
the environment, the image size and the maximum number of bounces. What maps one to one:
  lambertian -> twosided diffuse (zraka's Lambertian reflects on both sides; Mitsuba's diffuse
  alone is black from behind);  metal with fuzz 0 -> conductor 'none' scaled by the albedo (a mirror);
  dielectric -> dielectric (int_ior = ior, ext_ior = 1);  emitter -> black diffuse + area
  emitter (one-sided, like zraka's default);  point light -> point;  background -> constant.
  rough_conductor -> roughconductor, distribution ggx, alpha = zraka's alpha (not squared), eta
  and k per channel (zraka's presets are Mitsuba's own RGB values, microfacet.hpp);
  rough_dielectric -> roughdielectric, ggx, alpha, int_ior = ior.  Both sample visible normals.
  One difference remains, by design: Mitsuba's masking-shadowing is separable, G1(wo) G1(wi);
  zraka's is height-correlated, 1 / (1 + Lambda(wo) + Lambda(wi)), which is larger, so zraka's
  rough surfaces are brighter by a few per cent at large alpha and grazing angles (book 5.4).
  An image texture on a lambertian quad -> bitmap of zraka's linear texels (raw, bilinear,
  repeat or clamp), its rows flipped: Mitsuba puts row 0 at v = 0, zraka at v = 1; a rectangle's
  (u, v) is zraka's quad's (a, b).
  Environment: constant -> constant; a map -> envmap rotated about +y by `rotate` degrees. Its
  texels go over as zraka's bilinear function: Mitsuba interpolates between texel centres in u
  (as zraka) but puts its rows at v = j / (H - 1), poles included, while zraka's rows sit at
  v = (j + 1/2) / H, clamped at the poles; the map given to Mitsuba has 2H + 1 rows at
  v = j / (2H): zraka's rows, the means of neighbours between them, and the first and last row
  again at the poles, which is exactly zraka's piecewise bilinear radiance.
What has no exact Mitsuba counterpart is refused with a message: checker textures, fuzzy metal
(zraka's is RTIOW's fuzzed mirror, not a microfacet model), phong, two-sided emitters, planes
(and, already by the exporter: noise and roughness textures, an RGB f0, textures off quads).
Mitsuba's `path` integrator counts max_depth in path segments, so it gets zraka's bounces + 1;
the film uses a box filter, as zraka's pixel sampling does.

--compare prints RMSE, relative MSE, the mean of each channel of both images and the difference
of the means in standard errors (the spread of the per-pixel difference over sqrt(pixels)).
Render Mitsuba twice with different --seed and --compare its two images for its own noise;
--diff A.pfm B.pfm compares two files without rendering (two zraka renders of different seeds).
--doubling SECONDS renders 1, 2, 4, ... spp up to --spp, each a render of its own, and writes
OUT-<n>spp.pfm for each, printing `pass <n> <seconds> <file>` as each ends; it stops after a
render longer than SECONDS, or before the next one once a file OUT.stop exists (bench/time_to_error
reads the images as they come, measures their error itself, and makes that file when it is done).
Not part of the tests: Mitsuba is a few hundred MB from PyPI.
"""
import argparse
import json
import os
import sys
import tempfile
import time


def write_pfm(path, arr):
    import numpy as np

    h, w, _ = arr.shape
    tmp = path + ".tmp"
    with open(tmp, "wb") as f:
        f.write(f"PF\n{w} {h}\n-1.0\n".encode())
        f.write(np.ascontiguousarray(arr[::-1], dtype="<f4").tobytes())  # rows bottom to top
    os.replace(tmp, path)


def read_pfm(path):
    import numpy as np

    with open(path, "rb") as f:
        if f.readline().strip() != b"PF":
            sys.exit(f"{path}: not a colour PFM file")
        w, h = map(int, f.readline().split())
        if float(f.readline()) >= 0:
            sys.exit(f"{path}: big-endian PFM is not supported")
        data = np.frombuffer(f.read(w * h * 12), dtype="<f4")
    if data.size != w * h * 3:
        sys.exit(f"{path}: truncated PFM")
    return data.reshape(h, w, 3)[::-1].astype(np.float64)


def rgb(v):
    return {"type": "rgb", "value": [float(x) for x in v]}


def bitmap_of(tex, mi, np):
    """A Mitsuba bitmap texture equal to zraka's image texture (texture.hpp's lookup_bilinear)."""
    img = np.array(tex["texels"], dtype=np.float32).reshape(tex["height"], tex["width"], 3)
    return {"type": "bitmap", "bitmap": mi.Bitmap(np.ascontiguousarray(img[::-1])), "raw": True,
            "filter_type": "bilinear", "wrap_mode": "repeat" if tex["repeat"] else "clamp"}


def envmap_rows(img, np):
    """zraka's H rows (centres at v = (j + 1/2) / H, clamped at the poles) as 2H + 1 rows at
    v = j / (2H), where Mitsuba's envmap puts them: the same piecewise bilinear function."""
    h = img.shape[0]
    out = np.empty((2 * h + 1,) + img.shape[1:], dtype=np.float64)
    out[1::2] = img
    out[0], out[-1] = img[0], img[-1]
    out[2:-1:2] = 0.5 * (img[:-1].astype(np.float64) + img[1:])
    return out


def bsdf_of(m, index, mi=None, np=None):
    """The Mitsuba BSDF for zraka material `m`, or an error naming what cannot be converted."""
    kind = m["type"]
    if kind in ("lambertian", "emitter"):
        if m["checker"]:
            raise ValueError(f"material {index}: checker textures have no exact Mitsuba counterpart")
        if m.get("texture"):
            diffuse = {"type": "diffuse", "reflectance": bitmap_of(m["texture"], mi, np)}
        else:
            diffuse = {"type": "diffuse", "reflectance": rgb([0, 0, 0] if kind == "emitter" else m["albedo"])}
        # zraka's Lambertian reflects on both sides of a surface (a quad facing away from the
        # camera is lit the same), Mitsuba's diffuse on its front only: twosided makes them one.
        return {"type": "twosided", "bsdf": diffuse}
    if kind == "metal":
        if m["fuzz"] != 0:
            raise ValueError(f"material {index}: fuzzy metal (fuzz {m['fuzz']}) has no Mitsuba counterpart")
        return {"type": "conductor", "material": "none", "specular_reflectance": rgb(m["albedo"])}
    if kind == "dielectric":
        if float(m["ior"]) == 1.0 and m.get("interior", -1) >= 0:  # zraka's boundary: index-matched
            return {"type": "null"}
        return {"type": "dielectric", "int_ior": float(m["ior"]), "ext_ior": 1.0}
    if kind == "rough_conductor":  # book 5.4
        return {"type": "roughconductor", "distribution": "ggx", "alpha": float(m["alpha"]),
                "eta": rgb(m["eta"]), "k": rgb(m["k"])}
    if kind == "rough_dielectric":
        return {"type": "roughdielectric", "distribution": "ggx", "alpha": float(m["alpha"]),
                "int_ior": float(m["ior"]), "ext_ior": 1.0}
    raise ValueError(f"material {index}: type {kind} has no exact Mitsuba counterpart")


def emitter_of(m, index):
    if not any(m["radiance"]):
        return None
    if m["two_sided"]:
        raise ValueError(f"material {index}: Mitsuba's area emitters are one-sided")
    return {"type": "area", "radiance": rgb(m["radiance"])}


def scene_dict(js, mi, workdir):
    import numpy as np

    T = mi.ScalarTransform4f
    cam = js["camera"]
    media = js.get("media", [])
    d = {
        "type": "scene",
        # volpath when there are media (book 6.1): Mitsuba's homogeneous medium with an hg phase
        "integrator": {"type": "volpath" if media else "path", "max_depth": int(js["max_depth"]) + 1},
        "sensor": {
            "type": "perspective",
            "fov": float(cam["vfov"]),
            "fov_axis": "y",
            "to_world": T().look_at(origin=cam["position"], target=cam["look_at"], up=cam["up"]),
            "film": {"type": "hdrfilm", "width": int(js["width"]), "height": int(js["height"]),
                     "rfilter": {"type": "box"}, "pixel_format": "rgb"},
            "sampler": {"type": "independent"},
        },
    }
    for i, md in enumerate(media):
        st = [a + s for a, s in zip(md["sigma_a"], md["sigma_s"])]
        d[f"medium{i}"] = {"type": "homogeneous", "sigma_t": rgb(st),
                           "albedo": rgb([s / t if t > 0 else 0.0 for s, t in zip(md["sigma_s"], st)]),
                           "phase": {"type": "hg", "g": float(md["g"])} if md["g"] != 0 else {"type": "isotropic"}}
    if js.get("global_medium", -1) >= 0:
        d["sensor"]["medium"] = {"type": "ref", "id": f"medium{js['global_medium']}"}
    mats = js["materials"]
    bsdfs = [bsdf_of(m, i, mi, np) for i, m in enumerate(mats)]
    emitters = [emitter_of(m, i) for i, m in enumerate(mats)]

    def shape(s, mat, name):
        s["bsdf"] = bsdfs[mat]
        if mats[mat].get("interior", -1) >= 0:
            s["interior"] = {"type": "ref", "id": f"medium{mats[mat]['interior']}"}
            if js.get("global_medium", -1) >= 0:
                s["exterior"] = {"type": "ref", "id": f"medium{js['global_medium']}"}
        if emitters[mat]:
            s["emitter"] = emitters[mat]
        d[name] = s

    for i, s in enumerate(js["spheres"]):
        shape({"type": "sphere", "center": s["center"], "radius": float(s["radius"])}, s["material"], f"sphere{i}")
    for i, q in enumerate(js["quads"]):
        # Mitsuba's rectangle is [-1,1]^2 at z = 0 facing +z: map it onto corner + a u + b v.
        u, v, c = q["u"], q["v"], q["corner"]
        n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
        ln = sum(x * x for x in n) ** 0.5
        n = [x / ln for x in n]
        centre = [c[k] + 0.5 * u[k] + 0.5 * v[k] for k in range(3)]
        m = [[0.5 * u[r], 0.5 * v[r], n[r], centre[r]] for r in range(3)] + [[0, 0, 0, 1]]
        shape({"type": "rectangle", "to_world": T(m)}, q["material"], f"quad{i}")
    by_material = {}
    for t in js.get("triangles", []):
        by_material.setdefault(t["material"], []).append(t)
    for mat, tris in by_material.items():  # one flat-shaded OBJ per material
        path = os.path.join(workdir, f"mesh{mat}.obj")
        with open(path, "w", encoding="utf-8") as f:
            for t in tris:
                for p in (t["a"], t["b"], t["c"]):
                    f.write("v %.17g %.17g %.17g\n" % tuple(p))
            for k in range(len(tris)):
                f.write(f"f {3 * k + 1} {3 * k + 2} {3 * k + 3}\n")
        shape({"type": "obj", "filename": path, "face_normals": True}, mat, f"mesh{mat}")
    for i, p in enumerate(js.get("point_lights", [])):
        d[f"point{i}"] = {"type": "point", "position": p["position"], "intensity": rgb(p["intensity"])}
    env = js.get("environment")
    if env and env["type"] == "constant":
        d["sky"] = {"type": "constant", "radiance": rgb(env["radiance"])}
    elif env:  # book 5.3: the map, turned about +y as zraka turns it (environment.hpp)
        img = np.array(env["texels"], dtype=np.float32).reshape(env["height"], env["width"], 3)
        d["sky"] = {"type": "envmap", "bitmap": mi.Bitmap(envmap_rows(img, np).astype(np.float32)),
                    "to_world": T().rotate([0, 1, 0], float(env["rotate"]))}
    elif any(js["background"]):
        d["sky"] = {"type": "constant", "radiance": rgb(js["background"])}
    return d


def compare(ours_path, theirs, crop=None, names=("zraka", "Mitsuba")):
    import numpy as np

    ours = read_pfm(ours_path)
    if ours.shape != theirs.shape:
        sys.exit(f"{ours_path} is {ours.shape[1]}x{ours.shape[0]}, Mitsuba's {theirs.shape[1]}x{theirs.shape[0]}")
    if crop:  # x0 y0 x1 y1, pixels, x1 and y1 excluded, rows from the top
        x0, y0, x1, y1 = crop
        if not (0 <= x0 < x1 <= ours.shape[1] and 0 <= y0 < y1 <= ours.shape[0]):
            sys.exit(f"error: --crop {x0} {y0} {x1} {y1} is not inside the {ours.shape[1]}x{ours.shape[0]} image")
        ours, theirs = ours[y0:y1, x0:x1], theirs[y0:y1, x0:x1]
        print(f"pixels [{x0}, {x1}) x [{y0}, {y1}) only")
    diff = ours - theirs
    rmse = float(np.sqrt(np.mean(diff * diff)))
    relmse = float(np.mean(diff * diff / (theirs * theirs + 0.01)))
    mo, mt = ours.reshape(-1, 3).mean(0), theirs.reshape(-1, 3).mean(0)
    print(f"RMSE {rmse:.5f}, relMSE {relmse:.5f}")
    a, b = names
    print(f"mean R G B: {a} %.5f %.5f %.5f, {b} %.5f %.5f %.5f" % (*mo, *mt))
    print(f"{a}/{b} - 1 per channel: %+.4f %+.4f %+.4f" % tuple(mo / mt - 1))
    se = diff.reshape(-1, 3).std(0, ddof=1) / np.sqrt(diff.shape[0] * diff.shape[1])
    print("difference of the means in standard errors: %+.1f %+.1f %+.1f" % tuple((mo - mt) / se))


def doubling(mi, np, scene, a):
    stem = a.out[:-4] if a.out.endswith(".pfm") else a.out
    n = 1
    while n <= a.spp and not os.path.exists(a.out + ".stop"):
        start = time.time()
        img = np.array(mi.render(scene, spp=n, seed=a.seed), dtype=np.float64)[:, :, :3]
        secs = time.time() - start
        name = f"{stem}-{n}spp.pfm"
        write_pfm(name, img)
        print(f"pass {n} {secs:.6f} {name}", flush=True)
        if secs > a.doubling:
            break
        n *= 2


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scene", nargs="?", help="JSON written by `pathtrace --export`")
    ap.add_argument("-o", "--out", help="PFM file to write")
    ap.add_argument("--spp", type=int, default=256, help="samples per pixel (default 256)")
    ap.add_argument("--seed", type=int, default=0, help="Mitsuba's sampler seed")
    ap.add_argument("--compare", help="a zraka PFM of the same scene: print RMSE and channel means")
    ap.add_argument("--crop", type=int, nargs=4, metavar=("X0", "Y0", "X1", "Y1"),
                    help="compare only pixels x0 <= x < x1, y0 <= y < y1 (rows from the top)")
    ap.add_argument("--variant", default="scalar_rgb", choices=["scalar_rgb", "llvm_ad_rgb"],
                    help="Mitsuba's variant (default scalar_rgb; llvm_ad_rgb needs libLLVM)")
    ap.add_argument("--doubling", type=float, metavar="SECONDS",
                    help="render 1, 2, 4, ... spp up to --spp, one PFM each, until a render takes longer")
    ap.add_argument("--diff", nargs=2, metavar=("A.pfm", "B.pfm"),
                    help="render nothing: compare two PFM files (e.g. two zraka renders, for their noise)")
    a = ap.parse_args()
    if a.diff:
        compare(a.diff[0], read_pfm(a.diff[1]), a.crop, ("A", "B"))
        return
    if not a.scene or not a.out:
        sys.exit("error: give the scene JSON and -o OUT.pfm (or --diff A.pfm B.pfm)")
    if a.spp < 1:
        sys.exit("error: --spp must be at least 1")
    with open(a.scene, encoding="utf-8") as f:
        js = json.load(f)

    import mitsuba as mi
    import numpy as np

    mi.set_variant(a.variant)
    with tempfile.TemporaryDirectory() as work:
        try:
            d = scene_dict(js, mi, work)
        except ValueError as e:
            sys.exit(f"error: {e}")
        scene = mi.load_dict(d)
        if a.doubling is not None:
            doubling(mi, np, scene, a)
            return
        start = time.time()
        img = np.array(mi.render(scene, spp=a.spp, seed=a.seed), dtype=np.float64)[:, :, :3]
        secs = time.time() - start
    write_pfm(a.out, img)
    print(f"Mitsuba {mi.__version__} {a.variant}: {js['width']}x{js['height']}, {a.spp} spp, "
          f"max_depth {js['max_depth'] + 1} (zraka: {js['max_depth']} bounces) in {secs:.1f} s; wrote {a.out}")
    if a.compare:
        compare(a.compare, img, a.crop)


if __name__ == "__main__":
    main()
