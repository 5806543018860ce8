#!/usr/bin/env bash
# The comparison of book 6.4 ("Every integrator, one table"): runs bench/compare_integrators once
# (its table on stdout, one CSV per scene and integrator in build/out/) and plots each scene's
# RMSE against time into book/figures/6.4-compare-<scene>.png (tools/plot_convergence.py with
# Debian's python3-matplotlib). Takes about 3 minutes on two cores; the mis references are
# cached in build/out/ after the first run.
# Usage: bash tools/compare_integrators.sh [extra options for compare_integrators]
set -euo pipefail
cd "$(dirname "$0")/.."
bin=build/bin/compare_integrators
[[ -x $bin ]] || { echo "compare_integrators.sh: build first (bash tools/build.sh)" >&2; exit 1; }
"$bin" --threads 2 --target 0.02 --max-seconds 8 "$@"
for s in ajar-door caustic-box tiny-light; do
  python3 tools/plot_convergence.py build/out/compare-$s-{naive,nee,mis,bdpt,sppm,mlt}.csv \
    --labels "naive,nee,mis,bdpt,sppm,mlt" --column rmse --title "$s, 48x36: RMSE against time" \
    -o book/figures/6.4-compare-$s.png
done
