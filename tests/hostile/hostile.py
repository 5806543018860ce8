#!/usr/bin/env python3
"""Hostile inputs against the chapter programs, under an address-space limit (issue 18).

    hostile.py SCENES PATHTRACE       (the programs of chapters 4.1 and 2.3)

Each case runs one program on a small hostile input (every file here is under 1 MB) with
RLIMIT_AS = 1 GiB (what `ulimit -v 1048576` sets) and a time limit, and checks the exit code and a
message: no crash, no hang, no std::bad_alloc, and the error names what is wrong. Some cases are
legal but large inputs that must still fit (exit 0). Every path-tracer case writes over an
existing keep.png/keep.pfm, which must survive byte for byte, with no temporary left beside it.
"""
import os
import re
import signal
import subprocess
import sys
import tempfile
import time
import resource

ADDRESS_SPACE = 1 << 30   # 1 GiB
TIME_LIMIT = 120          # seconds; a hang fails the case
KEEP = {"keep.png": b"\x89PNG not really, but these bytes must stay\n" * 7,
        "keep.pfm": b"PF\n1 1\n-1.0\n" + b"\0" * 12}


def limit_memory():
    resource.setrlimit(resource.RLIMIT_AS, (ADDRESS_SPACE, ADDRESS_SPACE))


def wait_with_usage(p):
    """Exit code (None after a time-out) and resource usage (peak RSS) of the child."""
    deadline = time.monotonic() + TIME_LIMIT
    while True:
        pid, status, usage = os.wait4(p.pid, os.WNOHANG)
        if pid:
            p.returncode = os.waitstatus_to_exitcode(status)  # reaped here: tell Popen
            return p.returncode, usage
        if time.monotonic() > deadline:
            p.kill()
            os.wait4(p.pid, 0)
            p.returncode = -9
            return None, usage
        time.sleep(0.01)


def write(name, data):
    with open(name, "wb" if isinstance(data, bytes) else "w") as f:
        f.write(data)
    assert os.path.getsize(name) < 1 << 20, f"{name}: a hostile input must stay under 1 MB"


def exr_header(w, h):
    """A single-part scanline OpenEXR header for w x h RGB float pixels, without the pixels."""
    import struct
    def attr(name, kind, value):
        return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(value)) + value
    channels = b"".join(c.encode() + b"\0" + struct.pack("<iBBBBii", 2, 0, 0, 0, 0, 1, 1) for c in "BGR") + b"\0"
    box = struct.pack("<iiii", 0, 0, w - 1, h - 1)
    return (b"\x76\x2f\x31\x01" + struct.pack("<i", 2) + attr("channels", "chlist", channels) +
            attr("compression", "compression", b"\0") + attr("dataWindow", "box2i", box) +
            attr("displayWindow", "box2i", box) + attr("lineOrder", "lineOrder", b"\0") +
            attr("pixelAspectRatio", "float", struct.pack("<f", 1)) +
            attr("screenWindowCenter", "v2f", struct.pack("<ff", 0, 0)) +
            attr("screenWindowWidth", "float", struct.pack("<f", 1)) + b"\0")


