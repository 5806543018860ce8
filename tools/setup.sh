#!/usr/bin/env bash
# Installs the Debian packages zraka needs, and does nothing when they are all present.
# It covers every test and every command a page shows (tools/course_flow.sh runs those): the
# pages use no profiler (a user's perf needs kernel.perf_event_paranoid <= 2, which Debian's own
# kernels do not set by default, and a VM may have no counters): they time with the shell's `time`.
# Usage: bash tools/setup.sh [--extras]   (--extras adds Embree for the BVH benchmark, python3-venv for tools/mitsuba-setup.sh and LLVM 19 for Mitsuba's llvm_ad_rgb)
set -euo pipefail

core=(build-essential cmake pkg-config
      libglm-dev libstb-dev libtinyexr-dev libglfw3-dev libepoxy-dev
      opencl-headers opencl-clhpp-headers ocl-icd-opencl-dev pocl-opencl-icd clinfo
      doctest-dev libyaml-cpp-dev libpugixml-dev libcli11-dev libfmt-dev
      xvfb xauth libgl1-mesa-dri python3 python3-matplotlib  # matplotlib: tools/plot_convergence.py
      libassimp-dev  # PLY and glTF meshes (mesh_file.hpp)
      # the book as a website (tools/book_html.sh) and its test in headless Chromium (book.site):
      pandoc chromium chromium-driver python3-selenium python3-pil python3-numpy
      fonts-dejavu-core fonts-dejavu-extra  # the site's pinned fonts (DejaVu Math TeX Gyre for MathML)
      clang libclang-rt-14-dev)  # clang: tools/fuzz.sh (libFuzzer), which tools/test.sh runs
extras=(libembree-dev python3-venv libllvm19)  # python3-venv: tools/mitsuba-setup.sh; libllvm19: its llvm_ad_rgb variant

want=("${core[@]}")
[[ "${1:-}" == "--extras" ]] && want+=("${extras[@]}")

missing=()
for p in "${want[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[[ ${#missing[@]} -eq 0 ]] && exit 0

echo "setup: installing ${missing[*]}" >&2
sudo=""
if [[ $(id -u) -ne 0 ]]; then
  command -v sudo >/dev/null || { echo "setup: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  sudo="sudo"
fi
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
