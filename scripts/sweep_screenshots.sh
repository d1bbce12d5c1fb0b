#!/usr/bin/env bash
# Screenshots for docs/sweeps.md, by headless chromium (as tests/report_in_browser_test.sh
# renders a report): docs/img/sweep_bands.png, `sweep --report` of a sweep whose series are
# whole pattern mappings (long keys) with its robust bands; docs/img/check_sweep.png,
# `check --report` of the shipped robust-band sweep (a line per check, the failing points
# folded).
#   scripts/sweep_screenshots.sh build-dev/shapebench
set -euo pipefail
bin=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
top=$(cd "$(dirname "$0")/.." && pwd)
browser=$(command -v chromium || command -v chromium-browser || true)
[ -n "$browser" ] || { echo "sweep_screenshots: chromium is not installed (apt-get install chromium)" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$top"
cat >"$work/long_keys.yaml" <<YAML
name: long_keys
base: $top/configs/scenarios/sdof_method1.yaml
grid:
  controller.pattern:
    - {method: zv, mode: both, frequency_hz: 25, design_damping_ratio: 0.02}
    - {method: zvd, mode: both, frequency_hz: 25, design_damping_ratio: 0.02}
    - {method: ei, mode: both, frequency_hz: 25, design_damping_ratio: 0.02, vibration_tolerance: 0.02}
  machine.modes[0].damping_ratio: [0.02]
  machine.modes[0].frequency_hz: {from: 15, to: 35, steps: 201}
metrics: [residual_ratio, pattern_frequency_hz]
plots:
  - {metric: residual_ratio, x: "machine.modes[0].frequency_hz", series: controller.pattern, log: true}
checks:
  residual_ratio: {max: 0.05}
YAML
"$bin" sweep "$work/long_keys.yaml" --out "$work/out" --no-sync --report "$work/sweep.html" >/dev/null
"$bin" check configs/sweeps/robust_bands.yaml --report "$work/check.html" >/dev/null || true  # exit 1: points fail
shot() {  # PAGE PNG HEIGHT
  HOME="$work" timeout -k 10 120 "$browser" --headless=new --no-sandbox --disable-gpu --hide-scrollbars \
    --user-data-dir="$work/profile" --screenshot="$2" --window-size="1100,$3" "file://$1" >/dev/null 2>&1
  [ -s "$2" ] || { echo "sweep_screenshots: no screenshot $2" >&2; exit 1; }
  echo "wrote $2"
}
shot "$work/sweep.html" "$top/docs/img/sweep_bands.png" 1150
shot "$work/check.html" "$top/docs/img/check_sweep.png" 320