def make_inputs():
    # Billion laughs: nine levels of ten aliases are 10^9 nodes once expanded.
    lines = ["a0: &a0 [lol, lol, lol, lol, lol, lol, lol, lol, lol, lol]"]
    lines += [f"a{i}: &a{i} [" + ", ".join([f"*a{i-1}"] * 10) + "]" for i in range(1, 10)]
    write("laughs.yaml", "objects: [{type: sphere}]\nunused:\n" + "".join(f"  {l}\n" for l in lines))
    write("laughs-objects.yaml", "s: &s {type: sphere}\nl0: &l0 [*s, *s, *s, *s, *s, *s, *s, *s, *s, *s]\n" +
          "".join(f"l{i}: &l{i} [" + ", ".join([f"*l{i-1}"] * 10) + "]\n" for i in range(1, 8)) +
          "objects: *l7\n")
    write("deep.yaml", "objects: " + "[" * 200000 + "]" * 200000 + "\n")
    write("divs.yaml", "objects: [{type: bezier, file: teapot.bpt, divs: 1024}]\n")
    write("teapots.yaml", "objects:\n" + "  - {type: bezier, file: teapot.bpt, divs: 150}\n" * 1000)
    write("limit-teapot.yaml", "objects: [{type: bezier, file: teapot.bpt, divs: 249}]\n")  # 3984032 triangles
    write("fine-teapot.yaml", "objects: [{type: bezier, file: teapot.bpt, divs: 200}]\n")
    os.mkfifo("fifo.obj")
    os.mkfifo("fifo.yaml")
    os.mkfifo("fifo.pfm")
    os.mkdir("folder.yaml")
    os.mkdir("outdir")
    write("fifo-mesh.yaml", "objects: [{type: mesh, file: fifo.obj}]\n")
    # Mitsuba XML (mitsuba_xml.hpp): a DTD's entities are never expanded; 120000 nested elements;
    # an OBJ that is a FIFO.
    write("laughs.xml", "<!DOCTYPE scene [<!ENTITY l0 \"lol\">" +
          "".join(f"<!ENTITY l{i} \"" + f"&l{i-1};" * 10 + "\">" for i in range(1, 10)) +
          "]>\n<scene version=\"3.0.0\"><bsdf type=\"diffuse\" id=\"&l9;\"/></scene>\n")
    write("deep.xml", "<scene version=\"3.0.0\">" + "<b>" * 120000 + "</b>" * 120000 + "</scene>\n")
    write("fifo-mesh.xml", "<scene version=\"3.0.0\"><shape type=\"obj\"><string name=\"filename\" value=\"fifo.obj\"/>"
          "<boolean name=\"face_normals\" value=\"true\"/>"
          "<bsdf type=\"dielectric\"/></shape></scene>\n")
    write("urandom-mesh.yaml", "objects: [{type: mesh, file: /dev/urandom}]\n")
    write("stdin-mesh.yaml", "objects: [{type: mesh, file: /dev/stdin}]\n")
    # One face with 200000 corners: legal, 199998 triangles, about 1 MB.
    n = 200000
    write("fan.obj", "".join(f"v {i % 7} {i % 5} 0\n" for i in range(8)) +
          "f " + " ".join(str(1 + i % 8) for i in range(n)) + "\n")
    write("fan.yaml", "objects: [{type: mesh, file: fan.obj}]\n")
    write("nan.obj", "v 0 0 0\nv nan 1 0\nv 0 0 1\nf 1 2 3\n")
    write("nan-mesh.yaml", "objects: [{type: mesh, file: nan.obj}]\n")
    write("vt.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/2 3/1\n")
    write("vt-mesh.yaml", "objects: [{type: mesh, file: vt.obj}]\n")
    # PLY and glTF (mesh_file.hpp, assimp): counts that a small file cannot hold, a FIFO as buffer.
    ply_props = "".join(f"property float {c}\n" for c in "xyz")
    write("huge.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\n" + ply_props +
          "element face 1\nproperty list uchar uint vertex_indices\nend_header\n" + "\0" * 200)
    write("huge-ply.yaml", "objects: [{type: mesh, file: huge.ply}]\n")
    import base64
    import json
    tri = b"".join(__import__("struct").pack("<3f", *v) for v in [(0, 0, 0), (1, 0, 0), (0, 1, 0)])
    def gltf(count, uri):
        return json.dumps({"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
                           "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
                           "accessors": [{"bufferView": 0, "componentType": 5126, "count": count, "type": "VEC3",
                                          "min": [0, 0, 0], "max": [1, 1, 0]}],
                           "bufferViews": [{"buffer": 0, "byteLength": 36}],
                           "buffers": [{"byteLength": 36, "uri": uri}]})
    write("huge.gltf", gltf(2000000000, "data:application/octet-stream;base64," + base64.b64encode(tri).decode()))
    write("huge-gltf.yaml", "objects: [{type: mesh, file: huge.gltf}]\n")
    os.mkfifo("fifo.bin")
    write("fifo-bin.gltf", gltf(3, "fifo.bin"))
    write("fifo-bin.yaml", "objects: [{type: mesh, file: fifo-bin.gltf}]\n")
    write("far.yaml", "camera: {focus_distance: 1e308}\nobjects: [{type: sphere}]\n")
    # Many objects, about 1 MB: legal.
    write("spheres.yaml", "objects:\n" + "".join(f"  - {{type: sphere, center: [{i % 97}, {i % 89}, {i % 83}], radius: 0.25}}\n"
                                                  for i in range(18000)))
    # One flow list of half a million numbers under an unknown key: 500 k YAML nodes, then an error.
    write("numbers.yaml", "objects: [{type: sphere}]\nnumbers: [" + ",".join(["0"] * 500000) + "]\n")
    nan_px = bytes.fromhex("00000000") + bytes.fromhex("0000c07f") + bytes.fromhex("00000000")
    write("nan.pfm", b"PF\n24 24\n-1.0\n" + nan_px * (24 * 24))
    write("huge.pfm", b"PF\n16384 8192\n-1.0\n")
    # OpenEXR headers: one that declares 16384 x 8192 float pixels (and holds none), one cut short.
    write("huge.exr", exr_header(16384, 8192))
    write("cut.exr", exr_header(24, 24)[:60])


