#!/usr/bin/env python3
"""The test headers.self_contained: every header of include/zraka (and its folders) compiles on its own, header-only
(no ZRAKA_COMPILED), included twice (its include guard), with the project's warnings. Only the
compiler's front end runs (-fsyntax-only): a missing #include or declaration is a front-end
error, and the headers hold no code worth generating. A test rather than part of the build, so a
clean build does not parse 90 headers one by one (~100 CPU-s), and it runs on every core.
Usage: check_headers.py CXX INCLUDE_DIR -- FLAGS..."""
import concurrent.futures
import os
import subprocess
import sys
import tempfile


def main():
    cxx, include = sys.argv[1], sys.argv[2]
    flags = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    top = os.path.join(include, "zraka")
    headers = sorted(os.path.relpath(os.path.join(d, h), top) for d, _, hs in os.walk(top) for h in hs
                     if h.endswith(".hpp"))
    assert len(headers) > 50, f"only {len(headers)} headers in {include}/zraka"

    def check(h):
        with tempfile.NamedTemporaryFile("w", suffix=".cpp") as f:
            f.write(f"#include <zraka/{h}>\n#include <zraka/{h}>\n")
            f.flush()
            r = subprocess.run([cxx, "-std=c++20", "-fsyntax-only", f"-I{include}"] + flags + [f.name],
                               capture_output=True, text=True)
        return h, r.returncode, r.stdout + r.stderr

    failed = []
    with concurrent.futures.ThreadPoolExecutor(os.cpu_count() or 2) as pool:
        for h, code, out in pool.map(check, headers):
            if code != 0:
                failed.append(h)
                print(f"FAILED: zraka/{h} does not compile on its own:\n{out}")
    print(f"{len(headers) - len(failed)} of {len(headers)} headers compile on their own")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
