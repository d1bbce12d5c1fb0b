#!/usr/bin/env bash
# The golden set, written by BINARY into OUT_DIR: the `run --json` metrics of every shipped
# scenario, the results.csv of the shipped sweeps, and the `--json` answers of identify,
# recommend, compare, check and modes and the text of pattern on shipped inputs. Refactors
# must leave it byte-identical (ctest `golden_set_is_unchanged` compares a fresh set with
# tests/golden/). A change that means to move a number regenerates it on purpose and says
# why in its commit:
#   scripts/golden.sh build/shapebench tests/golden
set -euo pipefail
bin=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
out=$2
top=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$out"
out=$(cd "$out" && pwd)
# Paths in the outputs are written relative to the top folder (the same bytes from any clone).
cd "$top"
for f in configs/demo.yaml configs/scenarios/*.yaml; do
  name=$(basename "$f" .yaml)
  "$bin" run "$f" --json > "$out/$name.json"
done
for f in configs/sweeps/*.yaml; do
  name=$(basename "$f" .yaml)
  tmp=$(mktemp -d)
  "$bin" sweep "$f" --jobs 2 --out "$tmp/out" > /dev/null
  cp "$tmp/out/results.csv" "$out/sweep_$name.csv"
  rm -rf "$tmp"
done
# The other commands' answers. A command that exits 1 (a failed check or gate) still
# answers: its exit code is kept with the output.
answer() {  # NAME COMMAND...: stdout into NAME, then "exit N"
  local name=$1
  shift
  local code=0
  "$@" > "$out/$name" 2> /dev/null || code=$?
  echo "exit $code" >> "$out/$name"
}
answer identify_column_y.json "$bin" identify configs/measurements/column_y_accelerance.uff --json
answer recommend_accel_x.json "$bin" recommend configs/measurements/accel_x.csv --json
answer compare_demo_unshaped.json "$bin" compare configs/demo.yaml \
  --baseline-set controller.pattern.method=none --json
answer compare_method1_method2.json "$bin" compare configs/scenarios/method1.yaml \
  configs/scenarios/method2.yaml --json
answer compare_sweep_natural_period.json "$bin" compare configs/sweeps/natural_period.yaml \
  --candidate-set "machine.modes[0].damping_ratio=0.02" --jobs 2 --json
answer check_scenarios.json "$bin" check configs/scenarios/*.yaml --json
answer check_sweep_natural_period.json "$bin" check configs/sweeps/natural_period.yaml --jobs 2 --json
for f in configs/machines/*.yaml configs/scenarios/fe_modes.yaml configs/scenarios/measured_frf.yaml; do
  answer "modes_$(basename "$f" .yaml).json" "$bin" modes "$f" --json
done
for f in configs/scenarios/*.yaml; do
  answer "pattern_$(basename "$f" .yaml).txt" "$bin" pattern "$f"
done
