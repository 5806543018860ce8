#!/usr/bin/env python3
"""Book listings come from the real sources.

In a source file a listing is a tagged region:
    // [listing sphere-intersect]
    ...code...
    // [end]
In a book page a listing is a fenced code block preceded by a marker naming file and tag:
    <!-- listing: include/zraka/geometry/sphere.hpp sphere-intersect -->
    ```cpp
    ...code...
    ```
`--check` fails when a block differs from its region (the drift test, run by CTest);
`--write` rewrites the blocks from the sources. Regions are dedented; tag lines are not copied.
"""
import pathlib
import re
import sys
import textwrap

ROOT = pathlib.Path(__file__).resolve().parent.parent
MARKER = re.compile(r"<!-- listing: (\S+) (\S+) -->\n```(\w*)\n(.*?)```", re.S)
BEGIN = re.compile(r"^\s*(//|#)\s*\[listing (\S+)\]\s*$")
END = re.compile(r"^\s*(//|#)\s*\[end\]\s*$")


def region(path, tag):
    lines = (ROOT / path).read_text(encoding="utf-8").splitlines()
    out, inside, found = [], False, False
    for line in lines:
        m = BEGIN.match(line)
        if m and m.group(2) == tag:
            inside, found = True, True
            continue
        if inside and END.match(line):
            inside = False
            break
        if inside and not BEGIN.match(line):
            out.append(line)
    if not found:
        raise SystemExit(f"{path}: no region '[listing {tag}]'")
    if inside:
        raise SystemExit(f"{path}: region '{tag}' has no '[end]'")
    return textwrap.dedent("\n".join(out)).strip("\n") + "\n"


def main():
    mode = sys.argv[1] if len(sys.argv) > 1 else "--check"
    stale, count = [], 0
    for page in sorted((ROOT / "book").rglob("*.md")):
        text = page.read_text(encoding="utf-8")

        def replace(m):
            nonlocal count
            count += 1
            want = region(m.group(1), m.group(2))
            if m.group(4) != want:
                stale.append(f"{page.relative_to(ROOT)}: listing {m.group(1)} {m.group(2)}")
            return f"<!-- listing: {m.group(1)} {m.group(2)} -->\n```{m.group(3)}\n{want}```"

        new = MARKER.sub(replace, text)
        if mode == "--write" and new != text:
            page.write_text(new, encoding="utf-8")
    if mode == "--check" and stale:
        print("These book listings no longer match the code "
              "(run: python3 tools/book_listings.py --write):")
        print("\n".join("  " + s for s in stale))
        sys.exit(1)
    print(f"{count} listings checked" if mode == "--check" else f"{count} listings written")


if __name__ == "__main__":
    main()
