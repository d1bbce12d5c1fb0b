#!/usr/bin/env bash
# Tests that every include goes downwards in the house: a room may include itself and the
# rooms listed before it, never one after it (controller/ and model/ never each other).
#   common < model, controller < bench/config < bench/measured < bench/fmi < bench/scenario
#     < bench/run < bench/output < bench/sensitivity < bench/sweep < bench/compare < bench/fmu
#     < bench/cli
set -u
cd "$(dirname "$0")/.."
allowed() {  # the include prefixes a file in room $1 may use
  local below="common/ model/ controller/"
  case $1 in
    common) echo "common/" ;;
    model) echo "common/ model/" ;;
    controller|controller/shapers) echo "common/ controller/" ;;
    bench/config) echo "$below bench/config/" ;;
    bench/measured) echo "$below bench/config/ bench/measured/" ;;
    bench/fmi) echo "$below bench/config/ bench/measured/ bench/fmi/" ;;
    bench/scenario) echo "$below bench/config/ bench/measured/ bench/fmi/ bench/scenario/" ;;
    bench/run) echo "$below bench/config/ bench/measured/ bench/fmi/ bench/scenario/ bench/run/" ;;
    bench/output) echo "$below bench/config/ bench/measured/ bench/fmi/ bench/scenario/ bench/run/ bench/output/" ;;
    bench/sensitivity) echo "$below bench/config/ bench/measured/ bench/fmi/ bench/scenario/ bench/run/ bench/output/ bench/sensitivity/" ;;
    bench/sweep) echo "$below bench/config/ bench/measured/ bench/fmi/ bench/scenario/ bench/run/ bench/output/ bench/sensitivity/ bench/sweep/" ;;
    bench/compare) echo "$below bench/config/ bench/measured/ bench/fmi/ bench/scenario/ bench/run/ bench/output/ bench/sensitivity/ bench/sweep/ bench/compare/" ;;
    bench/fmu) echo "$below bench/" ;;
    bench/cli) echo "$below bench/" ;;
  esac
}
bad=0
checked=0
for room in common model controller controller/shapers bench/config bench/measured bench/scenario bench/run bench/output bench/sensitivity bench/sweep bench/compare bench/fmi bench/fmu bench/cli; do
  [ -d "$room" ] || continue
  prefixes=$(allowed "$room")
  for file in $(find "$room" -maxdepth 1 -name '*.h' -o -maxdepth 1 -name '*.cc'); do
    checked=$((checked + 1))
    while IFS= read -r inc; do
      ok=0
      for prefix in $prefixes; do
        case $inc in "$prefix"*) ok=1 ;; esac
      done
      if [ $ok -eq 0 ]; then
        echo "$file includes \"$inc\": room $room may include only: $prefixes"
        bad=1
      fi
    done < <(sed -n 's/^#include "\([^"]*\)".*/\1/p' "$file")
  done
done
# A new folder of bench/ is a room only once it has its place in the order above.
for dir in bench/*/; do
  [ -n "$(allowed "${dir%/}")" ] || { echo "${dir%/} is not a room of the order in $0: add it"; bad=1; }
done
stray=$(find bench -maxdepth 1 -name '*.cc' -o -maxdepth 1 -name '*.h')
[ -z "$stray" ] || { echo "files outside bench's rooms: $stray"; bad=1; }
echo "layering: $checked files checked"
exit $bad
