#!/usr/bin/env bash
# README command 1: set up, build the Whitted ray tracer, and render the default scene
# (scenes/default.yaml) to build/out/default.png.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/setup.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build --target whitted -j "$(nproc)"
mkdir -p build/out
./build/bin/whitted --scene default --out build/out/default.png
echo "rendered: $(pwd)/build/out/default.png"
