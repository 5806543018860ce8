#!/usr/bin/env python3
"""The book's structure, checked (CTest: book.structure).

Errors (exit code 1):
  - a chapter folder chapters/<N.M>-<slug>/ with no book page: neither book/<N.M>-<slug>.md nor a
    page that names chapters/<N.M>-<slug>/ (0.0-intro's page is book/intro.md);
  - a page that names no chapter program, or has no one-line command to run it: a line of a fenced
    code block that starts with build/bin/<slug> (after optional VAR=value words and an xvfb-run
    prefix), or a line "Run: `build/bin/<slug> ...`";
  - a page with no "Exercises" section (a heading that ends in "Exercises");
  - a figure or image a page (or an assignment's README) refers to that does not exist;
  - an errata entry that names no test that exists: a test file (tests/..., book/assignments/...,
    chapters/<N.M>-<slug>/smoke.txt), a CTest name (`unit.test_x`, `chapter.<N.M>-<slug>`,
    `assignment.NN-name`, `book.listings`), or a quoted test-case name found in a TEST_CASE of
    tests/ or book/assignments/; and any test file or CTest name an entry gives that does not exist;
    Entries that correct only wording or history say "Guard: text only" and are exempt.
  - a link in book/README.md that does not resolve, and a page missing from book/README.md.
Warnings (printed, not failing): a figure whose caption (the paragraph after it) shows no command.
Usage: python3 tools/book_check.py [--root DIR]
"""
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
if len(sys.argv) == 3 and sys.argv[1] == "--root":
    ROOT = pathlib.Path(sys.argv[2]).resolve()
BOOK = ROOT / "book"
NOT_CHAPTERS = {"README.md", "errata.md"}
FOLDER = re.compile(r"^(\d+)\.(\d+)-([a-z0-9-]+)$")
FENCE = re.compile(r"^```[^\n]*\n(.*?)^```", re.S | re.M)
COMMAND = re.compile(r"^\s*(\$\s*)?([A-Za-z_][A-Za-z0-9_]*=\S*\s+)*(xvfb-run\s.*?)?(\./)?build/bin/([a-z0-9-]+)")
RUN_LINE = re.compile(r"^Run:\s*`(?:[^`]*\s)?(?:\./)?build/bin/([a-z0-9-]+)", re.M)
IMAGE = re.compile(r"!\[[^\]]*\]\(([^)\s]+)[^)]*\)|<img[^>]*\ssrc=\"([^\"]+)\"", re.S)
LINK = re.compile(r"\[[^\]]*\]\(([^)\s]+)\)")
TEST_NAME = re.compile(r"TEST_CASE(?:_TEMPLATE)?\s*\(\s*\"((?:[^\"\\]|\\.)*)\"")
TEST_FILE = re.compile(r"((?:tests|book/assignments|chapters)/[A-Za-z0-9_./-]+\.(?:cpp|txt|sh))")
CTEST = re.compile(r"`((?:unit|chapter|assignment|book|install)\.[A-Za-z0-9_.-]+)`")
QUOTED = re.compile(r"\"([^\"\n]{4,})\"|“([^”]{4,})”")

errors, warnings = [], []


def natural_key(folder):
    m = FOLDER.match(folder)
    return (int(m.group(1)), int(m.group(2)), m.group(3)) if m else (1 << 30, 0, folder)


def chapter_folders():
    found = []
    for d in (ROOT / "chapters").iterdir():
        if d.is_dir() and (d / "main.cpp").exists() and FOLDER.match(d.name):
            found.append(d.name)
    return sorted(found, key=natural_key)


def pages():
    return sorted(p for p in BOOK.glob("*.md") if p.name not in NOT_CHAPTERS)


def page_of(folder, texts):
    """The page that teaches a chapter folder, or None."""
    own = "intro.md" if folder == "0.0-intro" else folder + ".md"
    if own in texts:
        return own
    for name, text in texts.items():
        if f"chapters/{folder}/" in text or f"chapters/{folder}`" in text:
            return name
    return None


def check_chapters_and_pages():
    texts = {p.name: p.read_text(encoding="utf-8") for p in pages()}
    programs = {name: [] for name in texts}  # page -> [(folder, slug)]
    for folder in chapter_folders():
        page = page_of(folder, texts)
        if page is None:
            errors.append(f"chapter {folder}: no book page (book/{folder}.md is missing and no page "
                          f"names chapters/{folder}/)")
        else:
            programs[page].append((folder, FOLDER.match(folder).group(3)))
    for name, text in texts.items():
        where = f"book/{name}"
        slugs = {slug for _, slug in programs[name]}
        if not slugs:
            errors.append(f"{where}: names no chapter program (no folder chapters/{name[:-3]}/ and "
                          f"no mention of one)")
        else:
            named = any(f"build/bin/{s}" in text or f"chapters/{f}" in text
                        for f, s in programs[name])
            if not named:
                errors.append(f"{where}: does not name its program (build/bin/{sorted(slugs)[0]})")
            commands = {m.group(5) for block in FENCE.findall(text) for line in block.splitlines()
                        if (m := COMMAND.match(line))}
            commands |= set(RUN_LINE.findall(text))
            if not commands & slugs:
                errors.append(f"{where}: no one-line command running build/bin/"
                              f"{'|'.join(sorted(slugs))} (in a ```sh block, or a line "
                              f"'Run: `build/bin/...`')")
        if not re.search(r"^#{1,6}\s.*\bExercises\s*$", text, re.M):
            errors.append(f"{where}: no 'Exercises' section")
        check_images(BOOK / name, text, slugs)


