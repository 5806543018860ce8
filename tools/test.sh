#!/usr/bin/env bash
# README command 2: set up, build (warnings are errors), and run every test; then the same tests
# built with AddressSanitizer + UndefinedBehaviorSanitizer (tools/sanitize.sh, build-sanitize/)
# and a short fuzz budget (tools/fuzz.sh: 10 s for each of the 6 targets, 2 at a time).
# Every phase runs even when an earlier one failed (a phase that needs a failed one is reported
# as not run); the last lines are one summary line per phase, and the exit code is 1 when any
# phase failed or did not run.
#   bash tools/test.sh               the whole run
#   bash tools/test.sh --self-test   the summary and exit code on stand-in phases (a second)
set -uo pipefail
cd "$(dirname "$0")/.."
logs=$(mktemp -d "${TMPDIR:-/tmp}/zraka-test.XXXXXX")
trap 'rm -rf "$logs"' EXIT

# The phases. Each writes its output to the terminal and to $logs/<phase>.log; its exit code is
# the phase's result. detail_<phase> prints what the summary says about a failure.
phase_setup() { bash tools/setup.sh; }
phase_build() { bash tools/build.sh -DZRAKA_WERROR=ON; }  # runs setup.sh again: a no-op by then
phase_tests() { (cd build && ctest --output-on-failure -j "$(nproc)"); }
phase_sanitizers() { bash tools/sanitize.sh; }
phase_fuzz() { bash tools/fuzz.sh --seconds 10; }

# The names of the tests that failed, from ctest's "The following tests FAILED:" block.
failed_tests() {
  awk '/The following tests FAILED:/ { on = 1; next } on && /^[[:space:]]+[0-9]+ - / { print $3 }
       on && !/^[[:space:]]+[0-9]+ - / { on = 0 }' "$1" | sort -u | tr '\n' ' '
}
detail_setup() { tail -n 1 "$1"; }
detail_build() {
  local e
  e=$(grep -m 3 -E 'error:|Error [0-9]+|CMake Error' "$1" | tr '\n' ' ')
  echo "${e:-see the build output above}"
}
detail_tests() {
  local t
  t=$(failed_tests "$1")
  if [[ -n $t ]]; then echo "failed: $t"; else tail -n 1 "$1"; fi
}
detail_sanitizers() { detail_tests "$1"; }
detail_fuzz() {
  local c
  c=$(grep -E 'crash\(es\)$' "$1" | grep -v ' 0 crash(es)$' | tr '\n' ' ')
  echo "${c:-$(tail -n 1 "$1")}"
}

run_all() {
  local -A result=() secs=() detail=()
  local order=(setup build tests sanitizers fuzz)
  local -A needs=([build]=setup [tests]=build [sanitizers]=setup [fuzz]=setup)
  local p t0 rc any=0
  for p in "${order[@]}"; do
    if [[ -n ${needs[$p]:-} && ${result[${needs[$p]}]} != pass ]]; then
      result[$p]="not run" secs[$p]=0 detail[$p]="needs ${needs[$p]}, which did not pass"
      any=1
      continue
    fi
    echo "=== test.sh: $p" >&2
    t0=$EPOCHREALTIME
    "phase_$p" 2>&1 | tee "$logs/$p.log"
    rc=${PIPESTATUS[0]}
    secs[$p]=$(awk -v a="$t0" -v b="$EPOCHREALTIME" 'BEGIN { printf "%.0f", b - a }')
    if [[ $rc -eq 0 ]]; then
      result[$p]=pass detail[$p]=""
    else
      result[$p]=FAIL detail[$p]="exit $rc; $("detail_$p" "$logs/$p.log")"
      any=1
    fi
  done
  echo
  echo "test.sh summary (phase, result, seconds, what failed):"
  for p in "${order[@]}"; do
    printf '%-11s %-8s %6s s  %s\n' "$p" "${result[$p]}" "${secs[$p]}" "${detail[$p]}"
  done
  return $any
}

if [[ ${1:-} == --self-test ]]; then
  # Stand-ins: the build fails, so the tests are not run; the sanitizers fail with two tests;
  # setup and fuzz pass. Expected: exit 1 and these lines.
  phase_setup() { echo "setup: nothing to install"; }
  phase_build() { echo "x.cpp:1:1: error: stand-in build error"; return 2; }
  phase_tests() { echo "must not run"; }
  phase_sanitizers() {
    printf 'The following tests FAILED:\n\t 12 - unit.test_a (Failed)\n\t 40 - chapter.b (Timeout)\nErrors while running CTest\n'
    return 8
  }
  phase_fuzz() { echo "fuzz scene       10s: 100 executions (10/s), corpus 3 inputs, 0 crash(es)"; }
  out=$(run_all 2>&1); rc=$?
  echo "$out" | sed -n "/^test.sh summary/,\$p"
  summary=$(sed -n '/^test.sh summary/,$p' <<<"$out")
  status=0
  for want in '^setup +pass ' '^build +FAIL .*stand-in build error' '^tests +not run .*needs build' \
              '^sanitizers +FAIL .*failed: chapter.b unit.test_a' '^fuzz +pass '; do
    grep -Eq "$want" <<<"$summary" || { echo "test.sh self-test: no line matching '$want' in:" >&2; status=1; }
  done
  grep -q 'must not run' <<<"$out" && { echo "test.sh self-test: the tests ran after a failed build" >&2; status=1; }
  [[ $rc -eq 1 ]] || { echo "test.sh self-test: exit code $rc, expected 1" >&2; status=1; }
  [[ $status -eq 0 ]] || { echo "$out" >&2; exit 1; }
  echo "test.sh self-test passed"
  exit 0
fi

run_all
