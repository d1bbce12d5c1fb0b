#!/usr/bin/env bash
# The golden set: the `run --json` metrics of every shipped scenario and the results.csv of
# the shipped sweeps, written by BINARY into OUT_DIR. Refactors must leave it byte-identical
# (ctest `golden_set_is_unchanged` compares a fresh set with tests/golden/). A change that
# means to move a number regenerates it on purpose and says why in its commit:
#   scripts/golden.sh build/shapebench tests/golden
set -euo pipefail
bin=$1
out=$2
top=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$out"
for f in "$top"/configs/demo.yaml "$top"/configs/scenarios/*.yaml; do
  name=$(basename "$f" .yaml)
  "$bin" run "$f" --json > "$out/$name.json"
done
for f in "$top"/configs/sweeps/*.yaml; do
  name=$(basename "$f" .yaml)
  tmp=$(mktemp -d)
  "$bin" sweep "$f" --jobs 2 --out "$tmp/out" > /dev/null
  cp "$tmp/out/results.csv" "$out/sweep_$name.csv"
  rm -rf "$tmp"
done
