#!/usr/bin/env python3
"""Every file a page or a comment names exists: a stale name (a header that was merged into another,
a test that was renamed) sends a student looking for nothing.

  python3 tools/file_names.py [--root DIR] [--self-test]

Read: the tracked book pages, READMEs and sources. A name is a path or a bare file name ending in
.hpp, .cpp, .cl, .py, .sh or .cmake. In C++ and OpenCL files only comments and #include "..." lines
count (elsewhere a member access can look like a file name), in Python and shell files the docstring and comments, and in pages the C++ blocks do not. A path must exist relative
to the root, the naming file's folder, include/ or include/zraka/; a bare name must be the name of some tracked file. Not checked: names in <...> (system
headers: the compiler checks them), names after $ or } (shell and CMake variables) or * (globs), build outputs
(CMakeFiles/, build/), placeholders written in capitals (test_X.cpp, FOLDER/NAME.hpp) and the few
names listed in EXAMPLES, which the text uses as examples of what a reader writes.
Prints each stale name with where it is; exit code 1 if any. CTest runs it as book.file_names."""
import argparse
import re
import subprocess
import sys
from pathlib import Path

NAME = re.compile(r'(?<![\w./$}<*-])((?:\.\./)*(?:[\w.-]+/)*[\w-]+\.(?:hpp|cpp|cl|py|sh|cmake))(?![\w/])')
TEXT = re.compile(r'\.(md|txt|hpp|cpp|cl|py|sh|cmake|yaml|xml)$|CMakeLists\.txt$')
CODE = ('.hpp', '.cpp', '.cl', '.h')
# Names the text gives as examples of a reader's own file, not as files of the project.
EXAMPLES = {
    'my_add.cl': 'book 3.3: the student\'s own kernel file',
    'kernels/x.cl': 'gpu/cl.hpp: the form of a kernel name',
    'no/such.cl': 'chapter 3.3 smoke test: a missing kernel on purpose',
    'kernels/no_such_kernel.cl': 'test_cl: a missing kernel on purpose',
}


def lines_to_read(path, text):
    if path.suffix == '.md':  # C++ blocks are code (their listings are checked by book_listings.py)
        out, code = [], False
        for line in text.splitlines():
            if line.startswith('```'):
                code = not code and line[3:].strip() in ('cpp', 'c++', 'c', 'opencl')
                continue
            out.append('' if code else line)
        return out
    if path.suffix == '.py':  # the docstring and comments; strings are data (self-tests make up trees)
        import ast
        import io
        import tokenize
        try:
            doc = ast.get_docstring(ast.parse(text)) or ''
            comments = [t.string for t in tokenize.generate_tokens(io.StringIO(text).readline)
                        if t.type == tokenize.COMMENT]
        except (SyntaxError, tokenize.TokenError):
            return text.splitlines()
        return doc.splitlines() + comments
    if path.suffix == '.sh':  # comments only; the commands' strings are data (self-tests make up trees)
        return [m.group(1) for m in re.finditer(r'(?:^|\s)(#[^\n]*)', text) if not m.group(1).startswith('#!')]
    if path.suffix not in CODE:
        return text.splitlines()
    out = []
    for line in text.splitlines():
        if re.match(r'\s*#\s*include\s*"', line):
            out.append(line)
        elif '//' in line:
            out.append(line[line.index('//'):])
        elif line.lstrip().startswith(('/*', '*')):
            out.append(line)
    return out


def stale_names(root, files):
    tracked = set(files)
    basenames = {Path(f).name for f in files}
    found = []
    for f in files:
        if not TEXT.search(f) or f.startswith('tests/fuzz-regressions/'):
            continue
        path = root / f
        try:
            text = path.read_text(encoding='utf-8')
        except (UnicodeDecodeError, OSError):
            continue
        for n, line in enumerate(lines_to_read(path, text), 1):
            for m in NAME.finditer(line):
                name = m.group(1)
                if name in EXAMPLES or 'CMakeFiles/' in name or name.startswith('build/'):
                    continue
                if re.search(r'[A-Z]', Path(name).stem) or any(re.fullmatch(r'[A-Z_]+', p) for p in name.split('/')[:-1]):
                    continue
                if '/' in name:  # from the root, the naming file's folder, or the include path
                    ok = any(here.is_relative_to(root) and here.relative_to(root).as_posix() in tracked
                             for here in ((base / name).resolve() for base in
                                          (root, path.parent, root / 'include', root / 'include' / 'zraka')))
                else:
                    ok = name in basenames
                if not ok:
                    found.append((f, name))  # (reported once per line)
    return found


def self_test():
    import tempfile
    with tempfile.TemporaryDirectory() as t:
        r = Path(t)
        files = {'include/a.hpp': '// see b.hpp and gone.hpp\nint x = vp.sh;\n#include <sys/none.hpp>\n',
                 'include/b.hpp': '#include "../tools/c.py"\n',
                 'tools/c.py': '# names test_X.cpp, $d/main.cpp and tools/missing.sh\n',
                 'book/p.md': 'See `include/a.hpp`, `include/old.hpp` and `my_add.cl`.\n'}
        for f, text in files.items():
            (r / f).parent.mkdir(parents=True, exist_ok=True)
            (r / f).write_text(text)
        got = sorted(stale_names(r, sorted(files)))
        want = [('book/p.md', 'include/old.hpp'), ('include/a.hpp', 'gone.hpp'), ('tools/c.py', 'tools/missing.sh')]
        if got != want:
            print('self-test failed: got', got, 'want', want)
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
    root = args.root.resolve()
    files = subprocess.run(['git', 'ls-files'], cwd=root, capture_output=True, text=True, check=True).stdout.split()
    found = stale_names(root, files)
    for f, name in found:
        print(f'{f}: names {name}, which does not exist')
    print(f'file names: {len(files)} files read; {len(found)} stale name(s)')
    return 1 if found else 0


if __name__ == '__main__':
    sys.exit(main())
