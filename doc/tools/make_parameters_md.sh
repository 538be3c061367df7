#!/bin/sh
# Regenerates the reference part of doc/parameters.md from `tribos --list-parameters` (the
# valid lists themselves: every parameter's path, type, default, range and documentation).
# The text outside the markers (how scenes are read, the measured defaults) is kept.
#
#   doc/tools/make_parameters_md.sh build/bin/tribos            # rewrite doc/parameters.md
#   doc/tools/make_parameters_md.sh --check build/bin/tribos    # fail if it is out of date (CTest)
set -eu

check=0
if [ "${1:-}" = "--check" ]; then
  check=1
  shift
fi
if [ $# -ne 1 ]; then
  echo "usage: $0 [--check] path/to/tribos" >&2
  exit 2
fi
tribos=$1
doc="$(cd "$(dirname "$0")/.." && pwd)/parameters.md"
begin='<!-- BEGIN GENERATED: doc/tools/make_parameters_md.sh from `tribos --list-parameters`; do not edit -->'
end='<!-- END GENERATED -->'

listing=$(mktemp)
generated=$(mktemp)
trap 'rm -f "$listing" "$generated"' EXIT
OMP_NUM_THREADS=1 "$tribos" --list-parameters > "$listing"

# "Path  (type, default D, range R)" + an indented doc line -> one table per list.
awk '
  function cell(s) {
    gsub(/\|/, "\\|", s); gsub(/\*/, "\\*", s); gsub(/_/, "\\_", s); gsub(/</, "\\&lt;", s)
    return s
  }
  function code(s) { gsub(/\|/, "\\|", s); return "`" s "`" }
  /^[^ ]/ {
    split_at = index($0, "  (")
    path = substr($0, 1, split_at - 1)
    inside = substr($0, split_at + 3, length($0) - split_at - 3)
    type = substr(inside, 1, index(inside, ", default ") - 1)
    rest = substr(inside, length(type) + 11)
    range = ""
    at = index(rest, ", range ")
    if (at > 0) { range = substr(rest, at + 8); rest = substr(rest, 1, at - 1) }
    n = split(path, parts, "/")
    list = parts[1]
    for (i = 2; i < n; i++) list = list "/" parts[i]
    name = parts[n]
    next
  }
  /^      / {
    doc = substr($0, 7)
    if (list != current) {
      printf "%s## `%s`\n\n| Parameter | Type | Default | Range | Meaning |\n|---|---|---|---|---|\n", \
             (current == "" ? "" : "\n"), list
      current = list
    }
    printf "| %s | %s | %s | %s | %s |\n", code(name), type, code(rest), (range == "" ? "" : code(range)), cell(doc)
  }
' "$listing" > "$generated"

result=$(mktemp)
trap 'rm -f "$listing" "$generated" "$result"' EXIT
awk -v begin="$begin" -v end="$end" -v generated="$generated" '
  $0 == begin { print; print ""; while ((getline line < generated) > 0) print line; print ""; skip = 1; next }
  $0 == end { skip = 0 }
  !skip { print }
' "$doc" > "$result"
grep -qxF "$begin" "$doc" || { echo "$doc: the marker line is missing: $begin" >&2; exit 1; }

if [ $check -eq 1 ]; then
  if ! cmp -s "$result" "$doc"; then
    echo "doc/parameters.md is out of date with the valid parameter lists:" >&2
    diff "$doc" "$result" | head -40 >&2 || true
    echo "Regenerate it: doc/tools/make_parameters_md.sh build/bin/tribos (and commit it)" >&2
    exit 1
  fi
  exit 0
fi
cp "$result" "$doc"
echo "wrote $doc"
