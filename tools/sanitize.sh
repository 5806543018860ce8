#!/usr/bin/env bash
# The test suite built with AddressSanitizer and UndefinedBehaviorSanitizer (-DZRAKA_SANITIZE=ON)
# in build-sanitize/: unit tests, chapter smoke tests, assignments and the replay
# of fuzz inputs. Any sanitizer report fails its test (UB stops the program: -fno-sanitize-recover).
# -O1 keeps the build and the runs short; without NDEBUG, so assert() checks too.
# Usage: bash tools/sanitize.sh [ctest arguments, e.g. -R scene]      (tools/test.sh runs it)
# Not run here: the book's text checks and the install tests (labels book, install), which test
# no compiled code of ours, the headers check (label headers: the compiler front end only), the address-space test (label hostile, see below), and the course flow (label course), which re-runs the chapters at their
# defaults and the pages' long commands: under the sanitizers that takes many minutes, and the
# chapter smoke tests, which do run here, exercise the same programs. Leaks inside the OpenCL driver are suppressed by tools/lsan.supp.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE=-O1 -DZRAKA_WERROR=ON \
      -DZRAKA_SANITIZE=ON >/dev/null
cmake --build build-sanitize -j "$(nproc)"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=0:detect_stack_use_after_return=1
export LSAN_OPTIONS=suppressions=$root/tools/lsan.supp:print_suppressions=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
cd build-sanitize
# The programs that open an OpenGL window (3.2, 4.3's viewer, --window in 2.3, 6.1-6.4) run with leak detection off: Mesa's
# driver is unloaded before LeakSanitizer reports, so its allocations show as "<unknown module>"
# and no suppression can name them. Memory errors (ASan) and undefined behaviour are still caught.
gl='^(chapter\.(3\.2-|4\.3-realtime)|preview\.)'
# hostile.inputs runs its programs under an address-space limit, which ASan's shadow memory
# (terabytes of reserved addresses) cannot live under: it runs in the normal build only.
ctest --output-on-failure -j "$(nproc)" -LE '^(book|install|course|hostile|bench|headers)$' -E "$gl" "$@"
ASAN_OPTIONS=$ASAN_OPTIONS:detect_leaks=0 ctest --output-on-failure -j "$(nproc)" -R "$gl" "$@"
