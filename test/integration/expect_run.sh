#!/bin/sh
# Runs a command and checks how it ended; passes only if every check holds:
#   expect_run.sh [--status N] [--within SECONDS] [--once TEXT]... [--never TEXT]...
#                 [--absent PATH]... -- command [args...]
#   --status N      the exit status is N
#   --within S      it ended within S seconds (wall clock)
#   --once TEXT     exactly one line of its output (stdout and stderr) contains TEXT
#   --never TEXT    no line contains TEXT
#   --absent PATH   nothing matches PATH afterwards, a shell pattern (no output file left behind)
status="" within="" once="" never="" absent=""
nl='
'
while [ $# -gt 0 ] && [ "$1" != "--" ]; do
  case "$1" in
    --status) status=$2 ;;
    --within) within=$2 ;;
    --once) once="$once$2$nl" ;;
    --never) never="$never$2$nl" ;;
    --absent) absent="$absent$2$nl" ;;
    *) echo "expect_run.sh: unknown option $1" >&2; exit 1 ;;
  esac
  shift 2
done
shift
output=$(mktemp)
start=$(date +%s)
"$@" >"$output" 2>&1
actual=$?
elapsed=$(($(date +%s) - start))
cat "$output"
failed=0
fail() { echo "expect_run.sh: $*" >&2; failed=1; }
[ -n "$status" ] && [ "$actual" -ne "$status" ] && fail "exit status $actual, expected $status"
[ -n "$within" ] && [ "$elapsed" -gt "$within" ] && fail "took $elapsed s, expected at most $within s"
printf '%s' "$once" | while IFS= read -r text; do
  count=$(grep -c -F -- "$text" "$output")
  [ "$count" -eq 1 ] || { echo "expect_run.sh: \"$text\" on $count lines, expected exactly 1" >&2; exit 1; }
done || failed=1
printf '%s' "$never" | while IFS= read -r text; do
  if grep -q -F -- "$text" "$output"; then echo "expect_run.sh: \"$text\" in the output" >&2; exit 1; fi
done || failed=1
printf '%s' "$absent" | while IFS= read -r pattern; do
  for path in $pattern; do  # unquoted: a pattern such as r.exo.tribos-partial* matches what a run left
    if [ -e "$path" ]; then echo "expect_run.sh: $path exists" >&2; exit 1; fi
  done
done || failed=1
rm -f "$output"
exit $failed
