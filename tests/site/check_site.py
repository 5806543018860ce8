#!/usr/bin/env python3
"""The test book.site: the book as a website (tools/book_html.sh), opened page by page in headless
Chromium (Debian's chromium, chromium-driver and python3-selenium; tools/setup.sh installs them).

On every page of the site, in the DOM as Chromium rendered it:
  - the page loaded (not Chromium's error page) and has the site's bar;
  - every <img> is a file of the site and decoded (naturalWidth > 0);
  - every link inside the site reaches a file of the site, and its #anchor an id of that page;
  - no TeX is left as text outside code (no $...$, no \\frac);
  - every <math> has a box, holds no <merror>, its TeX annotation is not shown, and its fractions,
    superscripts and subscripts are laid out as math (numerator above denominator...), no bar is
    drawn over only part of its base;
  - nothing is loaded from the network.
Every book page has its HTML page and every figure of book/figures/ is shown or linked on some
book page. A screenshot of one page (SHOT_PAGE, at SHOT_SIZE; fonts pinned to DejaVu by
tools/book_html.sh) is compared with tests/site/expected.png.

  check_site.py --work DIR        build the site into DIR/site (replaced) and check it
  check_site.py --site DIR        check a site already built (e.g. a scratch copy)
  check_site.py --work DIR --update-expected   also write the screenshot as the expected PNG
Exit 1 with one line per fault, each naming the page and the item."""
import argparse
import os
import re
import shutil
import subprocess
import sys
import time
from urllib.parse import unquote, urlsplit

root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
here = os.path.dirname(os.path.abspath(__file__))
expected_png = os.path.join(here, "expected.png")
SHOT_PAGE = "5.4-microfacets.html"  # a figure, inline math and a code block in the first screen
SHOT_SIZE = (1000, 1200)

try:
    import numpy as np
    from PIL import Image
    from selenium import webdriver
    from selenium.common.exceptions import WebDriverException
    from selenium.webdriver.chrome.service import Service
except ImportError as e:
    sys.exit(f"error: book.site needs python3-selenium, python3-pil and python3-numpy ({e}); "
             "run bash tools/setup.sh")

# Runs in the page; returns what Python checks.
PAGE_JS = r"""
const rect = e => { const r = e.getBoundingClientRect(); return [r.left, r.top, r.right, r.bottom]; };
const texOf = m => { const a = m.querySelector('annotation'); return a ? a.textContent : m.textContent; };
const out = {
  url: document.URL, title: document.title, bar: !!document.querySelector('nav.bar'),
  h1: !!document.querySelector('h1'),
  imgs: [...document.images].map(i => ({src: i.src, attr: i.getAttribute('src'),
                                          complete: i.complete, w: i.naturalWidth})),
  links: [...document.querySelectorAll('a[href]')].map(a => ({href: a.href, attr: a.getAttribute('href')})),
  ids: [...document.querySelectorAll('[id]')].map(e => e.id)
       .concat([...document.querySelectorAll('a[name]')].map(e => e.name)),
  resources: performance.getEntriesByType('resource').map(r => r.name),
  maths: [],
};
// Text as shown, without code, pre, math and the page's own scripts and styles.
const body = document.body.cloneNode(true);
body.querySelectorAll('code, pre, math, script, style').forEach(e => e.remove());
out.text = body.textContent;
document.querySelectorAll('math').forEach((m, k) => {
  const r = m.getBoundingClientRect();
  const bad = [];
  // Laid out as math: a fraction's numerator above its denominator, a superscript raised and
  // a subscript lowered against its base (as plain inline text they would sit side by side).
  m.querySelectorAll('mfrac').forEach(f => {
    if (f.children.length == 2 && rect(f.children[0])[3] > rect(f.children[1])[1] + 0.5)
      bad.push('a fraction is not stacked');
  });
  m.querySelectorAll('msup').forEach(s => {
    if (s.children.length == 2 && !(rect(s.children[1])[3] < rect(s.children[0])[3] - 0.5))
      bad.push('a superscript is not raised');
  });
  m.querySelectorAll('msub').forEach(s => {
    if (s.children.length == 2 && !(rect(s.children[1])[3] > rect(s.children[0])[3] + 0.5))
      bad.push('a subscript is not lowered');
  });
  // A bar (\bar, \overline: texmath writes U+00AF or U+203E) over more than one letter: the math
  // font has no wider variants of either, Chromium draws it at its width (over x^2 it covers
  // the x alone), so the book writes such a mean as \\langle...\\rangle. A letter is at most 2.5 bars wide.
  m.querySelectorAll('mover').forEach(o => {
    const s = o.children[1];
    if (o.children.length == 2 && s.localName == 'mo' && ['\u00af', '\u203e'].includes(s.textContent.trim())
        && o.children[0].getBoundingClientRect().width > 2.5 * s.getBoundingClientRect().width)
      bad.push('a bar does not reach over its base (write a mean of more than one letter as \\langle...\\rangle)');
  });
  const ann = m.querySelector('annotation');
  out.maths.push({k: k, tex: texOf(m), w: r.width, h: r.height,
                  merror: !!m.querySelector('merror'),
                  annotation_shown: !!ann && ann.getClientRects().length > 0,
                  // a MathML element Chromium does not lay out (MathML Core has no mfenced, menclose)
                  unknown: [...m.querySelectorAll('*')].map(e => e.localName)
                           .filter(n => ['mfenced', 'menclose', 'maction', 'mlabeledtr'].includes(n)),
                  bad: [...new Set(bad)]});
});
return out;
"""

