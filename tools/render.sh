#!/usr/bin/env bash
# README command 1: set up, build, and render the default image to build/out/default.png.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/build.sh
mkdir -p build/out
./build/bin/normals --out build/out/default.png
echo "rendered: $(pwd)/build/out/default.png"
