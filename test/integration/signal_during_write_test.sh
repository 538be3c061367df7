#!/bin/sh
# CTest integration.fileFaults.aSignalDuringTheWriteLeavesNoPartialFile.<SIGNAL> (issue 44): SIGTERM
# (or SIGINT, SIGHUP) while the Exodus result is being written left its temporary file behind
# (20-33 MB). SIGINT is not tried here: a background job of a non-interactive shell ignores it,
# and an ignored signal stays ignored (the handler is the same for the three).
# A 20-step history of the paper's bricks at 4x2x2/6 (8 450 nodes, a result of about 50 MB)
# is signalled as soon as its temporary file appears; the run must end by that signal (status
# 128 + signal) with neither the temporary file nor a result left. Tries again (up to 5 times)
# where the write finished before the signal landed; skipped (77) if it never lands.
# Usage: signal_during_write_test.sh TRIBOS SOURCE_DIR SIGNAL (TERM or HUP)
set -u
tribos=$1 source=$2 signal=$3
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
for attempt in 1 2 3 4 5; do
  rm -f "$dir"/*
  OMP_NUM_THREADS=1 "$tribos" --input "$source/input/two_bricks.xml" --set Solver/Verbose=false \
    --set "Mesh/Subdomains Per Brick=4x2x2" --set "Mesh/H Over h=6" --set "Load Steps/Number Of Steps=20" \
    --output "$dir/r.exo" > "$dir/log" 2>&1 &
  pid=$!
  caught=no
  while kill -0 "$pid" 2>/dev/null; do
    for f in "$dir"/r.exo.tribos-partial-*; do
      # Past the trial file of the start (created and removed at once): a file that grows.
      if [ -s "$f" ]; then kill "-$signal" "$pid"; caught=yes; break 2; fi
    done
    sleep 0.002
  done
  wait "$pid"
  status=$?
  if [ "$caught" = no ]; then echo "attempt $attempt: the write ended before the signal (status $status)"; continue; fi
  left=$(ls "$dir" | grep -v '^log$')
  echo "attempt $attempt: signalled during the write, status $status, left: [${left}]"
  case $signal in TERM) expected=143 ;; HUP) expected=129 ;; *) expected=unknown ;; esac
  [ "$status" = "$expected" ] || { echo "FAIL: status $status, expected $expected"; cat "$dir/log"; exit 1; }
  [ -z "$left" ] || { echo "FAIL: left behind: $left"; exit 1; }
  exit 0
done
# A machine that writes the result faster than the polling sees it: nothing was checked.
echo "skipped: the write never lasted long enough to be signalled (5 attempts)"
exit 77
