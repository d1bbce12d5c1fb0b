#!/usr/bin/env bash
# Tests that the documentation stays a map a newcomer can follow: README.md is short
# (fewer than 250 lines), every docs/*.md page can be reached from README.md by following
# relative markdown links (through docs pages), and every relative link in README.md and
# docs/*.md names a file that exists. Links may carry #anchors; http(s), mailto and other
# scheme links are not checked. Links inside code (fenced blocks, `spans`) and HTML
# comments are not links.
#   tests/docs_test.sh [ROOT]   ROOT: the repository (default: this script's ../)
set -u
root=${1:-"$(dirname "$0")/.."}
root=$(cd "$root" && pwd) || exit 1
cd "$root" || exit 1
readonly max_readme_lines=250
bad=0
fail() { echo "docs: $*"; bad=1; }

[ -f README.md ] || { echo "docs: README.md is missing"; exit 1; }
lines=$(awk 'END { print NR }' README.md)  # a last line without newline counts too
if [ "$lines" -ge "$max_readme_lines" ]; then
  fail "README.md has $lines lines; it must stay under $max_readme_lines (move detail to docs/)"
fi

# The link targets of a markdown file, one a line: inline links and images [t](target "title"),
# and reference definitions [t]: target.
links_of() {
  awk '
    /^[ \t]*(```|~~~)/ { fenced = !fenced; next }
    fenced { next }
    {
      line = $0
      # HTML comments, also across lines.
      if (in_comment) {
        if (index(line, "-->") == 0) next
        line = substr(line, index(line, "-->") + 3); in_comment = 0
      }
      while ((start = index(line, "<!--")) > 0) {
        rest = substr(line, start + 4)
        if ((stop = index(rest, "-->")) == 0) { line = substr(line, 1, start - 1); in_comment = 1; break }
        line = substr(line, 1, start - 1) substr(rest, stop + 3)
      }
      gsub(/`[^`]*`/, "", line)  # code spans
      if (match(line, /^[ \t]*\[[^]]+\]:[ \t]*[^ \t]+/)) {
        definition = substr(line, RSTART, RLENGTH); sub(/^[ \t]*\[[^]]+\]:[ \t]*/, "", definition)
        print definition
      }
      while (match(line, /\]\([^)]*\)/)) {
        target = substr(line, RSTART + 2, RLENGTH - 3)
        line = substr(line, RSTART + RLENGTH)
        sub(/^[ \t]+/, "", target); sub(/[ \t].*$/, "", target)   # drop a "title"
        gsub(/^<|>$/, "", target)
        if (target != "") print target
      }
    }' "$1"
}

# The relative links of every page, checked; the docs pages each page links to, kept as
# edges for the walk from README.md below.
declare -A links_to=()
checked_links=0
pages=()
while IFS= read -r page; do pages+=("${page#./}"); done < <(find docs -name '*.md' 2>/dev/null | sort)
for page in README.md "${pages[@]}"; do
  while IFS= read -r target; do
    case $target in http://* | https://* | mailto:* | \#*) continue ;; esac
    scheme=${target%%:*}
    if [ "$scheme" != "$target" ] && [ -n "$scheme" ] && [[ $scheme =~ ^[a-zA-Z][a-zA-Z0-9+.-]*$ ]]; then
      continue  # another scheme (ftp:, tel:, ...)
    fi
    path=${target%%#*}
    path=${path%%\?*}
    checked_links=$((checked_links + 1))
    if [ "${path#/}" != "$path" ]; then
      resolved=${path#/}  # /x: from the repository root, as GitHub reads it
    else
      resolved=$(dirname "$page")/$path
    fi
    resolved=$(realpath -m --relative-to=. "$resolved")
    if [ ! -e "$resolved" ]; then
      fail "$page links to '$target', which does not exist ($resolved)"
    elif [[ $resolved == docs/*.md ]]; then
      links_to[$page]+="$resolved "
    fi
  done < <(links_of "$page")
done

# Every docs page must be reachable from README.md (through other docs pages).
declare -A seen=([README.md]=1)
queue=(README.md)
while [ ${#queue[@]} -gt 0 ]; do
  page=${queue[0]}
  queue=("${queue[@]:1}")
  for next in ${links_to[$page]:-}; do
    if [ -z "${seen[$next]:-}" ]; then
      seen[$next]=1
      queue+=("$next")
    fi
  done
done
for page in "${pages[@]}"; do
  [ -n "${seen[$page]:-}" ] ||
    fail "$page is not reachable from README.md by relative links (link it from the README's contents)"
done

echo "docs: README.md $lines lines, ${#pages[@]} docs pages, $checked_links relative links checked"
exit $bad
