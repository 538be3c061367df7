#!/bin/bash
# CTest integration.launcher.setsTheEnvironmentThenRunsTheSolver (issue 46): `tribos` is a
# launcher that raises a small soft stack limit and sets OMP_WAIT_POLICY=PASSIVE (unless the user
# chose a policy or one thread) before the solver's image loads, then runs tribos-solver from its
# own folder in the same process, arguments unchanged. A stand-in solver beside a copy of the
# launcher prints what it was given; the real pair answers --version; a launcher without its
# solver is exit 1 naming it; tribos-solver started directly still raises the stack itself.
# Usage: launcher_test.sh TRIBOS SOURCE_DIR
set -u
tribos=$1 source=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
failed=0
check() {  # check WHAT EXPECTED ACTUAL
  if [ "$2" = "$3" ]; then echo "ok: $1"; else echo "FAILED: $1: expected '$2', got '$3'"; failed=1; fi
}
mkdir "$dir/pair" "$dir/alone"
cp "$tribos" "$dir/pair/tribos"
cp "$tribos" "$dir/alone/tribos"
cat > "$dir/pair/tribos-solver" <<'EOF'
#!/bin/bash
echo "policy=${OMP_WAIT_POLICY:-unset} stack=$(ulimit -S -s) args=$*"
EOF
chmod +x "$dir/pair/tribos-solver"
hard=$(ulimit -H -s)
wanted=8192
[ "$hard" != unlimited ] && [ "$hard" -lt "$wanted" ] && wanted=$hard
launch() {  # launch ENV-ARGS...: the stand-in's line under a soft stack limit of 1 MiB
  env -u OMP_WAIT_POLICY -u OMP_NUM_THREADS "$@" bash -c "ulimit -S -s 1024; \"$dir/pair/tribos\" --input a.xml --set 'X=1 2'"
}
check "no policy chosen: PASSIVE, the stack raised, the arguments kept" \
  "policy=PASSIVE stack=$wanted args=--input a.xml --set X=1 2" "$(launch)"
check "the user's policy kept" "policy=ACTIVE stack=$wanted args=--input a.xml --set X=1 2" "$(launch OMP_WAIT_POLICY=ACTIVE)"
check "one thread: no policy" "policy=unset stack=$wanted args=--input a.xml --set X=1 2" "$(launch OMP_NUM_THREADS=1)"

status=0
"$dir/alone/tribos" --version > "$dir/alone.log" 2>&1 || status=$?
check "a launcher without its solver: exit 1" 1 "$status"
grep -q "tribos-solver" "$dir/alone.log" || { echo "FAILED: the message does not name tribos-solver:"; cat "$dir/alone.log"; failed=1; }

status=0
"$tribos" --version > "$dir/version.log" 2>&1 || status=$?
check "the real pair: --version" 0 "$status"
grep -q "^tribos " "$dir/version.log" || { echo "FAILED: no version line"; cat "$dir/version.log"; failed=1; }

status=0
(ulimit -S -s 64 && OMP_NUM_THREADS=2 "$(dirname "$tribos")/tribos-solver" --input "$source/input/two_bricks.xml" \
  --set Solver/Verbose=false --summary "$dir/s.json") > "$dir/solver.log" 2>&1 || status=$?
check "tribos-solver started directly under ulimit -s 64: converged" 0 "$status"
grep -q '"converged": true' "$dir/s.json" 2>/dev/null || { echo "FAILED: not converged"; tail -5 "$dir/solver.log"; failed=1; }
exit $failed
