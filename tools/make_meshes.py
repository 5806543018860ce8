#!/usr/bin/env python3
"""Writes the PLY and glTF test models and the malformed ones (mesh_file.hpp), deterministically.

    python3 tools/make_meshes.py        # from the repository's root

scenes/meshes/
  sphere.obj, sphere.ply (binary), sphere.gltf + sphere.bin, sphere.glb
        one UV sphere (radius 1, 24 x 12 segments, the seam's vertices doubled) written four ways
        with the same positions, unit normals and texture coordinates, for the test that every
        reader gives the same triangles; the glTF ones carry scenes/uv-grid.png as their
        base-colour texture (sphere.gltf refers to ../uv-grid.png, sphere.glb embeds it).
  quad.gltf, quad.obj
        a unit square in the xy plane whose corner (0, 0, 0) has OBJ uv (0, 0), the image's
        bottom-left, which glTF writes as (0, 1) (its v counts down from the top): the test of
        texture orientation.
tests/scenes/bad/mesh/
  malformed PLY and glTF files; expect.txt gives the words each one's error must contain.

Python's own struct, json, base64 only: nothing to install.
"""
import base64
import json
import math
import os
import struct

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MESHES = os.path.join(ROOT, "scenes", "meshes")
BAD = os.path.join(ROOT, "tests", "scenes", "bad", "mesh")


def f32(x):
    """x as the float32 that the binary files hold, so every format carries the same values."""
    return struct.unpack("<f", struct.pack("<f", x))[0]


def sphere(seg_u=24, seg_v=12):
    pos, nor, uv, tri = [], [], [], []
    for j in range(seg_v + 1):
        theta = math.pi * j / seg_v  # from the north pole
        for i in range(seg_u + 1):
            phi = 2 * math.pi * i / seg_u
            n = (math.sin(theta) * math.cos(phi), math.cos(theta), -math.sin(theta) * math.sin(phi))
            n = tuple(f32(round(c, 7)) for c in n)
            pos.append(n)
            nor.append(n)
            uv.append((f32(i / seg_u), f32(1 - j / seg_v)))  # OBJ's convention: v up
    w = seg_u + 1
    for j in range(seg_v):
        for i in range(seg_u):
            a, b, c, d = j * w + i, (j + 1) * w + i, (j + 1) * w + i + 1, j * w + i + 1
            if j != 0:
                tri.append((a, b, d))  # counter-clockwise seen from outside
            if j != seg_v - 1:
                tri.append((b, c, d))
    return pos, nor, uv, tri


def quad():
    pos = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (1.0, 1.0, 0.0), (0.0, 1.0, 0.0)]
    nor = [(0.0, 0.0, 1.0)] * 4
    uv = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]
    return pos, nor, uv, [(0, 1, 2), (0, 2, 3)]


def write(path, data):
    mode = "wb" if isinstance(data, bytes) else "w"
    with open(path, mode, **({} if mode == "wb" else {"encoding": "utf-8", "newline": "\n"})) as f:
        f.write(data)


def obj_text(model, comment):
    pos, nor, uv, tri = model
    lines = [f"# {comment} (tools/make_meshes.py)"]
    lines += [f"v {x:.9g} {y:.9g} {z:.9g}" for x, y, z in pos]
    lines += [f"vn {x:.9g} {y:.9g} {z:.9g}" for x, y, z in nor]
    lines += [f"vt {u:.9g} {v:.9g}" for u, v in uv]
    lines += ["f " + " ".join(f"{k + 1}/{k + 1}/{k + 1}" for k in t) for t in tri]
    return "\n".join(lines) + "\n"


def ply_header(fmt, nv, nf, comment="made by tools/make_meshes.py"):
    return (f"ply\nformat {fmt} 1.0\ncomment {comment}\nelement vertex {nv}\n"
            "property float x\nproperty float y\nproperty float z\n"
            "property float nx\nproperty float ny\nproperty float nz\n"
            "property float u\nproperty float v\n"
            f"element face {nf}\nproperty list uchar uint vertex_indices\nend_header\n")


def ply_binary(model):
    pos, nor, uv, tri = model
    body = b"".join(struct.pack("<8f", *p, *n, *t) for p, n, t in zip(pos, nor, uv))
    body += b"".join(struct.pack("<B3I", 3, *t) for t in tri)
    return ply_header("binary_little_endian", len(pos), len(tri)).encode() + body


def ply_ascii(model, header=None):
    pos, nor, uv, tri = model
    text = header or ply_header("ascii", len(pos), len(tri))
    text += "".join(" ".join(f"{c:.9g}" for c in (*p, *n, *t)) + "\n" for p, n, t in zip(pos, nor, uv))
    text += "".join(f"3 {a} {b} {c}\n" for a, b, c in tri)
    return text


