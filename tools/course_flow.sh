#!/usr/bin/env bash
# The course flow: builds the chapter programs one by one in course order (chapter folders sorted
# naturally: 0.0, 1.0, ..., 1.9, 2.1, ..., 5.3) in an existing build tree and runs each once at its
# default settings in a fresh temporary folder, then prints a table of build and run times.
#   bash tools/course_flow.sh [BUILD_DIR]      (default: build; configure it first: tools/build.sh)
# Window programs run under xvfb-run: one with --headless runs headless, others with a --frames
# option draw 60 frames (their default is "until the window closes"). A chapter whose target was
# not configured (a missing dependency) or that needs a display when there is none is skipped,
# with the reason. Exit code 1 when a chapter fails to build or to run; a chapter whose run takes
# longer than 10 s is flagged but does not fail. Then it runs every command of the chapter's
# page (the build/bin/... lines of its ```sh blocks, and the `$ build/bin/...` lines of pasted
# outputs) from the same scratch folder; a command that fails counts as a failed run and shows
# in the table's page column (exit is the program's own run at its defaults). At the
# end the checkout must hold nothing new (git status and build/out/ as before): the programs
# write into the folder they run in. CTest runs this as book.course_flow.
set -uo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="$(cd "${1:-$root/build}" 2>/dev/null && pwd)" || { echo "course_flow: no build folder ${1:-$root/build} (run tools/build.sh first)" >&2; exit 1; }
[[ -f "$build/CMakeCache.txt" ]] || { echo "course_flow: $build is not a CMake build tree" >&2; exit 1; }
limit=10         # seconds a chapter may take at its default settings
run_timeout=300  # a run that hangs is killed and counted as failed
window_frames=60
xvfb=(xvfb-run -a -s "-screen 0 1280x720x24 -noreset")

# The targets the build tree knows (a chapter skipped at configure time has none).
targets=$(cmake --build "$build" --target help 2>/dev/null)
# Where the programs land: CMAKE_RUNTIME_OUTPUT_DIRECTORY is <build>/bin.
bin="$build/bin"

mapfile -t folders < <(cd "$root/chapters" && for d in */; do
  d=${d%/}; [[ -f "$d/main.cpp" && $d =~ ^[0-9]+\.[0-9]+-[a-z0-9-]+$ ]] && echo "$d"; done | sort -V)

