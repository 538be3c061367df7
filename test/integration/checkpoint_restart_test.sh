#!/bin/sh
# CTest integration.loadSteps.aKilledHistoryContinuesFromItsCheckpoint (issue 43): a 12-step
# history of the bricks (H/h 5, tolerance 1e-10) with Load Steps/Checkpoint Seconds = 0 writes its
# result after every converged step. Killed (SIGKILL: nothing of tribos runs after it) once the
# checkpoint of step 3 is written, the file holds the steps converged so far, whole; their
# displacements are those of the run that was not killed, bit for bit. Restarted from it
# (Load Steps/Restart From), the history ends at step 12 with the uninterrupted run's
# displacements to 1e-8 of their largest (issue 43's acceptance; the first step after a restart
# starts cold: the two differ by the solver's tolerance, measured 6.4e-11).
# Needs Debian's python3 with netCDF4; exit 77 (CTest: skipped) without it.
# Usage: checkpoint_restart_test.sh TRIBOS SOURCE_DIR
set -u
tribos=$1 source=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
/usr/bin/python3 -c "import netCDF4" 2>/dev/null || { echo "skipped: /usr/bin/python3 lacks netCDF4"; exit 77; }
cd "$dir" || exit 1
set -- --input "$source/input/two_bricks.xml" --set "Load Steps/Number Of Steps=12" \
  --set "Load Steps/Checkpoint Seconds=0" --set "Mesh/H Over h=5" --set Solver/Tolerance=1e-10 --set Solver/Verbose=false
"$tribos" "$@" --output whole.exo >whole.log 2>&1 || { cat whole.log; echo "the uninterrupted history failed"; exit 1; }
"$tribos" "$@" --output killed.exo >killed.log 2>&1 &
pid=$!
for _ in $(seq 1 6000); do grep -q "wrote steps 1 to 3 " killed.log && break; sleep 0.01; done
kill -KILL $pid 2>/dev/null
wait $pid 2>/dev/null
cat killed.log
grep -q "wrote steps 1 to 3 " killed.log || { echo "no checkpoint of step 3"; exit 1; }
"$tribos" "$@" --set "Load Steps/Restart From=killed.exo" --output restarted.exo >restarted.log 2>&1 ||
  { cat restarted.log; echo "the restart from the checkpoint failed"; exit 1; }
grep -E "restart|load step" restarted.log | head -3
/usr/bin/python3 - <<'PY'
import sys

import netCDF4
import numpy as np


def displacements(path):
    d = netCDF4.Dataset(path)
    names = ["".join(c.decode() for c in row if c) for row in d.variables["name_nod_var"][:].data]
    u = [d.variables["vals_nod_var%d" % (names.index("displ_" + c) + 1)][:].data for c in "xyz"]
    steps = [int(v) for v in d.variables["vals_glo_var"][:, ["".join(c.decode() for c in row if c) for row in
                                                              d.variables["name_glo_var"][:].data].index("load_step")]]
    return np.stack(u, axis=-1), steps


whole, whole_steps = displacements("whole.exo")
killed, killed_steps = displacements("killed.exo")
restarted, restarted_steps = displacements("restarted.exo")
print("whole: steps %s; killed: steps %s; restarted: steps %s" % (whole_steps, killed_steps, restarted_steps))
k = len(killed_steps)
if killed_steps != list(range(1, k + 1)) or not 3 <= k < 12:
    sys.exit("the checkpoint holds steps %s, expected 1 .. k with 3 <= k < 12" % killed_steps)
if not np.array_equal(killed, whole[:k]):
    sys.exit("the checkpoint's displacements differ from the uninterrupted run's")
if restarted_steps != list(range(k + 1, 13)):
    sys.exit("the restart solved steps %s, expected %d .. 12" % (restarted_steps, k + 1))
scale = np.abs(whole[-1]).max()
difference = np.abs(restarted[-1] - whole[-1]).max() / scale
print("step 12 after the restart: largest displacement difference %.3e of the largest displacement" % difference)
if not difference <= 1e-8:
    sys.exit("the restarted history ends %.3e away from the uninterrupted one" % difference)
PY
