#!/usr/bin/env bash
# README command 2: set up, build (warnings are errors), and run every test.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/build.sh -DZRAKA_WERROR=ON
cd build && ctest --output-on-failure -j "$(nproc)"
