#!/usr/bin/env bash
# README command 2: set up, build (warnings are errors), and run every test; then the same tests
# built with AddressSanitizer + UndefinedBehaviorSanitizer (tools/sanitize.sh, build-sanitize/)
# and a short fuzz budget (tools/fuzz.sh: 10 s for each of the 6 targets, 2 at a time).
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/build.sh -DZRAKA_WERROR=ON
(cd build && ctest --output-on-failure -j "$(nproc)")
bash tools/sanitize.sh
bash tools/fuzz.sh --seconds 10
