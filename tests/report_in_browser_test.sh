#!/usr/bin/env bash
# Tests that `run --report` of configs/demo.yaml renders in a real headless browser
# (Debian's chromium, installed by `make test`): the DOM has the metrics table and an
# <svg>, and the console shows no error (with --enable-logging=stderr chromium prints the
# page's console messages as CONSOLE lines; any "Uncaught" or console message fails).
#   tests/report_in_browser_test.sh SHAPEBENCH ROOT
set -u
bin=$1
root=$2
browser=$(command -v chromium || command -v chromium-browser || true)
if [ -z "$browser" ]; then
  # `make test` installs chromium (Makefile PACKAGES): its absence is a broken setup.
  echo "report_in_browser: chromium is not installed (make test installs it; apt-get install chromium)"
  exit 1
fi
work=$(mktemp -d) || exit 1
trap 'rm -rf "$work"' EXIT
cd "$root" || exit 1
"$bin" run configs/demo.yaml --report "$work/demo.html" >/dev/null || { echo "report_in_browser: run --report failed"; exit 1; }
chrome() {
  HOME="$work" timeout -k 10 120 "$browser" --headless=new --no-sandbox --disable-gpu --enable-logging=stderr --v=0 \
    --user-data-dir="$work/profile" "$@" "file://$work/demo.html"
}
chrome --dump-dom >"$work/dom.html" 2>"$work/console.log" || { echo "report_in_browser: chromium failed"; cat "$work/console.log"; exit 1; }
bad=0
fail() { echo "report_in_browser: $*"; bad=1; }
grep -q '<td>peak_ratio</td>' "$work/dom.html" || fail "no metrics table row peak_ratio in the DOM"
grep -q '<table>' "$work/dom.html" || fail "no <table> in the DOM"
grep -q '<svg' "$work/dom.html" || fail "no <svg> in the DOM"
grep -q '<h2>Effective scenario</h2>' "$work/dom.html" || fail "no effective scenario section in the DOM"
# The page has no script: any console message (chromium 156 logs them as INFO:CONSOLE:N,
# console.error included) is an error of the page.
if grep -E 'Uncaught|CONSOLE' "$work/console.log"; then
  fail "the console shows a message (above)"
fi
chrome --screenshot="$work/report.png" --window-size=1200,1600 >/dev/null 2>"$work/shot.log" ||
  fail "chromium --screenshot failed"
[ -s "$work/report.png" ] || fail "no screenshot written"
[ "$bad" = 0 ] && echo "report_in_browser: DOM has the metrics table and the plot; no console error"
exit "$bad"
