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
# A course's binary (tests/consumer/course.cpp): its own torus and material by name, rendered by
# zraka::pathtrace_main from the installed package, with pathtrace's options.
out=$(cd "$tmp" && env -u ZRAKA_ROOT "$tmp/build/course" --scene "$src/tests/course/torus.yaml" --width 24 \
      --height 24 --spp 4 --integrator nee --out torus.pfm)
echo "$out"
case "$out" in *"summary: $src/tests/course/torus.yaml nee 24x24, 4 spp"*"0 NaN/inf samples"*) ;;
  *) echo "course: wrong output"; exit 1;; esac
test -s "$tmp/torus.pfm" || { echo "course: no torus.pfm"; exit 1; }
(cd "$tmp" && "$tmp/build/course" --scene "$src/tests/course/torus.yaml" --integrator bidirectional \
   --out bad.png 2>/dev/null) && { echo "course: a bad --integrator did not fail"; exit 1; }
echo "install check passed"
