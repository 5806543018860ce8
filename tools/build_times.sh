#!/usr/bin/env bash
# The student's loop, measured (issue 12): wall-clock seconds for a full clean build, and for the
# rebuild after touching one chapter's main.cpp (each chapter), one test file and one header,
# next to Ray Tracing in One Weekend's main.cc compiled and linked with `g++ -O3` in the same run,
# the yardstick (a machine-independent figure is the ratio, not the seconds).
#
#   bash tools/build_times.sh [--rtiow DIR] [--build DIR] [--jobs N] [--repeat N]
#                             [--test tests/test_X.cpp] [--header include/zraka/X.hpp]
#                             [--chapters "1.2-sphere 2.2-whitted"] [--chapters-only]
#                             [--skip-full] [-- CMAKE_ARGS...]
#
# --rtiow DIR   a folder holding RTIOW book 1's sources (src/InOneWeekend: main.cc and its
#               headers); kept outside this repository. Without it the yardstick is skipped.
# --build DIR   the build folder (default: a new temporary one, removed at the end). A fresh
#               Release configuration without ccache, so every figure is a real compile.
# --skip-full   reuse an already built --build DIR (only the incremental rows).
# --chapters-only  no test-file and header rows (the same as --test '' --header '').
# On a shared machine the seconds swing with other users' load: RTIOW is compiled again after
# every row, and each row's ratio is to the mean of the RTIOW runs just before and after it.
# --repeat N    measure each incremental row N times and print the median (default 1).
# -- ARGS       the rest goes to cmake's configure step (e.g. -DZRAKA_WERROR=ON).
# Not a test: the figures depend on the machine and its load, which is printed with them.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cmake_args=() chapters_only=0 rtiow="" build="" jobs=$(nproc) repeat=1 skip_full=0 chapters=""
test_file=tests/test_sphere.cpp header=include/zraka/integrators/whitted.hpp

die() { echo "error: $*" >&2; exit 1; }
while (($#)); do
  case $1 in
    --rtiow) rtiow=${2:?}; shift 2 ;;
    --build) build=${2:?}; shift 2 ;;
    --jobs) jobs=${2:?}; shift 2 ;;
    --repeat) repeat=${2:?}; shift 2 ;;
    --test) test_file=${2?}; shift 2 ;;
    --header) header=${2?}; shift 2 ;;
    --chapters) chapters=${2:?}; shift 2 ;;
    --skip-full) skip_full=1; shift ;;
    --chapters-only) chapters_only=1; shift ;;
    --) shift; cmake_args=("$@"); break ;;
    -h|--help) sed -n '2,20p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) die "unknown option '$1' (see --help)" ;;
  esac
