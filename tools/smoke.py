#!/usr/bin/env python3
"""Smoke test for one chapter program: runs it as its chapters/<N.M>-<slug>/smoke.txt says and
checks the output, not only the exit code.

smoke.txt holds one or more cases; each starts with a `run:` line:
    run: <arguments>           run the program with these arguments (shell-like quoting)
    exit: <code>               expected exit code (default 0)
    expect: <regex>            must match somewhere in stdout+stderr (every expect line must)
    reject: <regex>            must not match
    file: <name>               the run must have written this non-empty file (PNG/PPM/PFM/CSV
                               files are checked for a valid header)
    absent: <name>             the run must not have left this file behind
    wrap: <command>            run the program through this command (shell-like quoting), e.g.
                               `xvfb-run -a -s "-screen 0 1280x720x24 -noreset"` for an X display, or
                               `env -u DISPLAY` to take it away; the case is skipped (with a
                               message) when the command is not installed
Lines starting with # are comments. Runs happen in the current directory (CTest gives each
chapter a folder of its own).
"""
import os
import re
import shlex
import shutil
import subprocess
import sys


def parse(path):
    cases, case = [], None
    with open(path, encoding="utf-8") as f:
        for lineno, raw in enumerate(f, 1):
            line = raw.rstrip("\n")
            if not line.strip() or line.lstrip().startswith("#"):
                continue
            key, sep, value = line.partition(":")
            if not sep:
                sys.exit(f"{path}:{lineno}: expected 'key: value'")
            key, value = key.strip(), value.strip()
            if key == "run":
                case = {"args": shlex.split(value), "exit": 0, "expect": [], "reject": [],
                        "file": [], "absent": [], "wrap": [], "line": lineno}
                cases.append(case)
            elif case is None:
                sys.exit(f"{path}:{lineno}: '{key}' before the first 'run:'")
            elif key == "exit":
                case["exit"] = int(value)
            elif key in ("expect", "reject", "file", "absent"):
                case[key].append(value)
            elif key == "wrap":
                case["wrap"] = shlex.split(value)
            else:
                sys.exit(f"{path}:{lineno}: unknown key '{key}'")
    if not cases:
        sys.exit(f"{path}: no 'run:' line")
    return cases


def check_file(name):
    if not os.path.isfile(name) or os.path.getsize(name) == 0:
        return f"file {name} was not written (or is empty)"
    with open(name, "rb") as f:
        head = f.read(8)
    ext = os.path.splitext(name)[1].lower()
    if ext == ".png" and head != b"\x89PNG\r\n\x1a\n":
        return f"{name} is not a PNG file"
    if ext == ".ppm" and not head.startswith(b"P3") and not head.startswith(b"P6"):
        return f"{name} is not a PPM file"
    if ext == ".pfm" and not head.startswith(b"PF"):
        return f"{name} is not a PFM file"
    return None


def main():
    program, spec = sys.argv[1], sys.argv[2]
    failures = 0
    for case in parse(spec):
        for name in case["file"] + case["absent"]:
            if os.path.exists(name):
                os.remove(name)
        cmd = case["wrap"] + [program] + case["args"]
        if case["wrap"] and shutil.which(case["wrap"][0]) is None:
            print(f"$ {shlex.join(cmd)}\nskipped: '{case['wrap'][0]}' is not installed\n")
            continue
        proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                              stdin=subprocess.DEVNULL, timeout=280)
        out = proc.stdout.decode("utf-8", "replace")
        problems = []
        if proc.returncode != case["exit"]:
            problems.append(f"exit code {proc.returncode}, expected {case['exit']}")
        problems += [f"output lacks /{rx}/" for rx in case["expect"] if not re.search(rx, out, re.M)]
        problems += [f"output has /{rx}/" for rx in case["reject"] if re.search(rx, out, re.M)]
        problems += [p for p in map(check_file, case["file"]) if p]
        problems += [f"{n} was left behind" for n in case["absent"] if os.path.exists(n)]
        print(f"$ {shlex.join(cmd)}\n{out}")
        if problems:
            failures += 1
            print(f"FAILED ({spec}:{case['line']}):\n  " + "\n  ".join(problems))
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
