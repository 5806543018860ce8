#!/usr/bin/env bash
# Makes the Python venv that tools/mitsuba_reference.py runs in: build/mitsuba-venv with Mitsuba 3
# from PyPI (its scalar_rgb variant, CPU only; llvm_ad_rgb too where LLVM 19 is installed, which
# tools/setup.sh --extras does: Dr.Jit 1.5 cannot compile with Debian 12's default LLVM 14) and numpy. Does nothing when the venv already
# imports mitsuba. Independent validation of the path tracer (book 4.2); never part of the tests.
# Needs Debian's python3-venv (bash tools/setup.sh --extras installs it).
# Usage: bash tools/mitsuba-setup.sh    then: build/mitsuba-venv/bin/python tools/mitsuba_reference.py ...
set -euo pipefail
cd "$(dirname "$0")/.."
venv="build/mitsuba-venv"
if [[ -x "$venv/bin/python" ]] && "$venv/bin/python" -c "import mitsuba" 2>/dev/null; then
  exit 0
fi
python3 -m venv --help >/dev/null 2>&1 || {
  echo "mitsuba-setup: python3 -m venv is missing: run 'bash tools/setup.sh --extras' (python3-venv)" >&2
  exit 1
}
echo "mitsuba-setup: making $venv with mitsuba and numpy (a few hundred MB)" >&2
mkdir -p build
python3 -m venv "$venv"
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check mitsuba numpy
"$venv/bin/python" -c "import mitsuba as mi; mi.set_variant('scalar_rgb'); print('mitsuba', mi.__version__)"
