#!/usr/bin/env bash
# Screenshots for docs/views.md: docs/img/bode_page.png, `bode --report` of the shipped
# measured machine rendered by headless chromium (as tests/report_in_browser_test.sh renders a
# report); docs/img/frf_overlay.png, its `bode --out` frf.png (measured FRF under the
# identified model); docs/img/command_plot.png, `run --out`'s command.png of the demo
# (method 1 against unshaped); docs/img/interactive_trace_zoomed.png, the demo's `run
# --report` page with a script appended that zooms its interactive trace to 0.6-0.9 s (the
# end of the motion), as a user would by dragging.
#   scripts/view_screenshots.sh build-dev/shapebench
set -euo pipefail
bin=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
top=$(cd "$(dirname "$0")/.." && pwd)
browser=$(command -v chromium || command -v chromium-browser || true)
[ -n "$browser" ] || { echo "view_screenshots: chromium is not installed (apt-get install chromium)" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$top"
"$bin" bode configs/scenarios/measured_frf.yaml --out "$work/bode" --report "$work/bode.html" >/dev/null
"$bin" run configs/demo.yaml --out "$work/run" --report "$work/run.html" >/dev/null 2>&1
# The trace's section alone (the others hidden), zoomed once drawn.
sed -e 's|</head>|<style>h1, .subtitle, section:not(:has(#trace)) { display: none }</style></head>|' \
  -e 's|</body>|<script>window.shapebenchTraces[0].updateOptions({dateWindow: [0.6, 0.9]});</script></body>|' \
  "$work/run.html" >"$work/zoom.html"
shot() {  # PAGE PNG WIDTH,HEIGHT
  HOME="$work" timeout -k 10 120 "$browser" --headless=new --no-sandbox --disable-gpu --hide-scrollbars \
    --user-data-dir="$work/profile" --virtual-time-budget=3000 --screenshot="$top/docs/img/$2" --window-size="$3" "file://$1" >/dev/null 2>&1
  [ -s "$top/docs/img/$2" ] || { echo "view_screenshots: no screenshot $2" >&2; exit 1; }
  echo "wrote docs/img/$2"
}
shot "$work/bode.html" bode_page.png 1000,1450
shot "$work/zoom.html" interactive_trace_zoomed.png 1100,560
cp "$work/bode/frf.png" "$top/docs/img/frf_overlay.png" && echo "wrote docs/img/frf_overlay.png"
cp "$work/run/command.png" "$top/docs/img/command_plot.png" && echo "wrote docs/img/command_plot.png"