def cases(scenes, pathtrace):
    S, P = scenes, pathtrace
    def pt(*extra, width="24", height="24", spp="4"):
        return [P, "--width", width, "--height", height, "--spp", spp, "--out", "keep.png", "--pfm", "keep.pfm", *extra]
    PT = pt()
    msg_nodes = r"more than 1000000 YAML nodes \(an alias counts each time it is used\) \(raise with --limit yaml_nodes=N\)"
    return [
        # name, command, expected exit, regex the output must match, stdin
        ("billion laughs", [S, "--scene", "laughs.yaml"], 1, msg_nodes, None),
        ("billion laughs, path tracer", PT + ["--scene", "laughs.yaml"], 1, msg_nodes, None),
        ("aliased objects (10^8 spheres)", [S, "--scene", "laughs-objects.yaml"], 1, msg_nodes, None),
        ("200000 nested lists", [S, "--scene", "deep.yaml"], 1, r"error: deep.yaml:\d+:\d+: YAML nesting deeper than", None),
        ("teapot at divs 1024", [S, "--scene", "divs.yaml"], 1,
         r"objects\[0\].divs: the scene would have 67108864 triangles, more than the limit of 4000000 "
         r"\(raise with --limit triangles=N\)", None),
        ("a thousand teapots", PT + ["--scene", "teapots.yaml"], 1,
         r"objects\[2\].divs: the scene would have 4320000 triangles, more than the limit of 4000000", None),
        ("a raised limit is a raised limit", [S, "--scene", "fine-teapot.yaml", "--limit", "triangles=3000000", "--quiet"], 0,
         r"1 mesh \(2560000 triangles", None),
        ("a teapot of 3.97 M triangles, at the limit (legal)",
         [P, "--scene", "limit-teapot.yaml", "--width", "16", "--height", "16", "--spp", "1", "--out", "big.png"], 0,
         r"wrote .*big.png", None),
        ("XML entities (a billion laughs in a DTD)", [S, "--scene", "laughs.xml"], 1,
         r"error: laughs.xml:2: <scene>: the scene has no <sensor>", None),
        ("120000 nested XML elements", PT + ["--scene", "deep.xml"], 1,
         r"error: deep.xml:1: <b>: unknown element <b>", None),
        ("XML mesh is a FIFO", [S, "--scene", "fifo-mesh.xml"], 1, r"fifo.obj: is a FIFO \(named pipe\)", None),
        ("mesh is a FIFO", [S, "--scene", "fifo-mesh.yaml"], 1,
         r"objects\[0\].file: fifo.obj: is a FIFO \(named pipe\); only regular files are read", None),
        ("scene is a FIFO", [S, "--scene", "fifo.yaml"], 1, r"error: fifo.yaml: is a FIFO \(named pipe\); only regular files", None),
        ("scene is /dev/zero", [S, "--scene", "/dev/zero"], 1, r"error: /dev/zero: is a character device; only regular files", None),
        ("scene is /dev/stdin, an endless pipe", [S, "--scene", "/dev/stdin"], 1, r"error: /dev/stdin: is a FIFO", "endless"),
        ("scene is a folder", [S, "--scene", "folder.yaml"], 1, r"error: folder.yaml: is a directory; only regular files", None),
        ("mesh is /dev/urandom", [S, "--scene", "urandom-mesh.yaml"], 1, r"/dev/urandom: is a character device", None),
        ("mesh is /dev/stdin, an endless pipe", [S, "--scene", "stdin-mesh.yaml"], 1, r"/dev/stdin: is a FIFO", "endless"),
        ("a face of 200000 corners (legal)", [S, "--scene", "fan.yaml", "--quiet"], 0, r"1 mesh \(199998 triangles", None),
        ("18000 spheres in 1 MB (legal)", [S, "--scene", "spheres.yaml", "--quiet"], 0, r"18000 spheres", None),
        ("500000 numbers under an unknown key", [S, "--scene", "numbers.yaml"], 1, r"numbers.yaml:2:1: numbers: unknown key", None),
        ("NaN in an OBJ, path tracer", PT + ["--scene", "nan-mesh.yaml"], 1,
         r"objects\[0\].file: nan.obj:2:3: vertex coordinate: 'nan' is not a finite number", None),
        ("texture index out of range", PT + ["--scene", "vt-mesh.yaml"], 1,
         r"vt.obj:5:7: refers to texture coordinate 2, but only 1 are defined before it", None),
        ("a PLY header of 4e9 vertices in 300 bytes", PT + ["--scene", "huge-ply.yaml"], 1,
         r"objects\[0\].file: huge.ply: the PLY header declares 4000000000 vertex elements, but the 200 bytes", None),
        ("a glTF accessor of 2e9 vertices on 36 bytes", PT + ["--scene", "huge-gltf.yaml"], 1,
         r"objects\[0\].file: huge.gltf: assimp cannot read it: .*out of range", None),
        ("a glTF whose .bin buffer is a FIFO", [S, "--scene", "fifo-bin.yaml"], 1,
         r"objects\[0\].file: fifo-bin.gltf: .*fifo.bin: is a FIFO \(named pipe\); only regular files are read", None),
        ("image plane at 1e308", PT + ["--scene", "far.yaml"], 1,
         r"camera.focus_distance: must be within \+-1e18 \(its square would overflow\), got 1e308", None),
        ("--threads 1000000", PT + ["--threads", "1000000"], 1,
         r"error: --threads 1000000 is more than \d+ \(8 per core on this \d+-core machine\) "
         r"\(raise with --limit threads_per_core=N\)", None),
        ("--threads 2147483647", PT + ["--threads", "2147483647"], 1, r"error: --threads 2147483647 is more than", None),
        ("--threads beyond int", PT + ["--threads", "99999999999"], 1, r"error: .*--threads", None),
        ("--spp 2000000000", pt(spp="2000000000"), 1, r"error: --spp must be in 1..65536, got 2000000000", None),
        ("4096 x 4096 pixels at 65536 spp", pt(width="4096", height="4096", spp="65536"), 1,
         r"4096x4096 pixels at 65536 spp are more samples than the limit of 4294967296 \(raise with --limit samples=N\)",
         None),
        ("8192 x 8192 pixels", pt(width="8192", height="8192"), 1,
         r"the image size 8192x8192 in pixels is 67108864, more than the limit of 16777216", None),
        ("--reference with a NaN pixel", PT + ["--reference", "nan.pfm"], 1, r"nan.pfm: pixel \(0, 0\) is NaN or infinite",
         None),
        ("--reference /dev/zero", PT + ["--reference", "/dev/zero"], 1, r"/dev/zero: is a character device", None),
        ("--reference a FIFO", PT + ["--reference", "fifo.pfm"], 1, r"fifo.pfm: is a FIFO", None),
        ("--reference a 134 M-pixel header", PT + ["--reference", "huge.pfm"], 1,
         r"huge.pfm: the image size 16384x8192 in pixels is 134217728, more than the limit", None),
        ("--reference an EXR header of 134 M pixels", PT + ["--reference", "huge.exr"], 1,
         r"huge.exr: the image size 16384x8192 in pixels is 134217728, more than the limit", None),
        ("--reference a truncated EXR", PT + ["--reference", "cut.exr"], 1, r"cut.exr: malformed EXR header", None),
        ("--limit with an unknown name", PT + ["--limit", "memory=1"], 1, r"error: --limit: unknown limit 'memory'", None),
        ("--limit with a negative value", PT + ["--limit", "triangles=-5"], 1,
         r"error: --limit triangles: expected a positive integer, got '-5'", None),
        ("--limit lowered", PT + ["--scene", "scenes/teapot.yaml", "--limit", "yaml_nodes=10"], 1,
         r"more than 10 YAML nodes", None),
        ("--out empty", [P, "--width", "8", "--height", "8", "--spp", "1", "--out", ""], 1,
         r"error: the output file name is empty", None),
        ("--out a folder only", [P, "--width", "8", "--height", "8", "--spp", "1", "--out", "outdir/"], 1,
         r"error: cannot write 'outdir/': it names a folder, not a file", None),
    ]


