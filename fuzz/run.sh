#!/usr/bin/env bash
# fuzz/run.sh BUILD_DIR SECONDS TARGET...: runs each libFuzzer target for SECONDS on a
# working corpus in BUILD_DIR/corpus/TARGET seeded from fuzz/corpus/NAME, with a
# dictionary of the input's words (fuzz/NAME.dict: gcode, manifest, rows; else
# fuzz/yaml.dict); new inputs land in the working corpus, the repository's seeds stay as
# they are. The targets' scratch directories go into one of this run (TMPDIR), removed at
# the end (libFuzzer's exits skip the targets' own clean-up), on /dev/shm when there is
# one: the output-directory readers write and fsync files for every input. Before that
# it replays fuzz/regressions/NAME. A crash, a hang (-timeout, 10 s an input), a memory blow-up
# (-rss_limit_mb) or a sanitizer report stops the target with its input in
# BUILD_DIR/artifacts/ and makes this script fail. Prints the executions of each target.
set -euo pipefail
cd "$(dirname "$0")/.."
build=$1 seconds=$2
shift 2
mkdir -p "$build/artifacts"
tmp_root=${TMPDIR:-/tmp}
[ -z "${TMPDIR:-}" ] && [ -d /dev/shm ] && [ -w /dev/shm ] && tmp_root=/dev/shm
scratch=$(mktemp -d "$tmp_root/shapebench_fuzz_run.XXXXXX")
trap 'rm -rf "$scratch"' EXIT
export TMPDIR=$scratch
summary=()
status=0
for target in "$@"; do
  name=${target#fuzz_}
  work="$build/corpus/$name"
  log="$build/$target.log"
  mkdir -p "$work"
  regressions=(fuzz/regressions/"$name"/*)
  if [ -e "${regressions[0]}" ]; then
    "$build/fuzz/$target" -runs=1 "${regressions[@]}" >/dev/null 2>"$log.regressions" ||
      { echo "$target: a regression input fails again (see $log.regressions)"; status=1; continue; }
  fi
  dict=fuzz/yaml.dict
  [ -f "fuzz/$name.dict" ] && dict=fuzz/$name.dict
  echo "== $target: ${seconds} s"
  if "$build/fuzz/$target" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=65536 \
       -print_final_stats=1 -dict="$dict" -artifact_prefix="$build/artifacts/$target-" \
       "$work" "fuzz/corpus/$name" >"$log" 2>&1; then
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
    summary+=("$target: ${runs:-?} executions in ${seconds} s, no finding")
  else
    summary+=("$target: FINDING, see $log and $build/artifacts/")
    tail -40 "$log"
    status=1
  fi
done
printf '%s\n' "${summary[@]}"
exit $status
