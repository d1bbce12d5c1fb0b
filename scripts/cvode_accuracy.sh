#!/usr/bin/env bash
# scripts/cvode_accuracy.sh BINARY: the CVODE accuracy table of docs/accuracy.md. For each
# case (shipped scenarios, the servo drive, a stiff 1e6 Hz mode), each lmm and each rtol:
# the worst difference of peak_ratio, residual_ratio and cruise_residual_ratio from the exact
# path's, and whether the cross-check refuses the run (R) under the default
# integrator.cross_check: refuse. The metrics of refused runs come from cross_check: warn.
set -euo pipefail
bin=${1:-build/shapebench}
cd "$(dirname "$0")/.."
rtols=(1e-6 3e-7 1e-7 3e-8 1e-8 1e-9 1e-10)
cases=(
  "demo|configs/demo.yaml|"
  "method1|configs/scenarios/method1.yaml|"
  "method3_mode_start|configs/scenarios/method3_mode_start.yaml|"
  "exponential (0.1 ms)|configs/scenarios/exponential.yaml|"
  "fig2_pulse|configs/scenarios/fig2_pulse.yaml|"
  "long_step|configs/scenarios/long_step.yaml|"
  "pocket_gcode|configs/scenarios/pocket_gcode.yaml|"
  "stroke_end|configs/scenarios/stroke_end.yaml|"
  "pocket_corner, servo|configs/scenarios/pocket_corner.yaml|--set drive.type=servo"
  "1e6 Hz mode, 1 ms|tests/bench/data/accuracy/stiff_mode.yaml|"
)
worst() {  # exact.json cvode.json -> worst ratio difference
  python3 - "$1" "$2" <<'PY'
import json, sys
e = json.load(open(sys.argv[1])); c = json.load(open(sys.argv[2]))
w = 0.0
for k in ("peak_ratio", "residual_ratio", "cruise_residual_ratio"):
    if e.get(k) is not None and c.get(k) is not None:
        w = max(w, abs(e[k] - c[k]))
print("%.1e" % w)
PY
}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
printf '| case | lmm |'; for r in "${rtols[@]}"; do printf ' %s |' "$r"; done; echo
printf '|---|---|'; for r in "${rtols[@]}"; do printf -- '---|'; done; echo
for c in "${cases[@]}"; do
  IFS='|' read -r name file extra <<<"$c"
  # shellcheck disable=SC2086
  "$bin" run "$file" $extra --set integrator.method=exact --json >"$tmp/exact.json"
  for lmm in adams bdf; do
    printf '| %s | %s |' "$name" "$lmm"
    for r in "${rtols[@]}"; do
      # shellcheck disable=SC2086
      if timeout 60 "$bin" run "$file" $extra --set integrator.method=cvode --set integrator.rtol="$r" \
           --set integrator.lmm=$lmm --set integrator.cross_check=warn --json >"$tmp/cvode.json" 2>"$tmp/err"; then
        cell=$(worst "$tmp/exact.json" "$tmp/cvode.json")
        grep -q "disagrees with the exact\|accuracy on this plant is unknown" "$tmp/err" && cell="$cell R"
      else
        cell="fails ($(grep -o 'CV_[A-Z_]*' "$tmp/err" | head -1 || true))"
      fi
      printf ' %s |' "$cell"
    done
    echo
  done
done
