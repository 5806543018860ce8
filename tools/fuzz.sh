#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/, clang) into build-fuzz/ and runs each for a given time.
# Usage: bash tools/fuzz.sh [--seconds N] [--jobs J] [--keep-going] [target...]
#   targets: scene obj bpt pfm png pathtrace (default: all), and mesh (PLY/glTF through
#   assimp: only when named, see fuzz/README.md); N seconds each (default 60);
#   J targets at a time (default 2, for 2 cores); --keep-going: libFuzzer's fork mode, which
#   goes on after a crash, timeout or out-of-memory (for long campaigns) instead of stopping.
# Each corpus (build-fuzz/corpus/<target>/) starts from the seed inputs (fuzz/CMakeLists.txt)
# and grows across runs. A crash, timeout (10 s for one input) or out-of-memory (an allocation
# above 1 GiB or 2 GiB resident) is copied to tests/fuzz-regressions/<target>/, which the test
# fuzz.replay.<target> of the normal build replays; then this script exits 1.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
seconds=60 jobs=2 keep_going=0 targets=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --seconds) seconds=$2; shift 2 ;;
    --jobs) jobs=$2; shift 2 ;;
    --keep-going) keep_going=1; shift ;;
    -h|--help) sed -n '2,12p' "$0"; exit 0 ;;
    -*) echo "fuzz.sh: unknown option $1" >&2; exit 1 ;;
    *) targets+=("$1"); shift ;;
  esac
done
all=(scene obj bpt pfm png pathtrace)
[[ ${#targets[@]} -eq 0 ]] && targets=("${all[@]}")
for t in "${targets[@]}"; do
  [[ " ${all[*]} mesh " == *" $t "* ]] || { echo "fuzz.sh: unknown target '$t' (${all[*]})" >&2; exit 1; }
done
[[ "$seconds" =~ ^[0-9]+$ && "$seconds" -ge 1 ]] || { echo "fuzz.sh: --seconds needs a positive whole number" >&2; exit 1; }

command -v clang++ >/dev/null || { echo "fuzz.sh: needs clang++ (bash tools/setup.sh)" >&2; exit 1; }
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=clang++ "${launcher[@]}" \
      -DZRAKA_FUZZ=ON -DZRAKA_BUILD_TESTS=OFF -DZRAKA_BUILD_CHAPTERS=OFF >/dev/null
cmake --build build-fuzz -j 2 --target "${targets[@]/#/fuzz_}"

work=$(mktemp -d "${TMPDIR:-/tmp}/zraka-fuzz.XXXXXX")
[[ -d /dev/shm && -w /dev/shm ]] && work_tmp=$(mktemp -d /dev/shm/zraka-fuzz.XXXXXX) || work_tmp=$work
trap 'rm -rf "$work" "$work_tmp"' EXIT
mkdir -p build-fuzz/logs

run_one() {  # target
  local t=$1 bin=$root/build-fuzz/fuzz/fuzz_$1 corpus=$root/build-fuzz/corpus/$1 art=$work/artifacts/$1
  mkdir -p "$corpus" "$art"
  while IFS= read -r s; do
    [[ -z "$s" ]] && continue
    if [[ -d "$s" ]]; then find "$s" -maxdepth 1 -type f ! -name README.md -exec cp -n -t "$corpus" {} +
    elif [[ -f "$s" ]]; then cp -n "$s" "$corpus"/; fi  # a folder that does not exist yet: no seeds
  done < "build-fuzz/fuzz/fuzz_$t.seeds"
  local mode=()
  [[ -f "$root/fuzz/$t.dict" ]] && mode+=(-dict="$root/fuzz/$t.dict")  # keywords the mutations try
  [[ $keep_going -eq 1 ]] && mode+=(-fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1)
  # The targets' own output (pathtrace's messages) is closed: only libFuzzer's report remains.
  TMPDIR=$work_tmp "$bin" "${mode[@]}" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -malloc_limit_mb=1024 -close_fd_mask=3 -print_final_stats=1 -artifact_prefix="$art/" "$corpus" \
    > "build-fuzz/logs/$t.log" 2>&1 || true
  local execs rate
  execs=$(grep -o 'stat::number_of_executed_units:[[:space:]]*[0-9]*' "build-fuzz/logs/$t.log" | awk '{s+=$2} END {print s+0}')
  rate=$(grep -o 'stat::average_exec_per_sec:[[:space:]]*[0-9]*' "build-fuzz/logs/$t.log" | tail -1 | awk '{print $2}')
  # Fork mode (--keep-going) prints no final statistics: its last status line has the count.
  [[ -z "$execs" || "$execs" == 0 ]] && execs=$(grep -o '^#[0-9]*' "build-fuzz/logs/$t.log" | tail -1 | tr -d '#')
  [[ -z "$rate" && -n "$execs" ]] && rate=$((execs / seconds))
  local found
  found=$(find "$art" -type f | wc -l)
  printf 'fuzz %-9s %4ss: %s executions (%s/s), corpus %s inputs, %s crash(es)\n' "$t" "$seconds" \
    "${execs:-?}" "${rate:-?}" "$(find "$corpus" -type f | wc -l)" "$found"
  if [[ $found -gt 0 ]]; then
    mkdir -p "tests/fuzz-regressions/$t"
    cp "$art"/* "tests/fuzz-regressions/$t/"
    echo "fuzz $t: kept $(ls "$art" | tr '\n' ' ')in tests/fuzz-regressions/$t/ (log: build-fuzz/logs/$t.log)"
  fi
}
export -f run_one
export seconds keep_going work work_tmp root

status=0
printf '%s\n' "${targets[@]}" | xargs -P "$jobs" -I{} bash -c 'run_one {}' | tee "$work/summary"
grep -q ' 0 crash(es)$' "$work/summary" || status=1
[[ $(grep -c ' 0 crash(es)$' "$work/summary") -eq ${#targets[@]} ]] || status=1
exit $status
