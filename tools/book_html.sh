#!/usr/bin/env bash
# Renders the book to HTML that works offline: every book/*.md and book/assignments/**/*.md becomes
# a page under build/book-html/ (README.md becomes index.html), math as MathML (no script, no
# network), figures and other files of book/ copied along, links between .md pages rewritten to
# .html, links to sources outside book/ pointed at the source tree, a bar on every page with the
# contents and the previous and next page in course order, and contents.html listing every page.
#   bash tools/book_html.sh [OUT_DIR]      (needs pandoc: bash tools/setup.sh)
# The test book.site (tests/site/check_site.py) opens every page in headless Chromium.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
book="$root/book"
out="${1:-$root/build/book-html}"
command -v pandoc >/dev/null || { echo "book_html: pandoc is missing (bash tools/setup.sh)" >&2; exit 1; }
# The site is written beside OUT_DIR and replaces it when complete: no half-written site, no page
# left from a removed chapter. A folder that is not a site of this script is never replaced.
if [[ -d $out && -n $(ls -A "$out") && ! -f $out/contents.html ]]; then
  echo "book_html: $out is not empty and not a site made by book_html.sh; not replacing it" >&2
  exit 1
fi
mkdir -p "$(dirname "$out")"
final="$(cd "$(dirname "$out")" && pwd)/$(basename "$out")"
out=$(mktemp -d "$final.new.XXXXXX")
chmod 755 "$out"
tmp=$(mktemp -d)
trap 'wait; rm -rf "$tmp" "$out"' EXIT  # wait: pandocs still running when one failed

# Pages in course order: the contents, the introduction, the chapters (N.M sorted as numbers),
# the errata, then the assignments.
mapfile -t pages < <(cd "$book" && {
  echo README.md
  [[ -f intro.md ]] && echo intro.md
  ls [0-9]*.md 2>/dev/null | sort -V
  [[ -f errata.md ]] && echo errata.md
  find assignments -name '*.md' 2>/dev/null | sort -V
  find . -name '*.md' -not -path './assignments/*' | sed 's|^\./||' | sort -V
} | awk '!seen[$0]++')

