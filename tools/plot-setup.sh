#!/usr/bin/env bash
# Makes the Python venv that tools/plot_convergence.py runs in: build/plot-venv with matplotlib
# (pip's matplotlib is ~200 MB lighter than Debian's python3-matplotlib). Does nothing when the
# venv already imports matplotlib. Plots are optional tooling and never part of the test path.
# Needs Debian's python3-venv (bash tools/setup.sh --extras installs it).
# Usage: bash tools/plot-setup.sh    then: build/plot-venv/bin/python tools/plot_convergence.py ...
set -euo pipefail
cd "$(dirname "$0")/.."
venv="build/plot-venv"
if [[ -x "$venv/bin/python" ]] && "$venv/bin/python" -c "import matplotlib" 2>/dev/null; then
  exit 0
fi
python3 -m venv --help >/dev/null 2>&1 || {
  echo "plot-setup: python3 -m venv is missing: run 'bash tools/setup.sh --extras' (python3-venv)" >&2
  exit 1
}
echo "plot-setup: making $venv with matplotlib (about 200 MB, half a minute)" >&2
mkdir -p build
python3 -m venv "$venv"
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check matplotlib
"$venv/bin/python" -c "import matplotlib" 
