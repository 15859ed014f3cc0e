# SPDX-License-Identifier: MIT
# Headless Chromium for the render tests (tests/report/render_report.sh, tests/doc/render_reference.sh),
# sourced by them with `.`: the skip when Chromium is missing, a throw-away profile per run with
# no network services and no first-run UI, and the console-message detector with its canary.
# The sourcing script sets WORK (an existing folder for logs) before calling check_console_detector.
CHROMIUM=${CHROMIUM:-/usr/bin/chromium}

if [ ! -x "$CHROMIUM" ]; then
  echo "SKIPPED: $CHROMIUM not found; install Debian's chromium (apt-get install -y chromium) to run this test"
  exit 77
fi

fail() { echo "FAIL: $*"; exit 1; }

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
check_console_detector() {
  printf '<!DOCTYPE html><html><body><script>console.error("smi-canary")</script></body></html>\n' > "$WORK/canary.html"
  chrome --dump-dom "file://$WORK/canary.html" > "$WORK/canary.dom" 2> "$WORK/canary.log"
  console_lines "$WORK/canary.log" | grep -q smi-canary ||
    fail "this Chromium does not log console messages as expected (see $WORK/canary.log); the checks below would prove nothing"
}
