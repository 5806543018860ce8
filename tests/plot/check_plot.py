#!/usr/bin/env python3
"""The test book.plot: tools/plot_convergence.py draws a small convergence CSV to a PNG of the
size asked for (--width W: W x W/2 pixels), with nothing beyond the test's packages; and a file
that is not a convergence CSV is refused with an error naming it."""
import os
import struct
import subprocess
import sys
import tempfile

root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
script = os.path.join(root, "tools", "plot_convergence.py")


def png_size(path):
    with open(path, "rb") as f:
        head = f.read(24)
    assert head[:8] == b"\x89PNG\r\n\x1a\n", f"{path} is not a PNG"
    return struct.unpack(">II", head[16:24])


with tempfile.TemporaryDirectory() as d:
    csv = os.path.join(d, "small.csv")
    with open(csv, "w", encoding="utf-8") as f:  # the shape convergence_log::write_csv writes
        f.write("n,seconds,abs_error,std_error\n")
        for k in range(1, 9):
            n = 4**k
            f.write(f"{n},{n * 1e-6},{1.3 / n**0.5},{1.0 / n**0.5}\n")
    out = os.path.join(d, "small.png")
    subprocess.run([sys.executable, script, csv, "-o", out, "--width", "300", "--title", "test"], check=True)
    size = png_size(out)
    assert size == (300, 150), f"expected a 300x150 PNG, got {size}"
    assert not os.path.exists(out + ".tmp.png"), "the temporary file was left behind"

    bad = os.path.join(d, "bad.csv")
    with open(bad, "w", encoding="utf-8") as f:
        f.write("a,b\n1,2\n")
    r = subprocess.run([sys.executable, script, bad, "-o", os.path.join(d, "bad.png")], capture_output=True, text=True)
    assert r.returncode == 1 and "bad.csv" in r.stderr, f"exit {r.returncode}, stderr: {r.stderr}"
    assert not os.path.exists(os.path.join(d, "bad.png")), "a refused CSV still made a PNG"
print("book.plot: 300x150 PNG written, a bad CSV refused by name")