def gltf(model, image=None, embed_image=None, bin_uri=None):
    """The glTF JSON and its binary buffer: positions, normals, uv (v turned to count down from
    the top), uint32 indices; one material whose base colour is the image."""
    pos, nor, uv, tri = model
    chunks = [b"".join(struct.pack("<3f", *p) for p in pos), b"".join(struct.pack("<3f", *n) for n in nor),
              b"".join(struct.pack("<2f", u, 1 - v) for u, v in uv), b"".join(struct.pack("<3I", *t) for t in tri)]
    if embed_image is not None:
        chunks.append(embed_image)
    views, offset = [], 0
    buf = b""
    for c in chunks:
        views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(c)})
        buf += c + b"\0" * (-len(c) % 4)
        offset = len(buf)
    lo = [min(p[k] for p in pos) for k in range(3)]
    hi = [max(p[k] for p in pos) for k in range(3)]
    doc = {
        "asset": {"version": "2.0", "generator": "zraka tools/make_meshes.py"},
        "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2},
                                    "indices": 3, "material": 0}]}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": len(pos), "type": "VEC3", "min": lo, "max": hi},
            {"bufferView": 1, "componentType": 5126, "count": len(nor), "type": "VEC3"},
            {"bufferView": 2, "componentType": 5126, "count": len(uv), "type": "VEC2"},
            {"bufferView": 3, "componentType": 5125, "count": 3 * len(tri), "type": "SCALAR"}],
        "bufferViews": views,
        "buffers": [{"byteLength": len(buf)}],
        "materials": [{"name": "uv-grid", "pbrMetallicRoughness": {
            "baseColorFactor": [1, 1, 1, 1], "metallicFactor": 0, "roughnessFactor": 1}}],
    }
    if bin_uri:
        doc["buffers"][0]["uri"] = bin_uri
    if image or embed_image is not None:
        doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {"index": 0}
        doc["textures"] = [{"source": 0, "sampler": 0}]
        doc["samplers"] = [{"wrapS": 10497, "wrapT": 10497}]
        doc["images"] = [{"uri": image} if image else {"bufferView": 4, "mimeType": "image/png"}]
    return doc, buf


def glb(doc, buf):
    js = json.dumps(doc, separators=(",", ":")).encode()
    js += b" " * (-len(js) % 4)
    body = struct.pack("<II", len(js), 0x4E4F534A) + js + struct.pack("<II", len(buf), 0x004E4942) + buf
    return struct.pack("<III", 0x46546C67, 2, 12 + len(body)) + body


def gltf_text(doc):
    return json.dumps(doc, indent=1) + "\n"


def data_uri(buf):
    return "data:application/octet-stream;base64," + base64.b64encode(buf).decode()