logdir=$(mktemp -d)
status_before=$(git -C "$root" status --porcelain --untracked-files=all 2>/dev/null)
out_before=$(ls -A "$root/build/out" 2>/dev/null)
export ZRAKA_ROOT="$root"
# The commands a page shows: build/bin/<program> lines of ```sh blocks and `$ build/bin/...`
# lines (comments after # dropped; lines ending in \ joined).
page_commands() {
  awk '
    /^```/ { if (inblock) { inblock = 0 } else { inblock = 1; sh = ($0 ~ /^```(sh|bash)?$/) ; text = ($0 ~ /^```text/) } ; next }
    inblock {
      line = $0
      if (line ~ /^\$ /) line = substr(line, 3)
      else if (!sh) next
      while (line ~ /\\$/ && (getline nxt) > 0) { sub(/\\$/, "", line); line = line " " nxt }
      if (line ~ /(^|&& |^[^#]*[ ;])build\/bin\//) print line
    }' "$1" | grep -v '^for \|^done\|^  ' | sed -E 's/[[:space:]]+#[^"]*$//'
}
trap 'rm -rf "$logdir"' EXIT
rows=()
failed=0 skipped=0 slow=0 ok=0
total_build=0 total_run=0
secs() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", b - a }'; }
add() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.2f", a + b }'; }

for folder in "${folders[@]}"; do
  slug=${folder#*-}
  section=${folder%%-*}
  if ! grep -Eq "(^|[ :])$slug(\$|[ :])" <<<"$targets"; then
    why="the build tree has no target $slug"
    [[ -f "$root/chapters/$folder/needs.txt" ]] &&
      why="$why; its needs.txt lists $(grep -v '^#' "$root/chapters/$folder/needs.txt" | tr '\n' ' ')(see the configure output)"
    rows+=("$section|$slug|-|-|-|-|skipped: $why")
    skipped=$((skipped + 1))
    echo "course_flow: $folder: skipped: $why" >&2
    continue
  fi
  echo "course_flow: $folder: building $slug" >&2
  t0=$EPOCHREALTIME
  if ! cmake --build "$build" --target "$slug" >"$logdir/$slug.build" 2>&1; then
    tb=$(secs "$t0" "$EPOCHREALTIME")
    rows+=("$section|$slug|$tb|-|-|-|BUILD FAILED")
    failed=$((failed + 1))
    echo "course_flow: $folder: the build failed:" >&2
    tail -n 20 "$logdir/$slug.build" >&2
    continue
  fi
  tb=$(secs "$t0" "$EPOCHREALTIME")
  total_build=$(add "$total_build" "$tb")

  # How to run it: at its defaults, but a window program must stop by itself.
  args=() wrap=() note="defaults"
  help=$("$bin/$slug" --help 2>&1)
  if [[ -f "$root/chapters/$folder/needs.txt" ]] && grep -Eq '^(glfw|epoxy)$' "$root/chapters/$folder/needs.txt"; then
    if grep -q -- '--headless' <<<"$help"; then
      args=(--headless) note="--headless"
    elif grep -q -- '--frames' <<<"$help"; then
      args=(--frames "$window_frames") note="--frames $window_frames"
    fi
    if [[ ${args[0]:-} != --headless ]]; then
      if command -v xvfb-run >/dev/null; then
        wrap=("${xvfb[@]}") note="$note, xvfb-run"
      elif [[ -z "${DISPLAY:-}" ]]; then
        rows+=("$section|$slug|$tb|-|-|-|skipped: needs a display (no DISPLAY, no xvfb-run)")
        skipped=$((skipped + 1))
        continue
      fi
    fi
  fi

  work=$(mktemp -d -p "$logdir")
  t0=$EPOCHREALTIME
  (cd "$work" && timeout "$run_timeout" "${wrap[@]}" "$bin/$slug" "${args[@]}") >"$logdir/$slug.run" 2>&1
  code=$?
  tr=$(secs "$t0" "$EPOCHREALTIME")
  total_run=$(add "$total_run" "$tr")
  if [[ $code -ne 0 ]]; then
    note="RUN FAILED ($note)"
    [[ $code -eq 124 ]] && note="RUN TIMED OUT after ${run_timeout} s ($note)"
    failed=$((failed + 1))
    echo "course_flow: $folder: '$slug ${args[*]}' exited with $code:" >&2
    tail -n 20 "$logdir/$slug.run" >&2
  else
    ok=$((ok + 1))
    if awk -v t="$tr" -v l="$limit" 'BEGIN { exit !(t > l) }'; then
      note="$note; SLOW: over $limit s"
      slow=$((slow + 1))
    fi
  fi
  # The page's commands, from the same scratch folder.
  page=$(ls "$root"/book/"$section"-*.md 2>/dev/null | head -n 1)
  [[ $section == 0.0 ]] && page="$root/book/intro.md"
  page_col="-"
  if [[ -n $page && -f $page && ${wrap[*]:-} == "" ]]; then
    pc=0 pf=0
    while IFS= read -r cmd; do
      [[ -z $cmd || $cmd == *xvfb-run* || $cmd == *pathtrace_bench* || $cmd == *bvh_embree* ]] && continue
      pc=$((pc + 1))
      (cd "$work" && timeout "$run_timeout" bash -c "${cmd//build\/bin\//$bin/}") >>"$logdir/$slug.page" 2>&1
      pcode=$?
      # A page also shows commands that must fail (a bad scene): those print "error:".
      if [[ $pcode -ne 0 ]] && ! tail -n 3 "$logdir/$slug.page" | grep -q '^error: '; then
        pf=$((pf + 1))
        echo "course_flow: $folder: page command exited with $pcode: $cmd" >&2
        if [[ $pcode -eq 127 ]]; then
          # bash's code for a command it did not find: name it, if that is what happened.
          missing=$(grep -o '[^ :]*: command not found' "$logdir/$slug.page" | tail -n 1)
          [[ -n $missing ]] && echo "course_flow: $folder: ${missing%: command not found} is not installed (tools/setup.sh installs what the pages use)" >&2
        fi
        tail -n 5 "$logdir/$slug.page" >&2
      fi
    done < <(page_commands "$page")
    note="$note; page: $pc commands"
    page_col="$pc ok"
    if [[ $pf -gt 0 ]]; then
      note="$note, $pf FAILED"
      page_col="$pf/$pc FAIL"
      failed=$((failed + 1))
    fi
  fi
  rows+=("$section|$slug|$tb|$tr|$code|$page_col|$note")
done

if [[ $(git -C "$root" status --porcelain --untracked-files=all 2>/dev/null) != "$status_before" ||
      $(ls -A "$root/build/out" 2>/dev/null) != "$out_before" ]]; then
  echo "course_flow: the run left files in the checkout:" >&2
  git -C "$root" status --porcelain --untracked-files=all >&2
  failed=$((failed + 1))
fi

# exit: the program's at its defaults; page: the page's commands that ran, or how many failed.
printf '\n%-8s %-16s %9s %9s %5s %-11s  %s\n' chapter program build_s run_s exit page note
printf '%-8s %-16s %9s %9s %5s %-11s  %s\n' ------- ------- ------- ----- ---- ---- ----
for r in "${rows[@]}"; do
  IFS='|' read -r c p b t e g n <<<"$r"
  printf '%-8s %-16s %9s %9s %5s %-11s  %s\n' "$c" "$p" "$b" "$t" "$e" "$g" "$n"
done
echo
echo "summary: ${#folders[@]} chapters: $ok ran, $failed failed, $skipped skipped, $slow over $limit s;" \
     "build ${total_build} s, run ${total_run} s in total (build tree $build, $(nproc) cores)"
[[ $failed -eq 0 ]]
