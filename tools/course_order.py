#!/usr/bin/env python3
"""Course order: no chapter includes a zraka header, or calls a function, that only a later page
teaches (book/course_order.txt explains the table). Prints each violation; exit code 1 if any.

  python3 tools/course_order.py [--root DIR] [--list] [--self-test]

--self-test first checks the checker on a small made-up tree (each kind of violation found, a
call in a comment or a string ignored).
--list prints the page that teaches every header the chapters include (derived or from the table).
Only the chapter folders' own sources (chapters/<N.M>-<slug>/*.cpp, *.hpp) are read; what the
library headers include among themselves is the library's business, not the course's."""
import argparse
import re
import sys
from pathlib import Path

INCLUDE = re.compile(r'^\s*#\s*include\s*<zraka/([A-Za-z0-9_/]+\.hpp)>', re.M)
COMMENT = re.compile(r'//[^\n]*|/\*.*?\*/', re.S)
STRING = re.compile(r'"(?:\\.|[^"\\\n])*"')


def page_key(page):
    return tuple(int(x) for x in page.split('.'))


def self_test():
    import subprocess
    import tempfile
    with tempfile.TemporaryDirectory() as t:
        r = Path(t)
        for h in ('io/scene_file.hpp', 'core/vec.hpp'):
            (r / 'include' / 'zraka' / h).parent.mkdir(parents=True, exist_ok=True)
            (r / 'include' / 'zraka' / h).write_text('')
        (r / 'book').mkdir()
        (r / 'book' / 'course_order.txt').write_text('header io/scene_file.hpp 4.1\nfunction parse_scene 4.1\n')
        def chapter(name, text):
            (r / 'chapters' / name).mkdir(parents=True)
            (r / 'chapters' / name / 'main.cpp').write_text(text)
        chapter('1.0-a', '#include <zraka/core/vec.hpp>\n#include <zraka/io/scene_file.hpp>\n')
        chapter('2.0-b', 'int f() { return parse_scene (1); }\n')
        chapter('3.0-c', '// parse_scene(x) is taught later\nconst char* s = "parse_scene(";\n')
        chapter('4.1-d', '#include <zraka/io/scene_file.hpp>\nint g() { return parse_scene(2); }\n')
        out = subprocess.run([sys.executable, __file__, '--root', str(r)], capture_output=True, text=True)
        want = ['chapters/1.0-a includes <zraka/io/scene_file.hpp>, which page 4.1 teaches',
                'chapters/2.0-b calls parse_scene(), which page 4.1 teaches', '2 problem(s)']
        bad = [w for w in want if w not in out.stdout] + (['3.0-c or 4.1-d flagged'] if '3.0-c' in out.stdout or '4.1-d' in out.stdout else [])
        if out.returncode != 1 or bad:
            print('self-test failed:', bad, '\n' + out.stdout)
            return False
    print('self-test passed')
    return True


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('--root', default=Path(__file__).resolve().parent.parent, type=Path)
    ap.add_argument('--list', action='store_true')
    ap.add_argument('--self-test', action='store_true')
    args = ap.parse_args()
    if args.self_test and not self_test():
        return 1
    root = args.root
    headers, functions, problems = {}, {}, []
    for n, line in enumerate((root / 'book' / 'course_order.txt').read_text().splitlines(), 1):
        line = line.split('#', 1)[0].split()
        if not line:
            continue
        if len(line) != 3 or line[0] not in ('header', 'function') or not re.fullmatch(r'\d+\.\d+', line[2]):
            problems.append(f'book/course_order.txt:{n}: expected "header FOLDER/NAME.hpp PAGE" or "function NAME PAGE"')
            continue
        (headers if line[0] == 'header' else functions)[line[1]] = line[2]
    for h in headers:
        if not (root / 'include' / 'zraka' / h).is_file():
            problems.append(f'book/course_order.txt: header {h} is not in include/zraka/')

    chapters = []
    for d in (root / 'chapters').iterdir():
        m = re.fullmatch(r'(\d+\.\d+)-[a-z0-9-]+', d.name)
        if m and (d / 'main.cpp').is_file():
            text = '\n'.join(p.read_text() for p in sorted(d.iterdir()) if p.suffix in ('.cpp', '.hpp'))
            chapters.append((page_key(m.group(1)), m.group(1), d.name, text))
    chapters.sort()

    taught = dict(headers)  # header -> page; the first chapter that includes it, unless listed
    for _, page, _, text in chapters:
        for h in INCLUDE.findall(text):
            taught.setdefault(h, page)
    if args.list:
        for h, p in sorted(taught.items(), key=lambda kv: (page_key(kv[1]), kv[0])):
            print(f'{p:5} {h}' + ('  (table)' if h in headers else ''))

    for key, page, name, text in chapters:
        for h in sorted(set(INCLUDE.findall(text))):
            if page_key(taught[h]) > key:
                problems.append(f'chapters/{name} includes <zraka/{h}>, which page {taught[h]} teaches')
        code = STRING.sub('""', COMMENT.sub('', text))
        for f, fpage in sorted(functions.items()):
            if page_key(fpage) > key and re.search(r'(?<![A-Za-z0-9_])' + re.escape(f) + r'\s*\(', code):
                problems.append(f'chapters/{name} calls {f}(), which page {fpage} teaches')
    for p in problems:
        print('error:', p)
    print(f'course order: {len(chapters)} chapters, {len(taught)} headers, {len(functions)} functions checked; '
          f'{len(problems)} problem(s)')
    return 1 if problems else 0


if __name__ == '__main__':
    sys.exit(main())