def main():
    os.makedirs(MESHES, exist_ok=True)
    os.makedirs(BAD, exist_ok=True)
    s, q = sphere(), quad()
    png = open(os.path.join(ROOT, "scenes", "uv-grid.png"), "rb").read()
    write(os.path.join(MESHES, "sphere.obj"), obj_text(s, "a UV sphere, radius 1, 24 x 12 segments"))
    write(os.path.join(MESHES, "sphere.ply"), ply_binary(s))
    doc, buf = gltf(s, image="../uv-grid.png", bin_uri="sphere.bin")
    write(os.path.join(MESHES, "sphere.gltf"), gltf_text(doc))
    write(os.path.join(MESHES, "sphere.bin"), buf)
    write(os.path.join(MESHES, "sphere.glb"), glb(*gltf(s, embed_image=png)))
    write(os.path.join(MESHES, "quad.obj"), obj_text(q, "a unit square, uv (0, 0) at the origin"))
    doc, buf = gltf(q, image="../uv-grid.png")
    doc["buffers"][0]["uri"] = data_uri(buf)
    write(os.path.join(MESHES, "quad.gltf"), gltf_text(doc))

    # The malformed files, each with the words its error must contain (expect.txt).
    expect = {}

    def bad(name, data, words):
        write(os.path.join(BAD, name), data)
        expect[name] = words

    t = ([(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)], [(0.0, 0.0, 1.0)] * 3,
         [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)], [(0, 1, 2)])
    good = ply_ascii(t)
    bad("empty.ply", "", "the file is empty")
    bad("empty.gltf", "", "the file is empty")
    bad("truncated.ply", good[: good.index("3 0 1 2")], "the PLY header declares 1 face elements, but the 0 bytes left")
    sb = ply_binary(s)
    bad("truncated-binary.ply", sb[: len(sb) // 2], "the PLY header declares 325 vertex elements")
    bad("huge-count.ply", ply_header("binary_little_endian", 4_000_000_000, 1).encode() + sb[-200:],
        "declares 4000000000 vertex elements")
    bad("count-overflow.ply", ply_header("ascii", 1, 1).replace("vertex 1", "vertex 99999999999999999999999")
        + "0 0 0 0 0 1 0 0\n3 0 0 0\n", "not a whole number of 64 bits")
    bad("broken-end-header.ply", good.replace("end_header", "end\x7f_header"), ":15: PLY header: a byte that is not printable ASCII (127)")
    bad("end-header-at-eof.ply", good[: good.index("end_header") + 10], ":15: PLY header: 'end_header' must end its line")
    bad("header-not-ascii.ply", good.replace("comment made", "comment \x01 made"), ":3: PLY header: a byte that is not printable ASCII (1)")
    bad("no-end-header.ply", good[: good.index("end_header")], "PLY header: no 'end_header' line")
    bad("bad-property-type.ply", good.replace("property float u", "property quad u"), ":11: PLY header: unknown type")
    bad("wrong-count.ply", ply_ascii(t, ply_header("ascii", 2, 1)), "face 0 has 0 corners")
    bad("nan-position.ply", good.replace("1 0 0 0 0 1", "nan 0 0 0 0 1", 1), "vertex 1 is (nan, 0, 0), not finite")
    bad("inf-position.ply", good.replace("1 0 0 0 0 1", "inf 0 0 0 0 1", 1), "vertex 1 is (inf, 0, 0), not finite")
    bad("index-out-of-range.ply", good.replace("3 0 1 2", "3 0 1 7"), "assimp cannot read it")
    bad("not-ply.ply", "solid cube\nendsolid\n", "assimp cannot read it")
    bad("points.ply", ply_ascii(t).replace("3 0 1 2", "1 0"), "a point or a line has no surface")

    doc, buf = gltf(t)
    bad("missing-bin.gltf", gltf_text(dict(doc, buffers=[{"byteLength": len(buf), "uri": "missing.bin"}])),
        "assimp cannot read it")
    doc, buf = gltf(t, image="missing.png")
    doc["buffers"][0]["uri"] = data_uri(buf)
    bad("missing-texture.gltf", gltf_text(doc), "baseColorTexture 'missing.png'")
    doc, buf = gltf(t)
    doc["buffers"][0]["uri"] = data_uri(buf)
    huge = json.loads(json.dumps(doc))
    huge["accessors"][0]["count"] = 2_000_000_000
    bad("huge-accessor.gltf", gltf_text(huge), "assimp cannot read it")
    oob = json.loads(json.dumps(doc))
    ib = bytearray(buf)
    struct.pack_into("<I", ib, doc["bufferViews"][3]["byteOffset"] + 8, 9)  # the third index: 9 of 3
    oob["buffers"][0]["uri"] = data_uri(bytes(ib))
    bad("index-out-of-range.gltf", gltf_text(oob), "assimp cannot read it")
    nanb = bytearray(buf)
    struct.pack_into("<f", nanb, 12, float("nan"))  # vertex 1's x
    nan = json.loads(json.dumps(doc))
    nan["buffers"][0]["uri"] = data_uri(bytes(nanb))
    bad("nan-position.gltf", gltf_text(nan), "vertex 1 is (nan, 0, 0), not finite")
    far = json.loads(json.dumps(doc))
    far["nodes"][0]["scale"] = [1e30, 1, 1]
    bad("far-node.gltf", gltf_text(far), "vertex 1 is (1, 0, 0) and its node's transform puts it")
    mime = json.loads(json.dumps(doc))
    mime["images"] = [{"uri": "../../../../scenes/uv-grid.png", "mimeType": "im\u00fepng"}]
    mime["textures"] = [{"source": 0}]
    mime["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {"index": 0}
    bad("mime-type-without-slash.gltf", gltf_text(mime), "an image's mimeType")
    bad("truncated.gltf", gltf_text(doc)[:200], "assimp cannot read it")
    g = glb(*gltf(s, embed_image=png))
    bad("truncated.glb", g[: len(g) // 2], "the GLB header declares 19232 bytes, the file has 9616")
    big = bytearray(g)
    struct.pack_into("<I", big, 12, 1919247471)  # the JSON chunk's length
    bad("huge-chunk.glb", bytes(big), "GLB chunk 0 declares 1919247471 bytes")
    short = json.loads(json.dumps(doc))
    short["buffers"][0]["byteLength"] = len(buf) * 1000
    bad("buffer-too-short.gltf", gltf_text(short), "assimp cannot read it")
    with open(os.path.join(BAD, "expect.txt"), "w", encoding="utf-8", newline="\n") as f:
        f.write("# Each malformed mesh file and the words its error must contain (made by tools/make_meshes.py)\n")
        for k in sorted(expect):
            f.write(f"{k}: {expect[k]}\n")
    print(f"wrote scenes/meshes/{{sphere,quad}}.* and {len(expect)} malformed files in tests/scenes/bad/mesh")


if __name__ == "__main__":
    main()
