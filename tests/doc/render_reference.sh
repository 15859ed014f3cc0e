#!/bin/sh
# SPDX-License-Identifier: MIT
# Generates the reference (smi-lua doc --html) and opens it in headless Chromium: no console
# message, nothing fetched from the network, the search (plain JavaScript over the index embedded
# in the page) finds entries, and pages look like pages. Screenshots are kept in WORKDIR
# (reference-search.png, reference-kde.png) for people to look at, as the report's is.
#   render_reference.sh SMI_LUA WORKDIR
# Exit 77 (ctest: skipped) when /usr/bin/chromium is missing; 1 with a message on any failure.
set -u
SMI_LUA=$1
WORK=$2
. "$(dirname "$0")/../chromium.sh"  # CHROMIUM, the skip, fail, chrome, console_lines, check_console_detector

rm -rf "$WORK"
mkdir -p "$WORK"
WORK=$(cd "$WORK" && pwd)
REF="$WORK/reference"
"$SMI_LUA" doc --html "$REF" > "$WORK/doc.log" 2>&1 || { cat "$WORK/doc.log"; fail "smi-lua doc --html failed"; }
[ -s "$REF/index.html" ] || fail "no $REF/index.html"
pages=$(ls "$REF"/*.html | wc -l)
[ "$pages" -ge 20 ] || fail "only $pages pages in $REF"

# Self-contained: inline script and style only; no external script, stylesheet, frame, image or URL.
if grep -Eiq '<script[^>]+src|<link|<iframe|<img|(src|href)="[a-z]+://|url\(["'"'"']?[a-zA-Z]+:|fetch\(|XMLHttpRequest' "$REF"/*.html; then
  grep -Eion '<script[^>]+src|<link|<iframe|<img|(src|href)="[a-z]+://|url\(["'"'"']?[a-zA-Z]+:|fetch\(|XMLHttpRequest' "$REF"/*.html | head -5
  fail "the reference refers to outside resources"
fi
# Every link between pages points at a page that exists.
for target in $(grep -oh 'href="[^"#]*' "$REF"/*.html | sed 's/href="//' | sort -u); do
  [ -z "$target" ] || [ -f "$REF/$target" ] || fail "a link points at $target, which was not written"
done

check_console_detector

# The search runs on load with ?q=: its results are in the DOM only if the script ran.
chrome --dump-dom "file://$REF/index.html?q=bandwidth" > "$WORK/search.dom" 2> "$WORK/search.log" || fail "chromium --dump-dom failed"
if console_lines "$WORK/search.log"; then fail "console messages while loading index.html (above)"; fi
grep -q 'entries mention' "$WORK/search.dom" || fail "the search produced no results list (see $WORK/search.dom)"
grep -q 'href="smi.kde_ebd.html#smi.kde_ebd"' "$WORK/search.dom" || fail "searching 'bandwidth' did not find smi.kde_ebd"
# Several words: entries holding all of them, in any order ("prior weight" must find the prior options).
chrome --dump-dom "file://$REF/index.html?q=weight%20prior" > "$WORK/search2.dom" 2> "$WORK/search2.log" || fail "chromium --dump-dom failed"
grep -q 'href="smi.calibrate.html#smi.calibrate"' "$WORK/search2.dom" || fail "searching 'weight prior' did not find smi.calibrate"

# Pages load without a console message. All pages share one template and script; a Chromium
# start costs about 2.5 s, so the largest pages stand for the rest (every page: 90 s).
for page in "$REF/smi.calibrate.html" "$REF/smi.report.html" "$REF/smi.kde_ebd.html" "$REF/smi.vec.html"; do
  chrome --dump-dom "file://$page" > "$WORK/page.dom" 2> "$WORK/page.log" || fail "chromium failed on $page"
  if console_lines "$WORK/page.log"; then fail "console messages while loading $page (above)"; fi
done
grep -q '<pre class="out">' "$REF/smi.kde_ebd.html" || fail "smi.kde_ebd.html shows no example output"

chrome --window-size=1100,900 --screenshot="$WORK/reference-search.png" "file://$REF/index.html?q=bandwidth" > /dev/null 2> "$WORK/shot.log" \
  || fail "chromium --screenshot failed (see $WORK/shot.log)"
chrome --window-size=1100,1400 --screenshot="$WORK/reference-kde.png" "file://$REF/smi.kde_ebd.html" > /dev/null 2>> "$WORK/shot.log" \
  || fail "chromium --screenshot failed (see $WORK/shot.log)"
if console_lines "$WORK/shot.log"; then fail "console messages while taking the screenshots (above)"; fi
size=$(wc -c < "$WORK/reference-search.png")
[ "$size" -gt 50000 ] || fail "the screenshot is only $size bytes: the page looks empty"
echo "OK: $pages pages written, index and 4 pages load with no console message; search works; screenshots $WORK/reference-search.png, $WORK/reference-kde.png"
