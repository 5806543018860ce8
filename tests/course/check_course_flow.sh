#!/usr/bin/env bash
# tools/course_flow.sh on a made-up course of two chapters: 1.1-good (its program and its page's
# command pass) and 1.2-bad (its program passes, its page calls a command that is not installed).
# The table must show 1.2's page as failed, name the missing command, and the exit code be 1.
set -euo pipefail
src=$(cd "$(dirname "$0")/../.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/tools" "$tmp/book" "$tmp/chapters/1.1-good" "$tmp/chapters/1.2-bad"
cp "$src/tools/course_flow.sh" "$tmp/tools/"
for c in 1.1-good 1.2-bad; do echo 'int main() { return 0; }' > "$tmp/chapters/$c/main.cpp"; done
cat > "$tmp/CMakeLists.txt" <<'CM'
cmake_minimum_required(VERSION 3.16)
project(fake CXX)
set(CMAKE_RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/bin)
add_executable(good chapters/1.1-good/main.cpp)
add_executable(bad chapters/1.2-bad/main.cpp)
CM
printf '# 1.1\n\n```sh\nbuild/bin/good --x\n```\n' > "$tmp/book/1.1-good.md"
printf '# 1.2\n\n```sh\nno-such-tool-zraka -e x build/bin/bad\n```\n' > "$tmp/book/1.2-bad.md"
cmake -S "$tmp" -B "$tmp/build" >/dev/null
set +e
out=$(bash "$tmp/tools/course_flow.sh" "$tmp/build" 2>&1)
rc=$?
set -e
fail() { echo "check_course_flow: $1"; echo "$out"; exit 1; }
[[ $rc -eq 1 ]] || fail "exit code $rc, expected 1"
grep -Eq '^1\.1 +good .* 0 1 ok ' <<<"$out" || fail "1.1's row does not show its page passing"
grep -Eq '^1\.2 +bad .* 0 1/1 FAIL ' <<<"$out" || fail "1.2's row does not show its page failing"
grep -q 'no-such-tool-zraka is not installed' <<<"$out" || fail "the missing command is not named"
echo "$out" | sed -n "/^chapter/,\$p"
echo "course_flow check passed"
