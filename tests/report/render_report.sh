#!/bin/sh
# SPDX-License-Identifier: MIT
# Renders the demo report in headless Chromium and checks that it loads with no console
# message, fetches nothing from the network, lays out its charts, and looks like a page (the
# screenshot is kept as WORKDIR/report.png for people to look at).
#   render_report.sh SMI_LUA DEMO_SCRIPT WORKDIR [TITLE]
# DEMO_SCRIPT may also be an existing report.html (made by another test), which is then checked
# as it is; TITLE is a text the rendered page must contain (default: the demo's title).
# Exit 77 (ctest: skipped) when /usr/bin/chromium is missing; 1 with a message on any failure.
set -u
SMI_LUA=$1
DEMO=$2
WORK=$3
TITLE=${4:-Demonstration study}
. "$(dirname "$0")/../chromium.sh"  # CHROMIUM, the skip, fail, chrome, console_lines, check_console_detector

rm -rf "$WORK"
mkdir -p "$WORK"
case "$DEMO" in
  *.html)
    REPORT=$DEMO
    [ -s "$REPORT" ] || fail "no $REPORT (the test that makes it must run first)"
    ;;
  *)
    OUT="$WORK/out"
    "$SMI_LUA" --quiet --out "$OUT" "$DEMO" || fail "the demo script failed"
    REPORT="$OUT/report.html"
    [ -s "$REPORT" ] || fail "no $REPORT"
    [ -s "$OUT/results.json" ] || fail "no $OUT/results.json"
    ;;
esac

# Self-contained: no script, no remote resource (xmlns declarations are names, not fetches).
if grep -Eiq '<script|<link|<iframe|<img|(src|href)="[a-z]+://|url\(["'"'"']?[a-zA-Z]+:' "$REPORT"; then
  grep -Eion '<script|<link|<iframe|<img|(src|href)="[a-z]+://|url\(["'"'"']?[a-zA-Z]+:' "$REPORT" | head -5
  fail "the report refers to scripts or outside resources"
fi

check_console_detector

chrome --dump-dom "file://$REPORT" > "$WORK/report.dom" 2> "$WORK/dom.log" || fail "chromium --dump-dom failed (see $WORK/dom.log)"
if console_lines "$WORK/dom.log"; then fail "console messages while loading the report (above)"; fi
svgs=$(grep -o '<svg' "$WORK/report.dom" | wc -l)
[ "$svgs" -ge 8 ] || fail "the rendered DOM holds $svgs <svg> elements, expected at least 8"
grep -qF "$TITLE" "$WORK/report.dom" || fail "'$TITLE' is missing from the rendered DOM"

chrome --window-size=1100,5600 --screenshot="$WORK/report.png" "file://$REPORT" > /dev/null 2> "$WORK/shot.log" \
  || fail "chromium --screenshot failed (see $WORK/shot.log)"
if console_lines "$WORK/shot.log"; then fail "console messages while taking the screenshot (above)"; fi
size=$(wc -c < "$WORK/report.png")
# a blank page compresses to a few kB; the demo's charts and tables take hundreds
[ "$size" -gt 100000 ] || fail "the screenshot is only $size bytes: the page looks empty"
echo "OK: $svgs charts rendered with no console message; screenshot $WORK/report.png ($size bytes)"
