#!/usr/bin/env python3
"""Re-runs every program output pasted in the book and compares it with what the program prints
now (CTest: book.outputs).

A pasted output is a fenced block whose lines start with `$ build/bin/<program> ...` (the command;
each `$` line starts a new one) followed by what it printed, or a fenced block right after a line
`<!-- output of: build/bin/<program> ... -->`. The commands run from the top of the checkout, as a
reader runs them (a bare --out name lands in build/out/, which git ignores).

The pasted lines must appear in the program's output in the same order (the page may leave lines
out). A line that reports a timing (a duration, a rate per second, a thread count), and the rows
of a table whose header names a timing column, are compared with their numbers masked; every
other line must match exactly, except that "..." in the page stands for any text.

    python3 tools/book_outputs.py BIN_DIR [PAGE.md ...]      (default: every book/*.md)
Exit code 1 when a pasted output is stale; the report names page, line and the expected text.
"""
import os
import re
import shlex
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FENCE = re.compile(r"^(```|~~~)")
OUTPUT_OF = re.compile(r"^<!--\s*output of:\s*(.+?)\s*-->\s*$")
# A duration or a rate: "1.29 s", "0.008 s", "14.49 ms", "ns/eval", "M rays/s", "on 2 threads".
TIMING = re.compile(r"\d\s*(s|ms|us|µs|ns|min)\b|/s\b|ns/|\bseconds?\b|\bthreads?\b|\bspeed-?up\b|x faster")
NUMBER = re.compile(r"[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?")


def blocks(path):
    """(line number, command, [(line number, expected line)]) for each pasted output."""
    with open(path, encoding="utf-8") as f:
        lines = f.read().split("\n")
    found, i, pending = [], 0, None
    while i < len(lines):
        m = OUTPUT_OF.match(lines[i].strip())
        if m:
            pending = (i + 1, m.group(1))
            i += 1
            continue
        if FENCE.match(lines[i]):
            j = i + 1
            while j < len(lines) and not FENCE.match(lines[j]):
                j += 1
            body = [(k + 1, lines[k]) for k in range(i + 1, j)]
            if pending and pending[0] >= i - 1:
                found.append((pending[0], pending[1], body))
            else:
                cur = None
                for no, text in body:
                    if text.startswith("$ "):
                        cur = (no, text[2:], [])
                        found.append(cur)
                    elif cur is not None:
                        cur[2].append((no, text))
            pending = None
            i = j + 1
            continue
        if lines[i].strip():
            pending = None if not OUTPUT_OF.match(lines[i].strip()) else pending
        i += 1
    return [b for b in found if "build/bin/" in b[1]]


def masked(text):
    """Numbers masked, and runs of spaces made one: a timing's width changes with its value."""
    return re.sub(r"\s+", " ", NUMBER.sub("#", text))


def pattern(expected, timing):
    text = masked(expected) if timing else expected
    parts = [re.escape(p) for p in text.strip().split("...")]
    return re.compile(r"\s*" + ".*".join(parts) + r"\s*$")


def check(page, bin_dir):
    failures = 0
    for no, command, expected in blocks(page):
        command = command.split(" #")[0].strip()  # a trailing comment is the page's
        args = shlex.split(command)
        wrap = []
        while args and "build/bin/" not in args[0]:
            wrap.append(args.pop(0))
        if not args:
            continue
        exe = os.path.join(bin_dir, os.path.basename(args[0]))
        where = f"{os.path.relpath(page, ROOT)}:{no}"
        if not os.path.exists(exe):
            print(f"{where}: skipped: {args[0]} is not built")
            continue
        if wrap and not shutil_which(wrap[0]):
            print(f"{where}: skipped: {wrap[0]} is not installed")
            continue
        try:
            run = subprocess.run(wrap + [exe] + args[1:], cwd=ROOT, capture_output=True, text=True, timeout=600,
                                 env=dict(os.environ, ZRAKA_ROOT=ROOT))
        except subprocess.TimeoutExpired:
            print(f"{where}: FAILED: `{command}` ran longer than 600 s")
            failures += 1
            continue
        actual = (run.stdout + run.stderr).split("\n")
        at, table_indent = 0, None
        for line_no, text in expected:
            if not text.strip():
                continue
            indent = len(text) - len(text.lstrip())
            if table_indent is not None and indent < table_indent:
                table_indent = None
            timing = table_indent is not None or bool(TIMING.search(text))
            if TIMING.search(text) and not NUMBER.search(TIMING.sub("", text)):
                table_indent = indent  # a header naming a timing column: its rows are timings
            pat = pattern(text, timing)
            k = at
            while k < len(actual) and not pat.match(masked(actual[k]) if timing else actual[k]):
                k += 1
            if k == len(actual):
                print(f"{os.path.relpath(page, ROOT)}:{line_no}: FAILED: `{command}` no longer prints\n    {text}")
                failures += 1
                break
            at = k + 1
    return failures


def shutil_which(name):
    import shutil
    return shutil.which(name)


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    bin_dir = os.path.abspath(sys.argv[1])
    pages = sys.argv[2:] or sorted(os.path.join(ROOT, "book", p) for p in os.listdir(os.path.join(ROOT, "book"))
                                   if p.endswith(".md"))
    failures, count = 0, 0
    for page in pages:
        count += len(blocks(page))
        failures += check(page, bin_dir)
    print(f"book_outputs: {count} pasted outputs in {len(pages)} pages, {failures} stale")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
