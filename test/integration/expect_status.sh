#!/bin/sh
# Runs a command and passes only if it exits with the given status:
#   expect_status.sh STATUS command [args...]
expected=$1
shift
"$@"
status=$?
[ "$status" -eq "$expected" ] && exit 0
echo "expect_status.sh: exit status $status, expected $expected" >&2
exit 1
