#!/usr/bin/env bash
# Tests that `run --report` of configs/demo.yaml renders in a real headless browser
# (Debian's chromium, installed by `make test`): the DOM has the metrics table and an
# <svg>, and the console shows no error (with --enable-logging=stderr chromium prints the
# page's console messages as CONSOLE lines; any "Uncaught" or console message fails).
# The interactive trace (dygraphs, inlined): the page names no URL to fetch, the graph
# draws its x axis, and a scripted zoom (the page's copy with a script appended that zooms
# to the first quarter) changes the x range and the x axis' labels.
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
chrome() {  # chrome OPTIONS... (the last: the page)
  HOME="$work" timeout -k 10 120 "$browser" --headless=new --no-sandbox --disable-gpu --enable-logging=stderr --v=0 \
    --user-data-dir="$work/profile" "$@"
}
chrome --dump-dom "file://$work/demo.html" >"$work/dom.html" 2>"$work/console.log" || { echo "report_in_browser: chromium failed"; cat "$work/console.log"; exit 1; }
bad=0
fail() { echo "report_in_browser: $*"; bad=1; }
grep -q '<td>peak_ratio</td>' "$work/dom.html" || fail "no metrics table row peak_ratio in the DOM"
grep -q '<table>' "$work/dom.html" || fail "no <table> in the DOM"
grep -q '<svg' "$work/dom.html" || fail "no <svg> in the DOM"
grep -q '<h2>Effective scenario</h2>' "$work/dom.html" || fail "no effective scenario section in the DOM"
# The page logs nothing: any console message (chromium 156 logs them as INFO:CONSOLE:N,
# console.error included) is an error of the page.
if grep -E 'Uncaught|CONSOLE' "$work/console.log"; then
  fail "the console shows a message (above)"
fi
# One file: no element's src= or href= naming anything to load (the library is inlined;
# its code sets data: icons, not attributes of the page).
if grep -Eo '[[:space:]](src|href)="[^"#][^"]*"' "$work/demo.html" | head -3 | grep .; then
  fail "the page names a resource to fetch (above)"
fi
x_labels() { grep -o 'dygraph-axis-label-x">[^<]*' "$1" | sed 's/.*>//' | tr '\n' ' '; }
before=$(x_labels "$work/dom.html")
[ -n "$before" ] || fail "the interactive trace drew no x axis labels"
sed 's|</body>|<script>var g = window.shapebenchTraces[0]; var full = g.xAxisRange(); g.updateOptions({dateWindow: [full[0], full[0] + (full[1] - full[0]) / 4]}); var zoomed = g.xAxisRange(); document.body.setAttribute("data-zoomed", String(zoomed[0] === full[0] \&\& zoomed[1] < full[1]));</script></body>|' \
  "$work/demo.html" >"$work/zoom.html"
chrome --dump-dom "file://$work/zoom.html" >"$work/zoom_dom.html" 2>"$work/zoom_console.log" || fail "chromium failed on the zoomed page"
grep -q 'data-zoomed="true"' "$work/zoom_dom.html" || fail "the scripted zoom did not narrow the x range"
after=$(x_labels "$work/zoom_dom.html")
[ -n "$after" ] && [ "$after" != "$before" ] || fail "the x axis labels did not change with the zoom ($before / $after)"
if grep -E 'Uncaught|CONSOLE' "$work/zoom_console.log"; then
  fail "the zoomed page's console shows a message (above)"
fi
chrome --screenshot="$work/report.png" --window-size=1200,1600 "file://$work/demo.html" >/dev/null 2>"$work/shot.log" ||
  fail "chromium --screenshot failed"
[ -s "$work/report.png" ] || fail "no screenshot written"
[ "$bad" = 0 ] && echo "report_in_browser: DOM has the metrics table and the plot; no console error; zoom: $before-> $after"
exit "$bad"