def check_images(page, text, slugs):
    rel = page.relative_to(ROOT)
    for m in IMAGE.finditer(text):
        target = m.group(1) or m.group(2)
        if re.match(r"^[a-z]+:", target):
            continue
        if not (page.parent / target.split("#")[0]).exists():
            errors.append(f"{rel}: figure {target} does not exist")
            continue
        if slugs is None:
            continue
        # The caption: the rest of the image's paragraph and the next paragraph.
        after = text[m.end():].lstrip("\n")
        caption = "\n\n".join(after.split("\n\n")[:2]) + m.group(0)
        shows = any(re.search(rf"`[^`]*\b{re.escape(s)}\b[^`]*`", caption) for s in slugs) or \
            re.search(r"make_figures\.sh|plot_convergence\.py|build/bin/", caption)
        if not shows:
            warnings.append(f"{rel}: the caption of {target} shows no command")


def test_names():
    names = set()
    for base in (ROOT / "tests", ROOT / "book" / "assignments"):
        for src in base.rglob("*.cpp"):
            names |= {n.replace('\\"', '"') for n in TEST_NAME.findall(src.read_text(encoding="utf-8", errors="replace"))}
    return names


def ctest_exists(name):
    """A CTest name an errata entry may give: unit.test_x, chapter.<N.M>-<slug>, assignment.NN-x..."""
    kind, _, rest = name.partition(".")
    if kind == "unit":
        return (ROOT / "tests" / f"{rest}.cpp").exists()
    if kind == "chapter":
        return (ROOT / "chapters" / rest / "smoke.txt").exists()
    if kind == "assignment":
        return (ROOT / "book" / "assignments" / rest.split(".")[0]).is_dir()
    cmake = "".join(p.read_text(encoding="utf-8") for p in (ROOT / "tests").rglob("CMakeLists.txt"))
    return f"NAME {name} " in cmake or f"NAME {name}\n" in cmake


def check_errata():
    path = BOOK / "errata.md"
    if not path.exists():
        errors.append("book/errata.md does not exist")
        return
    names = test_names()
    entries, current = [], None
    for line in path.read_text(encoding="utf-8").splitlines():
        if line.startswith("- "):
            current = [line]
            entries.append(current)
        elif line.startswith("#"):
            current = None
        elif current is not None and line.strip():
            current.append(line)
    for lines in entries:
        entry = " ".join(l.strip() for l in lines)
        label = re.sub(r"[*]", "", entry[2:70]).strip()
        if "Guard: text only" in entry:  # corrects wording or history: there is no code to test
            continue
        files = TEST_FILE.findall(entry)
        good = False
        for f in files:
            if (ROOT / f).exists():
                good = True
            else:
                errors.append(f"book/errata.md: entry '{label}…' names {f}, which does not exist")
        for t in CTEST.findall(entry):
            if ctest_exists(t):
                good = True
            else:
                errors.append(f"book/errata.md: entry '{label}…' names the test {t}, which does not exist")
        quoted = [a or b for a, b in QUOTED.findall(entry)]
        if any(q in n for q in quoted for n in names):
            good = True
        if not good:
            errors.append(f"book/errata.md: entry '{label}…' names no existing test (a test file in "
                          f"tests/ or book/assignments/, or a quoted TEST_CASE name)")


def check_readme():
    readme = BOOK / "README.md"
    text = readme.read_text(encoding="utf-8")
    linked = set()
    for target in LINK.findall(text):
        if re.match(r"^[a-z]+:", target) or target.startswith("#"):
            continue
        path = target.split("#")[0]
        if not (BOOK / path).exists():
            errors.append(f"book/README.md: link {target} does not resolve")
        linked.add(path)
    for p in pages():
        if p.name not in linked:
            errors.append(f"book/README.md: no link to {p.name}")
    for p in sorted((BOOK / "assignments").glob("*/README.md")):
        check_images(p, p.read_text(encoding="utf-8"), None)


def main():
    check_chapters_and_pages()
    check_errata()
    check_readme()
    for w in warnings:
        print(f"warning: {w}")
    for e in errors:
        print(f"error: {e}")
    print(f"book_check: {len(chapter_folders())} chapter folders, {len(pages())} pages, "
          f"{len(errors)} errors, {len(warnings)} warnings")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
