#!/usr/bin/env bash
# install.external: installs zraka from the build folder $1 into a temporary prefix, then
# configures, builds and runs book/assignments/external (an instructor's own repository: a user
# shape, a custom material, both registered for scene files and rendered from scene.yaml, and the
# disk from scene.xml, a Mitsuba 3 file) against
# it with find_package(zraka), and checks that it wrote its PNG. Modelled on tests/check_install.sh.
set -euo pipefail
build=$(cd "$1" && pwd)
here=$(cd "$(dirname "$0")" && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cmake --install "$build" --prefix "$tmp/prefix" >/dev/null
test -f "$tmp/prefix/include/zraka/app/testing.hpp" || { echo "zraka/app/testing.hpp not installed"; exit 1; }
cmake -S "$here" -B "$tmp/build" -DCMAKE_PREFIX_PATH="$tmp/prefix" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$tmp/build" >/dev/null
"$tmp/build/disk" "$tmp/disk.png"
test "$(head -c 8 "$tmp/disk.png" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" \
  || { echo "disk.png is not a PNG"; exit 1; }
# The Mitsuba 3 file of the disk: read through the registered disk (mitsuba_xml.hpp).
"$tmp/build/disk" "$tmp/disk-xml.png" "$here/scene.xml"
test "$(head -c 8 "$tmp/disk-xml.png" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" \
  || { echo "disk-xml.png is not a PNG"; exit 1; }
if [ -n "${ZRAKA_KEEP_EXTERNAL_PNG:-}" ]; then cp "$tmp/disk.png" "$ZRAKA_KEEP_EXTERNAL_PNG"; fi
echo "external assignment check passed"
