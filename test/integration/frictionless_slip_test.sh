#!/bin/sh
# CTest integration.frictionlessSlip.fieldsFromTheKinematics (issue 42): a frictionless interface
# has no tangential rows, and its slip fields were zero while its nodes slid. The paper's bricks
# without friction (matching meshes: each slave node's row is node-to-node with contact_master)
# in one step and in a 2-step ramp: at every slave node, the tangential part of
# u_slave - u_master (the tangent plane's, normal contact_n) has the length of
# (contact_tangential_t1, contact_tangential_t2); in the history the step's slip is the total's
# increment since step 1, and the accumulated slip sums the increments' lengths where the node slips.
# Needs Debian's python3 with netCDF4 (python3-netcdf4, scripts/setup.sh); exit 77 without it.
# Usage: frictionless_slip_test.sh TRIBOS SOURCE_DIR
set -u
tribos=$1 source=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
/usr/bin/python3 -c "import netCDF4" 2>/dev/null || { echo "skipped: /usr/bin/python3 lacks netCDF4"; exit 77; }
for steps in 1 2; do
  "$tribos" --input "$source/input/two_bricks_frictionless.xml" --set Solver/Verbose=false \
    --set "Load Steps/Number Of Steps=$steps" --output "$dir/r$steps.exo" --summary "$dir/s$steps.json" \
    > "$dir/run$steps.log" 2>&1 || { cat "$dir/run$steps.log"; exit 1; }
done
/usr/bin/python3 - "$dir/r1.exo" "$dir/r2.exo" <<'PY'
import sys
import netCDF4
import numpy as np

def steps(path):
    d = netCDF4.Dataset(path)
    names = ["".join(c.decode() for c in row if c) for row in d.variables["name_nod_var"][:].data]
    var = lambda name: np.array(d.variables["vals_nod_var%d" % (names.index(name) + 1)][:].data)
    return {name: var(name) for name in names}

def check(f, step, label):
    u = np.stack([f["displ_" + c][step] for c in "xyz"], axis=1)
    n = np.stack([f["contact_n" + c][step] for c in "xyz"], axis=1)
    master = f["contact_master"][step].astype(int)
    slaves = np.nonzero(master > 0)[0]
    relative = u[slaves] - u[master[slaves] - 1]
    along = np.sum(relative * n[slaves], axis=1)
    tangential = np.linalg.norm(relative - along[:, None] * n[slaves], axis=1)
    reported = np.hypot(f["contact_tangential_t1"][step][slaves], f["contact_tangential_t2"][step][slaves])
    scale = np.abs(u).max()
    error = np.abs(tangential - reported).max() / scale
    print("%s: %d slave nodes, largest tangential relative displacement %.4g (%.0f%% of max |u|), "
          "|reported - kinematic| / max|u| = %.2e" % (label, len(slaves), tangential.max(),
                                                      100 * tangential.max() / scale, error))
    if not tangential.max() > 1e-3 * scale:
        sys.exit(label + ": the nodes do not slide; the test shows nothing")
    if error > 1e-12:
        sys.exit(label + ": the slip fields are not the kinematic relative displacement")
    return slaves

one, two = steps(sys.argv[1]), steps(sys.argv[2])
scale = max(np.abs(one["displ_" + c]).max() for c in "xyz")
check(one, 0, "one step")
check(two, 0, "history step 1")
slaves = check(two, 1, "history step 2")
for c in ("t1", "t2"):
    increment = two["contact_tangential_" + c][1] - two["contact_tangential_" + c][0]
    if np.abs(two["contact_slip_" + c][1] - increment).max() > 1e-12 * np.abs(increment).max():
        sys.exit("history: contact_slip_%s at step 2 is not the increment of the total since step 1" % c)
    # Frictionless: the path does not matter; the two solves agree to the solver's tolerance (1e-5).
    difference = np.abs(two["contact_tangential_" + c][1] - one["contact_tangential_" + c][0]).max()
    print("history: total %s after 2 steps against one step: %.2e of max |u|" % (c, difference / scale))
    if difference > 1e-4 * scale:
        sys.exit("history: the 2-step total of %s differs from the one-step solve's" % c)
slipping = two["contact_status"][1][slaves] == 2
expected = np.hypot(two["contact_slip_t1"][1], two["contact_slip_t2"][1]) + two["contact_accumulated_slip"][0]
if np.abs(two["contact_accumulated_slip"][1][slaves][slipping] - expected[slaves][slipping]).max() > 1e-12:
    sys.exit("history: the accumulated slip is not the sum of the increments' lengths")
print("history: %d of %d slave nodes slip at step 2; increments and accumulated slip consistent"
      % (slipping.sum(), len(slaves)))
PY