html_of() {  # book-relative .md path -> book-relative .html path
  local p=${1%.md}
  [[ ${p##*/} == README ]] && p="${p%README}index"
  echo "$p.html"
}
title_of() {  # the first "# " heading, or the file name
  local t
  t=$(grep -m1 '^# ' "$book/$1" | sed 's/^# //') || true
  echo "${t:-$1}"
}
rel_to() {  # a path relative to the folder of page $1, to book-relative $2
  local up="" d
  d=$(dirname "$1")
  [[ $d != . ]] && up=$(sed -E 's|[^/]+|..|g' <<<"$d")/
  echo "$up$2"
}
escape() { sed -e 's/&/\&amp;/g' -e 's/</\&lt;/g' -e 's/>/\&gt;/g' <<<"$1"; }

# Files of book/ other than pages (figures, assignment sources and target images) go along.
(cd "$book" && find . -type f ! -name '*.md' -print0 | while IFS= read -r -d '' f; do
  mkdir -p "$out/$(dirname "$f")"; cp -p "$f" "$out/$f"; done)

# Fonts pinned to DejaVu (fonts-dejavu-core, and fonts-dejavu-extra for the OpenType math font;
# tools/setup.sh installs both) so that a page looks the same on every machine (the screenshot of
# the test book.site).
cat >"$tmp/style.html" <<'EOF'
<style>
body { max-width: 52em; margin: 1em auto; padding: 0 1em; font-family: "DejaVu Sans", sans-serif; line-height: 1.5; color: #222; }
pre, div.sourceCode { background: #f5f5f5; overflow-x: auto; max-width: 100%; }
code, pre { font-family: "DejaVu Sans Mono", monospace; }
math { font-family: "DejaVu Math TeX Gyre", math; }
pre { padding: .6em; font-size: 90%; }
code { font-size: 95%; }
img { max-width: 100%; }
nav.bar { font-size: 90%; border-bottom: 1px solid #ccc; padding-bottom: .4em; margin-bottom: 1em; }
nav.bar.bottom { border-bottom: none; border-top: 1px solid #ccc; padding-top: .4em; margin-top: 2em; }
table { border-collapse: collapse; } td, th { border: 1px solid #ccc; padding: .2em .5em; }
math[display="block"] { margin: .8em 0; }
</style>
EOF

# Links: foo.md[#x] -> foo.html[#x] (README.md -> index.html); a relative link that leaves book/
# (a source file) -> the file in the source tree.
cat >"$tmp/links.lua" <<'EOF'
local book = os.getenv("BOOK_SRC")
local page_dir = os.getenv("PAGE_DIR")
local depth = 0
if page_dir ~= "." then for _ in page_dir:gmatch("[^/]+") do depth = depth + 1 end end
local function fix(target)
  if target:match("^%a[%w+.-]*:") or target:match("^#") or target == "" then return target end
  local path, frag = target:match("^([^#]*)(.*)$")
  local ups = 0
  for _ in path:gmatch("%.%./") do ups = ups + 1 end
  if ups > depth then
    return "file://" .. book .. "/" .. (page_dir == "." and "" or page_dir .. "/") .. path .. frag
  end
  if path:match("/$") then path = path .. "index.html" end  -- a folder: its README or listing page
  if path:match("%.md$") then
    path = path:gsub("README%.md$", "index.md"):gsub("%.md$", ".html")
  end
  return path .. frag
end
function Link(el) el.target = fix(el.target); return el end
function Image(el) el.src = fix(el.src); return el end
EOF

n=${#pages[@]}
jobs=$(nproc)  # pandocs at a time
pids=()
: >"$tmp/contents.md"
echo "# All pages" >>"$tmp/contents.md"
echo >>"$tmp/contents.md"
for ((i = 0; i < n; i++)); do
  page=${pages[i]}
  html=$(html_of "$page")
  title=$(title_of "$page")
  mkdir -p "$out/$(dirname "$html")"
  nav="<a href=\"$(rel_to "$page" index.html)\">Contents</a> · <a href=\"$(rel_to "$page" contents.html)\">All pages</a>"
  ((i > 0)) && nav="$nav · previous: <a href=\"$(rel_to "$page" "$(html_of "${pages[i - 1]}")")\">$(escape "$(title_of "${pages[i - 1]}")")</a>"
  ((i + 1 < n)) && nav="$nav · next: <a href=\"$(rel_to "$page" "$(html_of "${pages[i + 1]}")")\">$(escape "$(title_of "${pages[i + 1]}")")</a>"
  echo "<nav class=\"bar\">$nav</nav>" >"$tmp/before-$i.html"
  echo "<nav class=\"bar bottom\">$nav</nav>" >"$tmp/after-$i.html"
  BOOK_SRC="$book" PAGE_DIR="$(dirname "$page")" \
    pandoc "$book/$page" -f markdown+gfm_auto_identifiers-implicit_figures -t html5 --standalone \
      --mathml --lua-filter "$tmp/links.lua" --metadata pagetitle="$title — zraka" \
      --include-in-header "$tmp/style.html" --include-before-body "$tmp/before-$i.html" \
      --include-after-body "$tmp/after-$i.html" -o "$out/$html" &
  pids+=($!)
  if ((${#pids[@]} >= jobs)); then wait "${pids[0]}"; pids=("${pids[@]:1}"); fi  # a failure stops here (set -e)
  echo "- [$(sed 's/[][]/\\&/g' <<<"$title")]($html) \`book/$page\`" >>"$tmp/contents.md"
done
for p in "${pids[@]}"; do wait "$p"; done
# A folder of book/ without a README.md (figures, an assignment's student/ and solution/) gets a
# page listing its files, so that a link to the folder works in the site as it does on a forge.
while IFS= read -r -d '' d; do
  d=${d#./}
  [[ -f "$book/$d/README.md" ]] && continue
  {
    echo "# Files in \`book/$d/\`"
    echo
    echo "[Contents]($(rel_to "$d/x" index.html)) · [All pages]($(rel_to "$d/x" contents.html))"
    echo
    (cd "$book/$d" && for f in *; do
      if [[ -d $f ]]; then echo "- [$f/]($f/index.html)"; else echo "- [$f]($f)"; fi
    done)
  } >"$tmp/listing.md"
  pandoc "$tmp/listing.md" -f markdown -t html5 --standalone --metadata pagetitle="book/$d — zraka" \
    --include-in-header "$tmp/style.html" -o "$out/$d/index.html"
done < <(cd "$book" && find . -mindepth 1 -type d -print0)
pandoc "$tmp/contents.md" -f markdown -t html5 --standalone --metadata pagetitle="All pages — zraka" \
  --include-in-header "$tmp/style.html" -o "$out/contents.html"
rm -rf "$final"
mv "$out" "$final"
echo "book_html: $n pages -> $final/index.html (and $final/contents.html)"