# TeX that pandoc left as text: $...$ around something mathematical, $$, or a control word.
TEX_PATTERNS = [
    (re.compile(r"\$\$"), "$$"),
    (re.compile(r"\$[^$\n]*[\\^_{}][^$\n]*\$"), "$...$"),
    (re.compile(r"\\(?:[A-Za-z]{2,}|[,;!{}])"), "a TeX command"),
]


def path_of(url):
    """The local file of a file:// URL, and its fragment."""
    u = urlsplit(url)
    return unquote(u.path), unquote(u.fragment)


def build(work):
    site = os.path.join(work, "site")  # book_html.sh replaces it whole
    t = time.monotonic()
    subprocess.run(["bash", os.path.join(root, "tools", "book_html.sh"), site], check=True)
    print(f"book.site: built the site in {time.monotonic() - t:.1f} s")
    return site


def html_of(md):  # the same mapping as tools/book_html.sh
    p = md[:-3]
    if os.path.basename(p) == "README":
        p = p[: -len("README")] + "index"
    return p + ".html"


def driver_for():
    opts = webdriver.ChromeOptions()
    opts.binary_location = shutil.which("chromium") or "/usr/bin/chromium"
    # Headless needs no display; as root (CI) Chromium's sandbox cannot start; no /dev/shm
    # (a container's /dev/shm can be too small for it), no scrollbars in the screenshot.
    for a in ["--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
              "--force-device-scale-factor=1", "--hide-scrollbars",
              f"--window-size={SHOT_SIZE[0]},{SHOT_SIZE[1]}"]:
        opts.add_argument(a)
    service = Service(shutil.which("chromedriver") or "/usr/bin/chromedriver")
    try:
        d = webdriver.Chrome(service=service, options=opts)
    except WebDriverException as e:
        sys.exit(f"error: book.site: headless Chromium did not start ({e.msg}); "
                 "bash tools/setup.sh installs chromium and chromium-driver")
    d.set_page_load_timeout(30)
    # The viewport itself fixed (the window's size includes the browser's frame).
    d.execute_cdp_cmd("Emulation.setDeviceMetricsOverride",
                      {"width": SHOT_SIZE[0], "height": SHOT_SIZE[1], "deviceScaleFactor": 1, "mobile": False})
    return d


