#!/usr/bin/env bash
# Installs zraka from the build folder $1 into a temporary prefix, then configures, builds and
# runs tests/consumer against it with find_package(zraka).
set -euo pipefail
build=$(cd "$1" && pwd)
src=$(cd "$(dirname "$0")/.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cmake --install "$build" --prefix "$tmp/prefix" >/dev/null
test -f "$tmp/prefix/share/zraka/scenes/teapot.bpt" || { echo "scenes/ not installed"; exit 1; }
cmake -S "$src/tests/consumer" -B "$tmp/build" -DCMAKE_PREFIX_PATH="$tmp/prefix" >/dev/null
cmake --build "$tmp/build" >/dev/null
out=$(env -u ZRAKA_ROOT "$tmp/build/consumer")
echo "$out"
case "$out" in *"resource root $tmp/prefix/share/zraka"*) ;; *) echo "wrong resource root"; exit 1;; esac
out=$(cd "$tmp" && env -u ZRAKA_ROOT "$tmp/build/consumer_compiled" --out c.png --width 5)
echo "$out"
case "$out" in *"wrote c.png; resource root $tmp/prefix/share/zraka"*) ;; *) echo "zraka::compiled: wrong output"; exit 1;; esac
test "$(head -c 8 "$tmp/c.png" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" || { echo "c.png is not a PNG"; exit 1; }
(cd "$tmp" && "$tmp/build/consumer_compiled" --width x 2>/dev/null) && { echo "a bad value did not fail"; exit 1; }
echo "install check passed"
