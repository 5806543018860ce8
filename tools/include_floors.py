#!/usr/bin/env python3
"""The library's floors (README.md, "The library's floors"): a header of include/zraka/ includes only
headers of its own folder or of a folder on a lower floor, no headers include each other in a
cycle, and every folder's README.md names each of its headers. The floors are read from the README's table, the one place they are written.

  python3 tools/include_floors.py [--root DIR] [--self-test]

Prints each violation; exit code 1 if any. CTest runs it as library.floors."""
import argparse
import re
import sys
from pathlib import Path

ROW = re.compile(r'^\|\s*(\d+)\s*\|\s*`([a-z_]+)/`\s*\|', re.M)
INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]zraka/([A-Za-z0-9_/]+\.hpp)[>"]', re.M)


def check(root):
    floors = {m.group(2): int(m.group(1)) for m in ROW.finditer((root / 'README.md').read_text())}
    inc = root / 'include' / 'zraka'
    problems = []
    if not floors:
        return ['README.md: no table of floors ("| 1 | `core/` | ...")']
    graph = {}
    for h in sorted(inc.rglob('*.hpp')):
        rel = h.relative_to(inc).as_posix()
        folder = rel.split('/')[0] if '/' in rel else ''
        if folder not in floors:
            problems.append(f'include/zraka/{rel}: folder "{folder or "."}" is not in the README\'s table of floors')
            continue
        graph[rel] = []
        for m in INCLUDE.finditer(h.read_text()):
            dep = m.group(1)
            # A header that includes its own definitions file (app/cli.hpp and app/cli_impl.hpp,
            # which includes it back) is one header in two files, not a cycle.
            if dep != rel[:-len('.hpp')] + '_impl.hpp':
                graph[rel].append(dep)
            if not (inc / dep).is_file():
                problems.append(f'include/zraka/{rel} includes <zraka/{dep}>, which does not exist')
                continue
            dfolder = dep.split('/')[0] if '/' in dep else ''
            if dfolder != folder and floors.get(dfolder, 99) >= floors[folder]:
                problems.append(f'include/zraka/{rel} (floor {floors[folder]}, {folder}/) includes <zraka/{dep}> '
                                f'(floor {floors.get(dfolder, "?")}, {dfolder}/), which is not below it')
    for d in sorted(p for p in inc.iterdir() if p.is_dir()):
        readme = d / 'README.md'
        text = readme.read_text() if readme.is_file() else ''
        for h in sorted(d.glob('*.hpp')):
            if f'`{h.name}`' not in text:
                problems.append(f'include/zraka/{d.name}/README.md does not name {h.name}')
    # Cycles among headers (also inside one folder), by depth-first search.
    state, stack = {}, []

    def visit(h):
        state[h] = 1
        stack.append(h)
        for d in graph.get(h, []):
            if state.get(d) == 1:
                problems.append('include cycle: ' + ' -> '.join(stack[stack.index(d):] + [d]))
            elif d in graph and not state.get(d):
                visit(d)
        stack.pop()
        state[h] = 2

    for h in graph:
        if not state.get(h):
            visit(h)
    return problems


def self_test():
    import tempfile
    with tempfile.TemporaryDirectory() as t:
        r = Path(t)
        (r / 'README.md').write_text('| 1 | `core/` | x |\n| 2 | `scene/` | y |\n')
        (r / 'include' / 'zraka' / 'core').mkdir(parents=True)
        (r / 'include' / 'zraka' / 'core' / 'README.md').write_text('| `a.hpp` |\n')
        files = {'core/a.hpp': '#include <zraka/scene/b.hpp>\n', 'scene/b.hpp': '#include <zraka/scene/c.hpp>\n',
                 'scene/c.hpp': '#include <zraka/scene/b.hpp>\n#include <zraka/core/none.hpp>\n',
                 'other/d.hpp': ''}
        for f, text in files.items():
            (r / 'include' / 'zraka' / f).parent.mkdir(parents=True, exist_ok=True)
            (r / 'include' / 'zraka' / f).write_text(text)
        got = check(r)
        want = ['include/zraka/core/a.hpp (floor 1, core/) includes <zraka/scene/b.hpp>',
                'include cycle: scene/b.hpp -> scene/c.hpp -> scene/b.hpp',
                'include/zraka/scene/c.hpp includes <zraka/core/none.hpp>, which does not exist',
                'folder "other" is not in the README', 'scene/README.md does not name b.hpp',
                'scene/README.md does not name c.hpp', 'other/README.md does not name d.hpp']
        missing = [w for w in want if not any(w in g for g in got)]
        if missing or len(got) != len(want):
            print('self-test failed; missing:', missing, 'got:', got)
            return False
    print('self-test passed')
    return True


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument('--root', default=Path(__file__).resolve().parent.parent, type=Path)
    ap.add_argument('--self-test', action='store_true')
    args = ap.parse_args()
    if args.self_test and not self_test():
        return 1
    problems = check(args.root)
    for p in problems:
        print(p)
    n = len(list((args.root / 'include' / 'zraka').rglob('*.hpp')))
    print(f'floors: {n} headers checked; {len(problems)} problem(s)')
    return 1 if problems else 0


if __name__ == '__main__':
    sys.exit(main())