done
[[ $jobs =~ ^[1-9][0-9]*$ ]] || die "--jobs must be a positive integer, got '$jobs'"
[[ $repeat =~ ^[1-9][0-9]*$ ]] || die "--repeat must be a positive integer, got '$repeat'"
[[ -z $test_file || -f $root/$test_file ]] || die "--test: no file $root/$test_file"
[[ -z $header || -f $root/$header ]] || die "--header: no file $root/$header"
if [[ -n $rtiow ]]; then
  [[ -f $rtiow/main.cc ]] || die "--rtiow: no main.cc in $rtiow"
  rtiow=$(cd "$rtiow" && pwd)
  case $rtiow/ in "$root"/*) die "--rtiow: keep RTIOW's sources outside this repository" ;; esac
fi

tmp=$(mktemp -d)
cleanup() { rm -rf "$tmp"; }
trap cleanup EXIT
if [[ -z $build ]]; then
  ((skip_full == 0)) || die "--skip-full needs --build DIR"
  build=$tmp/build
fi
mkdir -p "$build"
build=$(cd "$build" && pwd)
# Only a folder this script made is ever emptied.
marker=$build/.zraka_build_times
if ((skip_full == 0)) && [[ -n $(ls -A "$build") && ! -f $marker ]]; then
  die "--build $build is not empty and was not made by this script"
fi
((skip_full == 0)) || [[ -f $marker ]] || die "--skip-full: $build was not made by this script"
export CCACHE_DISABLE=1  # a cached object would measure ccache, not the compiler

now() { date +%s.%N; }
# seconds <command...>: runs the command quietly, prints "<wall> <cpu>": wall-clock seconds, and
# the user+system CPU seconds of it and its children (less sensitive to other users' load).
seconds() {
  local t0 t1 cpu
  t0=$(now)
  cpu=$( ( "$@" >"$tmp/last.log" 2>&1 || exit 1; times ) | tail -1) ||
    { cat "$tmp/last.log" >&2; die "failed: $*"; }
  t1=$(now)
  awk -v a="$t0" -v b="$t1" -v c="$cpu" 'BEGIN {
    split(c, f, " "); n = 0
    for (i = 1; i <= 2; i++) { split(f[i], m, "m"); sub("s", "", m[2]); n += m[1] * 60 + m[2] }
    printf "%.2f %.2f\n", b - a, n }'
}
# median of lines "<wall> <cpu>", each column on its own
median1() { sort -g | awk '{v[NR] = $1} END {m = int((NR + 1) / 2); print (NR % 2) ? v[m] : (v[m] + v[m + 1]) / 2}'; }
median() {
  local lines
  lines=$(cat)
  echo "$(cut -d' ' -f1 <<<"$lines" | median1) $(cut -d' ' -f2 <<<"$lines" | median1)"
}
build_target() { cmake --build "$build" --target "$1" -j "$jobs"; }
# touch_and_build <file> <target>: the median rebuild after an edit that changes only the time.
touch_and_build() {
  local i samples=()
  for ((i = 0; i < repeat; i++)); do
    touch "$root/$1"
    samples+=("$(seconds build_target "$2")")
  done
  printf '%s\n' "${samples[@]}" | median
}

rtiow_once() { g++ -O3 -o "$tmp/rtiow" "$rtiow/main.cc"; }
rtiow_times=()
measure_rtiow() {
  [[ -z $rtiow ]] || { rtiow_times+=("$(seconds rtiow_once)"); echo "  RTIOW: ${rtiow_times[-1]} (wall cpu)" >&2; }
}

rows=()  # "label<TAB>wall cpu<TAB>index of the RTIOW run before it"; "-" when not measured
row() {
  rows+=("$1"$'\t'"$2"$'\t'"$((${#rtiow_times[@]} - 1))")
  echo "  $1: $2 (wall cpu)" >&2
  [[ $2 == - ]] || measure_rtiow
}

echo "load before: $(uptime)"
measure_rtiow
if ((skip_full == 0)); then
  find "$build" -mindepth 1 -delete
  touch "$marker"
  generator=()
  if command -v ninja >/dev/null; then generator=(-G Ninja); fi
  cmake -S "$root" -B "$build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release "${cmake_args[@]}" \
        >"$tmp/configure.log" 2>&1 || { cat "$tmp/configure.log" >&2; die "configure failed"; }
  row "full clean build (all, -j$jobs)" "$(seconds cmake --build "$build" -j "$jobs")"
  # A rejected precompiled header is only a warning here (no ZRAKA_WERROR), and a slow build.
  if grep -q "Winvalid-pch" "$tmp/last.log"; then
    grep "Winvalid-pch" "$tmp/last.log" | head -5 >&2
    echo "warning: some units did not use their precompiled header (above)" >&2
  fi
fi

if [[ -z $chapters ]]; then
  chapters=$(cd "$root/chapters" && for d in */main.cpp; do echo "${d%/main.cpp}"; done | sort -V)
fi
for ch in $chapters; do
  [[ -f $root/chapters/$ch/main.cpp ]] || die "--chapters: no chapters/$ch/main.cpp"
  slug=${ch#*-}
  if [[ -x $build/bin/$slug ]]; then
    row "chapter $ch (touch main.cpp)" "$(touch_and_build "chapters/$ch/main.cpp" "$slug")"
  else
    row "chapter $ch (not built here)" "-"
  fi
done
if ((chapters_only == 0)) && [[ -n $test_file ]]; then
  test_name=$(basename "$test_file" .cpp)
  row "$test_file (touch, build $test_name)" "$(touch_and_build "$test_file" "$test_name")"
fi
if ((chapters_only == 0)) && [[ -n $header ]]; then
  row "$header (touch, build all)" "$(touch_and_build "$header" all)"
fi
echo "load after:  $(uptime)"

rtiow_s=""
if ((${#rtiow_times[@]})); then rtiow_s=$(printf '%s\n' "${rtiow_times[@]}" | median); fi
ratio() { awk -v a="$1" -v b="$2" -v c="$3" 'BEGIN {printf "%.2f", a / ((b + c) / 2)}'; }
echo
printf '%-50s %7s %7s %8s %8s\n' "what" "wall s" "cpu s" "wall/RT" "cpu/RT"
for r in "${rows[@]}"; do
  IFS=$'\t' read -r label t i <<<"$r"
  if [[ $t == - ]]; then printf '%-50s %7s\n' "$label" "-"; continue; fi
  read -r w c <<<"$t"
  if [[ -z $rtiow || $label == full* ]]; then
    printf '%-50s %7.2f %7.2f\n' "$label" "$w" "$c"
  else
    read -r bw bc <<<"${rtiow_times[i]}"
    read -r aw ac <<<"${rtiow_times[i + 1]}"
    printf '%-50s %7.2f %7.2f %8s %8s\n' "$label" "$w" "$c" "$(ratio "$w" "$bw" "$aw")" "$(ratio "$c" "$bc" "$ac")"
  fi
done
if [[ -n $rtiow_s ]]; then
  read -r rw rc <<<"$rtiow_s"
  printf '%-50s %7.2f %7.2f   (median of %s runs)\n' "RTIOW book 1 main.cc (g++ -O3, compile+link)" "$rw" "$rc" \
         "${#rtiow_times[@]}"
else
  echo "RTIOW book 1 main.cc: skipped (give --rtiow DIR, the folder of its main.cc)"
fi