def compare(shot, expected, diff_out):
    """The fraction of 4x4 blocks whose mean grey level differs by more than TOL, at the best
    whole-page shift of up to SHIFT pixels. Averaging 4x4 blocks forgives the anti-aliasing of glyph
    edges and the shift a rounding of the page's origin; a moved line of text or figure, a reflowed
    paragraph or another font still fail (measured below TOL). Returns (fraction,
    message or None); on failure writes the difference of the blocks to diff_out."""
    a = np.asarray(Image.open(shot).convert("L"), dtype=np.float32)
    b = np.asarray(Image.open(expected).convert("L"), dtype=np.float32)
    if a.shape != b.shape:
        return 1.0, f"size {a.shape[1]}x{a.shape[0]}, expected {b.shape[1]}x{b.shape[0]}"
    def blocks(x):
        h, w = x.shape[0] // 4 * 4, x.shape[1] // 4 * 4
        return x[:h, :w].reshape(h // 4, 4, w // 4, 4).mean(axis=(1, 3))
    best = None
    s = SHIFT
    for dy in range(-s, s + 1):
        for dx in range(-s, s + 1):
            # b shifted by (dx, dy) against a, both cropped to the same inner window
            d = np.abs(blocks(a[s:-s, s:-s]) - blocks(b[s + dy:b.shape[0] - s + dy, s + dx:b.shape[1] - s + dx]))
            frac = float((d > TOL).mean())
            if best is None or frac < best[0]:
                best = (frac, d, dx, dy)
    frac, d, dx, dy = best
    if frac > MAX_FRAC:
        Image.fromarray(np.clip(d * 4, 0, 255).astype(np.uint8)).resize((d.shape[1] * 4, d.shape[0] * 4)).save(diff_out)
        return frac, f"{100 * frac:.2f}% of 4x4 blocks differ by more than {TOL} grey levels at the best " \
                     f"shift ({dx}, {dy}) px (allowed {100 * MAX_FRAC:.2f}%); difference image {diff_out}"
    return frac, None


# Measured against expected.png (1000x1200, 75,000 blocks): two runs on one machine 0.000%; the
# screenshot blurred by a Gaussian of 0.8 px 0.08%, its grey levels to the power 1.3 0.13%, shifted
# by 1 or 2 px 0.000% (all as other anti-aliasing would do); the figure moved 8 px down 2.6%, the
# last lines 30 px down 2.9%, two words added to the figure's caption 0.76%, Chromium without
# subpixel glyph positioning (lines drift by up to 3 px) 5.9%.
TOL = 24          # grey levels (0..255) of a 4x4 block's mean
MAX_FRAC = 0.003  # 0.3% of the blocks
SHIFT = 2         # pixels, either way, in x and y


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    g = ap.add_mutually_exclusive_group(required=True)
    g.add_argument("--work", help="build the site into WORK/site and check it")
    g.add_argument("--site", help="check this built site")
    ap.add_argument("--update-expected", action="store_true", help=f"write the screenshot to {expected_png}")
    args = ap.parse_args()
    t0 = time.monotonic()
    site = os.path.abspath(build(args.work) if args.work else args.site)
    work = os.path.abspath(args.work) if args.work else os.path.dirname(site)  # screenshots go here
    faults = []

    def fault(page, what):
        faults.append(f"{page}: {what}")

    book = os.path.join(root, "book")
    pages = sorted(os.path.relpath(os.path.join(dp, f), site)
                   for dp, _, fs in os.walk(site) for f in fs if f.endswith(".html"))
    book_pages = set()  # the pages made from book/**/*.md (the others: contents, folder listings)
    for dp, _, fs in os.walk(book):
        for f in fs:
            if f.endswith(".md"):
                md = os.path.relpath(os.path.join(dp, f), book)
                book_pages.add(html_of(md))
                if not os.path.isfile(os.path.join(site, html_of(md))):
                    fault(html_of(md), f"missing: no page for book/{md}")

    d = driver_for()
    seen = {}      # page -> its ids
    anchors = []   # (page, link, target page, fragment)
    shown = set()  # image files shown
    linked = set()  # files linked from book pages
    nmath = 0
    try:
        for page in pages:
            url = "file://" + os.path.join(site, page)
            try:
                d.get(url)
                r = d.execute_script(PAGE_JS)
            except WebDriverException as e:
                fault(page, f"did not load: {e.msg}")
                continue
            if not r["url"].startswith("file://") or not (r["h1"] and r["title"]):
                fault(page, f"did not load (Chromium shows {r['url']!r}, title {r['title']!r})")
                continue
            if not r["bar"] and page in book_pages:
                fault(page, "has no navigation bar")
            seen[page] = set(r["ids"])
            nmath += len(r["maths"])
            for im in r["imgs"]:
                f, _ = path_of(im["src"])
                if not im["src"].startswith("file://") or not f.startswith(site + "/"):
                    fault(page, f"image {im['attr']} is not a file of the site")
                elif not im["complete"] or im["w"] == 0:
                    fault(page, f"image {im['attr']} did not load" +
                          ("" if os.path.isfile(f) else f" ({os.path.relpath(f, site)} does not exist)"))
                else:
                    shown.add(os.path.relpath(f, site))
            for ln in r["links"]:
                scheme = urlsplit(ln["href"]).scheme
                if scheme in ("http", "https", "mailto"):
                    continue  # outside the site: not checked offline
                if scheme != "file":
                    fault(page, f"link {ln['attr']}: unexpected target {ln['href']}")
                    continue
                f, frag = path_of(ln["href"])
                rel = os.path.relpath(f, site)
                if not f.startswith(site + "/"):
                    fault(page, f"link {ln['attr']} leaves the site ({f})")
                elif os.path.isdir(f):
                    fault(page, f"link {ln['attr']} is a folder ({rel}/), not a page")
                elif not os.path.isfile(f):
                    fault(page, f"link {ln['attr']}: {rel} does not exist")
                elif page in book_pages:  # not the folder listings, which link every file
                    linked.add(rel)
                if frag and os.path.isfile(f):
                    if not rel.endswith(".html"):
                        fault(page, f"link {ln['attr']}: an anchor into {rel}, which is not a page")
                    else:
                        anchors.append((page, ln["attr"], rel, frag))
            for res in r["resources"]:
                if not res.startswith("file://"):
                    fault(page, f"loads {res} from outside the site")
            for pat, what in TEX_PATTERNS:
                for m in pat.finditer(r["text"]):
                    ctx = r["text"][max(0, m.start() - 30): m.end() + 30].replace("\n", " ")
                    fault(page, f"raw TeX ({what}) in the text: ...{ctx}...")
            for m in r["maths"]:
                name = f"formula {m['k'] + 1} ${m['tex'].strip()[:70]}$"
                if m["w"] <= 0 or m["h"] <= 0:
                    fault(page, f"{name} has no box ({m['w']:.0f}x{m['h']:.0f} px)")
                if m["merror"]:
                    fault(page, f"{name}: pandoc could not convert it (<merror>)")
                if m["annotation_shown"]:
                    fault(page, f"{name}: its TeX source is shown (MathML not rendered)")
                for u in m["unknown"]:
                    fault(page, f"{name}: <{u}> is not MathML Core, Chromium does not lay it out")
                for b in m["bad"]:
                    fault(page, f"{name}: {b}")
        for page, attr, target, frag in anchors:
            if target in seen and frag not in seen[target]:
                fault(page, f"link {attr}: no anchor #{frag} in {target}")
        figures = os.path.join(site, "figures")
        for f in sorted(os.listdir(figures)) if os.path.isdir(figures) else []:
            if f.endswith(".png") and f"figures/{f}" not in shown | linked:
                fault(f"figures/{f}", "is shown or linked on no page")

        # The look of one page.
        shot = os.path.join(work, "screenshot.png")
        d.get("file://" + os.path.join(site, SHOT_PAGE))
        d.execute_script("return document.fonts.ready")
        time.sleep(0.2)
        d.save_screenshot(shot)
        if args.update_expected:
            shutil.copyfile(shot, expected_png)
            print(f"book.site: wrote {expected_png}")
        frac, msg = compare(shot, expected_png, os.path.join(work, "screenshot-diff.png"))
        if msg:
            fault(SHOT_PAGE, f"the screenshot {shot} does not look like {os.path.relpath(expected_png, root)}: "
                  f"{msg} (if the page changed on purpose: check_site.py --work DIR --update-expected, "
                  "and look at the new PNG)")
        else:
            print(f"book.site: screenshot of {SHOT_PAGE} matches ({100 * frac:.3f}% of blocks differ)")
    finally:
        d.quit()

    print(f"book.site: {len(pages)} pages, {nmath} formulas, {len(anchors)} anchored links, "
          f"{len(shown)} images shown, "
          f"{time.monotonic() - t0:.1f} s")
    if faults:
        for f in faults:
            print(f"error: {f}", file=sys.stderr)
        print(f"book.site: {len(faults)} fault(s)", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
