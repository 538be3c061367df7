#!/bin/sh
# CTest integration.loadSteps.conditionsSwitchedPerStep (issue 43: a plate could not be gripped
# after the bolt was tightened). grip_after_preload.xml: block_on_plate's block pressed (step 1,
# held by contact and friction only), its top gripped where the press left it (step 2, Active
# {0, 1, 1}), the press removed while the grip holds (step 3). Exact consequences checked:
#  - step 2 equals step 1 (the grip takes hold where the body is; before this change a condition
#    could only hold from the reference), and the grip carries nothing (<= 1e-6 of the press);
#  - step 3 equals step 1 and the grip's reaction is the press's resultant (300, 0, -12000) N;
#  - the same on 2 ranks, bit for bit;
#  - restarted after step 2 from a 2-step result (the grip's hold read from the file's step 1),
#    step 3 as in the whole run;
#  - a grip released (Active {1, 0}, pressed in both steps): step 1 carries the press in the grip,
#    nothing moves (|u| <= 1e-5 of the press's; before the KKT residuals took B K^+ f as their
#    floor, this zero solution read as "gluing/Dirichlet" 0.79, exit 3); step 2 equals the
#    one-step solve without the grip;
#  - Active on a load, of the wrong length or with a value other than 0 and 1: exit 2 naming it.
# Needs Debian's python3 with netCDF4; exit 77 (CTest: skipped) without it.
# Usage: condition_steps_test.sh TRIBOS SOURCE_DIR [LAUNCHER...] (the launcher: the 2-rank run)
set -u
tribos=$1 source=$2
shift 2
launcher="$*"
scene=$source/test/integration/grip_after_preload.xml
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
/usr/bin/python3 -c "import netCDF4" 2>/dev/null ||
  { echo "skipped: /usr/bin/python3 lacks netCDF4 (python3-netcdf4)"; exit 77; }
failed=0
run() {  # run NAME [OPTIONS...]: the scene, quiet; exit status in $status
  name=$1
  shift
  status=0
  "$tribos" --input "$scene" --set Solver/Verbose=false "$@" > "$dir/$name.log" 2>&1 || status=$?
  [ "$status" = 0 ] || { cat "$dir/$name.log"; echo "FAILED: $name: exit $status"; failed=1; }
}
run added --output "$dir/added.exo"
# shellcheck disable=SC2086 # $launcher: separate words
$launcher "$tribos" --input "$scene" --set Solver/Verbose=false --output "$dir/added_np2.exo" > "$dir/np2.log" 2>&1 ||
  { cat "$dir/np2.log"; echo "FAILED: 2 ranks"; failed=1; }
run first2 --set "Load Steps/Number Of Steps=2" --set "Load Steps/press/Factors={1, 1}" \
  --set "Load Steps/grip/Active={0, 1}" --output "$dir/first2.exo"
run restarted --set "Load Steps/Restart From=$dir/first2.exo" --output "$dir/restarted.exo"
run released --set "Load Steps/Number Of Steps=2" --set "Load Steps/press/Factors={1, 1}" \
  --set "Load Steps/grip/Active={1, 0}" --output "$dir/released.exo"
run oneStep --set "Load Steps/Number Of Steps=1" --set "Load Steps/press/Factors={1}" \
  --set "Load Steps/grip/Active={0}" --output "$dir/one.exo"
[ "$failed" = 0 ] || exit 1
/usr/bin/python3 - "$dir" <<'PY' || failed=1
import sys

import netCDF4
import numpy as np

d = sys.argv[1]
names = lambda v: ["".join(c.decode() for c in row if c) for row in v[:].data]
def field(path, prefix, k):
    f = netCDF4.Dataset(path)
    nod = names(f.variables["name_nod_var"])
    return np.array([f.variables["vals_nod_var%d" % (nod.index(prefix + c) + 1)][k, :] for c in "xyz"])
f = netCDF4.Dataset(d + "/added.exo")
top = f.variables["node_ns%d" % (names(f.variables["ns_names"]).index("block_top") + 1)][:] - 1
u = [field(d + "/added.exo", "displ_", k) for k in range(3)]
grip = [field(d + "/added.exo", "reaction_", k)[:, top].sum(axis=1) for k in range(3)]
scale = abs(u[0]).max()
press = np.array([300.0, 0.0, -12000.0])
bad = []
def check(what, value, bound):
    print("%s: %.3g (at most %.3g)" % (what, value, bound))
    if not value <= bound:
        bad.append(what)
check("step 2 - step 1, relative", abs(u[1] - u[0]).max() / scale, 1e-4)
check("the grip's force in step 2 / the press", abs(grip[1]).max() / 12000.0, 1e-6)
check("step 3 - step 1, relative", abs(u[2] - u[0]).max() / scale, 1e-4)
check("the grip's force in step 3 - the press, relative", abs(grip[2] - press).max() / 12000.0, 1e-6)
check("2 ranks - 1 rank", max(abs(field(d + "/added_np2.exo", "displ_", k) - u[k]).max() for k in range(3)), 0.0)
check("restarted step 3 - whole, relative", abs(field(d + "/restarted.exo", "displ_", 0) - u[2]).max() / scale, 1e-4)
released = [field(d + "/released.exo", "displ_", k) for k in range(2)]
check("released: step 1 |u| / |u of the press|", abs(released[0]).max() / scale, 1e-5)
check("released: step 2 - one step, relative", abs(released[1] - field(d + "/one.exo", "displ_", 0)).max() / scale, 1e-4)
sys.exit(1 if bad else 0)
PY
# expect_refused NAME TEXT OPTIONS...: exit 2 and TEXT.
expect_refused() {
  name=$1 text=$2
  shift 2
  status=0
  "$tribos" --input "$scene" "$@" > "$dir/$name.log" 2>&1 || status=$?
  if [ "$status" != 2 ] || ! grep -qF -- "$text" "$dir/$name.log"; then
    cat "$dir/$name.log"; echo "FAILED: $name: exit $status, 2 and \"$text\" expected"; failed=1
  else
    echo "$name: exit 2, $(grep -o 'Load Steps/.*' "$dir/$name.log" | head -1)"
  fi
}
expect_refused activeLoad "Load Steps/press/Active: Loads/press is a load" --set "Load Steps/press/Active={1, 1, 1}"
expect_refused wrongLength "Load Steps/grip/Active: 2 values for Load Steps/Number Of Steps = 3" \
  --set "Load Steps/grip/Active={0, 1}"
expect_refused notAFlag "Load Steps/grip/Active: step 2's value 2" --set "Load Steps/grip/Active={0, 2, 1}"
exit $failed
