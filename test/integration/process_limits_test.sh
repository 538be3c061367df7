#!/bin/bash
# CTest integration.processLimits.aSmallStackIsRaisedOtherLimitsAreSaid (issue 44): under ulimit -s 64 the
# run ended in MPI_Init (exit 1, Open MPI's report that its daemon could not start) before any of
# tribos's code. A small soft limit is now raised up to the hard limit (the run converges, exit 0);
# a hard limit below 1 MiB is exit 2 naming ulimit -s. One thread and two: the raise also takes
# effect in the threads' stacks (the binary executes itself again). Under ulimit -f 4000 (KiB) the
# run ended in MPI_Init too (exit 1, "PMIX ERROR" only): now exit 2 naming ulimit -f. A result
# that cannot fit under the file size limit is exit 2 before the assembly, naming --output.
# bash: its ulimit -f counts KiB (dash's counts 512-byte blocks).
# Usage: process_limits_test.sh TRIBOS SOURCE_DIR
set -u
tribos=$1 source=$2
dir=$(mktemp -d)
trap 'umount "$dir/small" 2>/dev/null; rm -rf "$dir"' EXIT
failed=0
for threads in 1 2; do
  status=0
  (ulimit -S -s 64 && OMP_NUM_THREADS=$threads "$tribos" --input "$source/input/two_bricks.xml" \
    --set Solver/Verbose=false --summary "$dir/s.json") > "$dir/soft.log" 2>&1 || status=$?
  if [ "$status" != 0 ] || ! grep -q '"converged": true' "$dir/s.json"; then
    cat "$dir/soft.log"; echo "FAILED: soft limit 64 KiB, $threads thread(s): exit $status, 0 and converged expected"
    failed=1
  else
    echo "soft limit 64 KiB, $threads thread(s): raised, converged"
  fi
done
status=0
(ulimit -S -s 64 && ulimit -H -s 64 && "$tribos" --input "$source/input/two_bricks.xml") > "$dir/hard.log" 2>&1 ||
  status=$?
if [ "$status" != 2 ] || ! grep -qF "the stack limit (ulimit -s) is 64 KiB at most" "$dir/hard.log"; then
  cat "$dir/hard.log"; echo "FAILED: hard limit 64 KiB: exit $status, 2 and the message expected"; failed=1
else
  echo "hard limit 64 KiB: exit 2, $(cat "$dir/hard.log")"
fi
# expect_refused NAME TEXT LIMITS [OPTIONS...]: exit 2 with TEXT under the ulimit arguments LIMITS.
expect_refused() {
  name=$1 text=$2 limits=$3
  shift 3
  status=0
  # shellcheck disable=SC2086 # $limits: separate words
  (ulimit $limits && "$tribos" --input "$source/input/block_on_plate.xml" --set Solver/Verbose=false "$@") \
    > "$dir/$name.log" 2>&1 || status=$?
  if [ "$status" != 2 ] || ! grep -qF -- "$text" "$dir/$name.log"; then
    cat "$dir/$name.log"; echo "FAILED: $name: exit $status, 2 and \"$text\" expected"; failed=1
  else
    echo "$name: exit 2, $(head -c 300 "$dir/$name.log")"
  fi
}
expect_refused fileSizeLimit "the file size limit (ulimit -f) is 4000 KiB" "-f 4000"
# 100 steps of block_on_plate write at least 100 x (13 x 515 + 8 x 1386) x 8 bytes = 14.2 MB.
expect_refused resultBeyondTheLimit "r.exo (--output): the result of 100 step(s)" "-f 10240" \
  --set "Load Steps/Number Of Steps=100" --output "$dir/r.exo"
[ -e "$dir/r.exo" ] && { echo "FAILED: r.exo was written"; failed=1; }
# The free space of the output's file system: a 4 MiB tmpfs where this user may mount one (root).
mkdir "$dir/small"
if mount -t tmpfs -o size=4m tmpfs "$dir/small" 2>/dev/null; then
  expect_refused resultBeyondTheFreeSpace "small/r.exo (--output): the result of 100 step(s)" "-f unlimited" \
    --set "Load Steps/Number Of Steps=100" --output "$dir/small/r.exo"
  [ -z "$(ls -A "$dir/small")" ] || { echo "FAILED: the small file system holds $(ls "$dir/small")"; failed=1; }
else
  echo "resultBeyondTheFreeSpace: not tried (no tmpfs can be mounted here)"
fi
exit $failed
