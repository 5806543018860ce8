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
echo "install check passed"
