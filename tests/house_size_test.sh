#!/usr/bin/env bash
# Tests that the house stays easy to live in, in model/, controller/, bench/, common/: no
# function over 80 lines (universal-ctags measures it), no source file over 600 lines, no
# include cycle between files (a.h and a.cc are one unit), no folder's own .cc/.h files
# (each subfolder counted on its own) above 30% of all of their lines; and no test folder
# with more than 25 *_test.cc files.
set -u
cd "$(dirname "$0")/.."
rooms="model controller bench common"
max_function=80
max_file=600
max_tests=25
bad=0

tags=$(ctags -x --_xformat="%{end} %n %N %F" --fields=+ne --kinds-c++=f -R $rooms)
long=$(echo "$tags" | awk -v max=$max_function \
  'NF && $1 - $2 + 1 > max {print "  " $1 - $2 + 1 " lines: " $3 " (" $4 ")"}')
if [ -n "$long" ]; then
  echo "functions over $max_function lines (split them into named stages):"
  echo "$long"
  bad=1
fi
functions=$(echo "$tags" | grep -c .)

big=$(find $rooms \( -name '*.cc' -o -name '*.h' \) -print0 | xargs -0 wc -l |
      awk -v max=$max_file '$2 != "total" && $1 > max {print "  " $1 " lines: " $2}')
if [ -n "$big" ]; then
  echo "source files over $max_file lines (split them by purpose):"
  echo "$big"
  bad=1
fi

# The include graph between units (a file's path without .h/.cc): an edge from the unit
# that includes to the unit of the included header. tsort names the units of every loop.
edges=$(grep -rHo --include='*.cc' --include='*.h' '^#include "[^"]*\.h"' $rooms |
        sed -E 's/^(.*)\.(cc|h):#include "(.*)\.h"$/\1 \3/' | awk '$1 != $2')
loops=$(echo "$edges" | tsort 2>&1 >/dev/null | sed 's/^tsort: //' |
        awk '/input contains a loop/ {if (loop) print "  " loop; loop = ""; next}
             {loop = loop (loop ? ", " : "") $0} END {if (loop) print "  " loop}')
if [ -n "$loops" ]; then
  echo "include cycles between files (units in a loop; includes must go one way):"
  echo "$loops"
  bad=1
fi

total=$(find $rooms \( -name '*.cc' -o -name '*.h' \) -print0 | xargs -0 cat | wc -l)
for dir in $(find $rooms -type d); do
  lines=$(find "$dir" -maxdepth 1 \( -name '*.cc' -o -name '*.h' \) -print0 | xargs -0 -r cat | wc -l)
  if [ $((lines * 100)) -gt $((total * 30)) ]; then
    echo "$dir/ holds $lines of $total lines (over 30%): split it by purpose"
    bad=1
  fi
done

for dir in $(find tests -type d); do
  count=$(find "$dir" -maxdepth 1 -name '*_test.cc' | wc -l)
  if [ "$count" -gt $max_tests ]; then
    echo "$dir/ holds $count test files (over $max_tests): split it like the sources"
    bad=1
  fi
done

echo "house: $functions functions, $total lines checked"
exit $bad
