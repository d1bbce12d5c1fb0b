#!/usr/bin/env bash
# Tests that the house stays easy to live in: no function in model/, controller/, bench/,
# common/ longer than 120 lines (universal-ctags measures it), and no folder's own .cc/.h
# files (each subfolder counted on its own) above 30% of all of their lines.
set -u
cd "$(dirname "$0")/.."
rooms="model controller bench common"
bad=0
long=$(ctags -x --_xformat="%{end} %n %N %F" --fields=+ne --kinds-c++=f -R $rooms |
       awk '$1 - $2 + 1 > 120 {print "  " $1 - $2 + 1 " lines: " $3 " (" $4 ")"}')
if [ -n "$long" ]; then
  echo "functions over 120 lines (split them into named stages):"
  echo "$long"
  bad=1
fi
functions=$(ctags -x --_xformat="%{end} %n %N %F" --fields=+ne --kinds-c++=f -R $rooms | wc -l)
total=$(find $rooms \( -name '*.cc' -o -name '*.h' \) -print0 | xargs -0 cat | wc -l)
for dir in $(find $rooms -type d); do
  lines=$(find "$dir" -maxdepth 1 \( -name '*.cc' -o -name '*.h' \) -print0 | xargs -0 -r cat | wc -l)
  if [ $((lines * 100)) -gt $((total * 30)) ]; then
    echo "$dir/ holds $lines of $total lines (over 30%): split it by purpose"
    bad=1
  fi
done
echo "house: $functions functions, $total lines checked"
exit $bad