def main():
    scenes, pathtrace = (os.path.abspath(p) for p in sys.argv[1:3])
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    env = dict(os.environ, ZRAKA_ROOT=root)
    failures = 0
    with tempfile.TemporaryDirectory(prefix="zraka-hostile-") as work:
        os.chdir(work)
        os.symlink(os.path.join(root, "scenes"), "scenes")
        write("teapot.bpt", open(os.path.join(root, "scenes", "teapot.bpt")).read())
        make_inputs()
        for name, cmd, code, rx, stdin in cases(scenes, pathtrace):
            for k, v in KEEP.items():
                write(k, v)
            feeder = subprocess.Popen(["yes", "objects: [{type: sphere}]"], stdout=subprocess.PIPE) if stdin else None
            start = time.monotonic()
            rss = 0
            with tempfile.TemporaryFile() as log:
                p = subprocess.Popen(cmd, stdin=feeder.stdout if feeder else subprocess.DEVNULL, stdout=log,
                                     stderr=subprocess.STDOUT, preexec_fn=limit_memory, env=env)
                rc, usage = wait_with_usage(p)
                rss = usage.ru_maxrss // 1024
                log.seek(0)
                out = log.read().decode("utf-8", "replace")
            if feeder:
                feeder.kill()
                feeder.wait()
            secs = time.monotonic() - start
            problems = []
            if rc != code:
                problems.append(f"exit code {rc}, expected {code}")
            if not re.search(rx, out):
                problems.append(f"output lacks /{rx}/")
            if re.search(r"bad_alloc|terminate|Aborted|Segmentation", out):
                problems.append("the output shows a crash")
            for k, v in KEEP.items():
                if open(k, "rb").read() != v:
                    problems.append(f"{k} was changed")
            left = [f for f in os.listdir(".") if ".zraka-tmp." in f]
            if left:
                problems.append(f"temporaries left: {left}")
            status = "ok" if not problems else "FAILED"
            print(f"{status:6} {name} ({secs:.2f} s, peak {rss} MiB): {out.strip().splitlines()[-1] if out.strip() else ''}")
            for pr in problems:
                print(f"       {pr}\n       $ {' '.join(cmd)}\n       " + out.strip().replace("\n", "\n       "))
            failures += bool(problems)
        # SIGINT while rendering: the process ends by the signal; keep.png stays, nothing is left.
        for k, v in KEEP.items():
            write(k, v)
        p = subprocess.Popen([pathtrace, "--width", "200", "--height", "200", "--spp", "65536", "--out", "keep.png",
                              "--pfm", "keep.pfm"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                             preexec_fn=limit_memory, env=env)
        time.sleep(1.0)
        p.send_signal(signal.SIGINT)
        rc = p.wait(timeout=30)
        ok = rc == -signal.SIGINT and all(open(k, "rb").read() == v for k, v in KEEP.items()) and \
            not [f for f in os.listdir(".") if ".zraka-tmp." in f]
        print(f"{'ok' if ok else 'FAILED':6} SIGINT during a render: exit {rc}, outputs intact")
        failures += not ok
    total = len(cases("", "")) + 1
    print(f"{total - failures} of {total} hostile cases passed (address space limited to {ADDRESS_SPACE >> 20} MiB)")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
