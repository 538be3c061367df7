#!/bin/sh
# CTest integration.restartFaults.damagedValuesAreRefused (issue 44): a restart file whose values
# cannot be a tribos history's is refused with exit 2 naming the file, the variable and the node
# or step, before any solve. The result of block_on_plate.xml's first 2 steps (sheared, then the
# shear removed), damaged with netCDF4 in one way per run:
#   - load_step of step 2 set to 1.5 (was taken as step 1, exit 0), and of step 1 to -1 (read the
#     factor table before its start);
#   - contact_tangential_t1 at one node set to NaN, and to 1e300 (exit 3 "check the loads");
#   - contact_accumulated_slip at one node negative (exit 0);
#   - the dissipated energy NaN (exit 0);
#   - the memory of the last step zero at every node from node 3 on, as a file cut inside that
#     step reads (its contact_memory_sum then disagrees; exit 0 before, the memory lost).
# The undamaged file restarts (exit 0). With LAUNCHER (e.g. mpiexec -n 2) every run goes through
# it: rank 0 reads the file and hands its state to the others (stack/Restart.hpp). Needs Debian's
# python3 with netCDF4; exit 77 (CTest: skipped) without it.
# Usage: restart_faults_test.sh TRIBOS SOURCE_DIR [LAUNCHER...]
set -u
tribos=$1 source=$2
shift 2
launcher="$*"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
/usr/bin/python3 -c "import netCDF4" 2>/dev/null ||
  { echo "skipped: /usr/bin/python3 lacks netCDF4 (python3-netcdf4)"; exit 77; }
# run STEPS PRESS-FACTORS SHEAR-FACTORS [OPTIONS...]: block_on_plate.xml sheared by 5 MPa.
run() {
  steps=$1 press=$2 shear=$3
  shift 3
  # shellcheck disable=SC2086 # $launcher: separate words
  $launcher "$tribos" --input "$source/input/block_on_plate.xml" --set Solver/Verbose=false \
    --set "Loads/shear/Side Set=block_top" --set "Loads/shear/Traction={5, 0, 0}" \
    --set "Load Steps/Number Of Steps=$steps" --set "Load Steps/press/Factors=$press" \
    --set "Load Steps/shear/Factors=$shear" "$@" > "$dir/out.log" 2>&1
}
run 2 "{1, 1}" "{1, 0}" --output "$dir/first.exo" || { cat "$dir/out.log"; echo "the first 2 steps failed"; exit 1; }
failed=0
# damage NAME PYTHON-STATEMENTS EXPECTED-TEXT: a copy of the result damaged, then restarted.
damage() {
  cp "$dir/first.exo" "$dir/$1.exo"
  /usr/bin/python3 - "$dir/$1.exo" "$2" <<'PY' || exit 1
import sys

import netCDF4

d = netCDF4.Dataset(sys.argv[1], "r+")
text = lambda rows: ["".join(c.decode() for c in row if c) for row in rows]
glo = text(d.variables["name_glo_var"][:].data)
nod = text(d.variables["name_nod_var"][:].data)
def set_global(name, step, value):
    d.variables["vals_glo_var"][step, glo.index(name)] = value
def set_nodal(name, step, node, value):
    values = d.variables["vals_nod_var%d" % (nod.index(name) + 1)]
    row = values[step, :]
    row[node] = value
    values[step, :] = row
exec(sys.argv[2])
d.close()
PY
  status=0
  run 4 "{1, 1, 1, 1}" "{1, 0, -1, 0}" --set "Load Steps/Restart From=$dir/$1.exo" --output "$dir/r.exo" || status=$?
  if [ "$status" != 2 ] || ! grep -qF -- "$3" "$dir/out.log"; then
    cat "$dir/out.log"
    echo "FAILED: $1: exit $status (2 expected) or no \"$3\" in the output"
    failed=1
  else
    echo "$1: exit 2, $(grep -o 'Restart From: .*' "$dir/out.log" | head -1 | cut -c1-160)"
  fi
}
slave=$(/usr/bin/python3 -c "
import sys, netCDF4
d = netCDF4.Dataset('$dir/first.exo')
text = lambda rows: [''.join(c.decode() for c in row if c) for row in rows]
nod = text(d.variables['name_nod_var'][:].data)
m = d.variables['vals_nod_var%d' % (nod.index('contact_master') + 1)][-1, :]
print(int(next(i for i, v in enumerate(m) if v != 0)))")
damage halfStep "set_global('load_step', 1, 1.5)" "its time step 2 has load_step 1.5"
damage negativeStep "set_global('load_step', 0, -1)" "its time step 1 has load_step -1"
damage nanMemory "set_nodal('contact_tangential_t1', 1, $slave, float('nan'))" "contact_tangential_t1 at node $((slave + 1)) is nan"
damage hugeMemory "set_nodal('contact_tangential_t1', 1, $slave, 1e300)" "contact_tangential_t1 at node $((slave + 1)) is 1e+300"
damage negativeSlip "set_nodal('contact_accumulated_slip', 1, $slave, -0.5)" "contact_accumulated_slip at node $((slave + 1)) is -0.5"
damage nanEnergy "set_global('dissipated_energy', 1, float('nan'))" "global variable dissipated_energy is nan"
damage cutStep "
for name in ('contact_tangential_t1', 'contact_tangential_t2', 'contact_accumulated_slip'):
    values = d.variables['vals_nod_var%d' % (nod.index(name) + 1)]
    row = values[1, :]
    row[2:] = 0.0
    values[1, :] = row" "the file is cut or damaged"
run 4 "{1, 1, 1, 1}" "{1, 0, -1, 0}" --set "Load Steps/Restart From=$dir/first.exo" --output "$dir/r.exo" ||
  { cat "$dir/out.log"; echo "FAILED: the undamaged file did not restart"; failed=1; }
exit $failed
