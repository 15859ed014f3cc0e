#!/bin/sh
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
CHROMIUM=${CHROMIUM:-/usr/bin/chromium}

if [ ! -x "$CHROMIUM" ]; then
  echo "SKIPPED: $CHROMIUM not found; install Debian's chromium (apt-get install -y chromium) to run this test"
  exit 77
fi

fail() { echo "FAIL: $*"; exit 1; }

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

# One throw-away profile per run; no network services, no first-run UI.
chrome() {
  profile=$(mktemp -d)
  "$CHROMIUM" --headless --no-sandbox --disable-gpu --disable-background-networking \
    --disable-component-update --disable-sync --no-first-run --hide-scrollbars \
    --user-data-dir="$profile" --enable-logging=stderr --v=0 "$@"
  rc=$?
  rm -rf "$profile"
  return $rc
}

# Console messages look like "[...:INFO:CONSOLE:1] "text", source: ..." (older builds: CONSOLE(1)).
console_lines() { grep -E ':CONSOLE[:(]|Page load failed|Uncaught' "$1"; }

# The detector must see a console error on a page that has one, or its silence means nothing.
CANARY="$WORK/canary.html"
printf '<!DOCTYPE html><html><body><script>console.error("smi-canary")</script></body></html>\n' > "$CANARY"
chrome --dump-dom "file://$CANARY" > "$WORK/canary.dom" 2> "$WORK/canary.log"
console_lines "$WORK/canary.log" | grep -q smi-canary || fail "this Chromium does not log console messages as expected (see $WORK/canary.log); the check below would prove nothing"

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
