#!/bin/bash
# The counts and displacement bits of a tribos binary on a fixed set of runs, one line each:
# every scene under input/, the Table 1 cells up to 2s = 256 (2x1x1 .. 8x4x4, H/h 2..5), and
# friction variants on 1 and 2 ranks (Tresca, exact Coulomb, the Paper slip-bound test, no and
# lumped preconditioner, a curved Coulomb contact, a capped run, an open gap, orthotropic).
# A reshaping that must keep the bits (issue 29) gives the same output as the binary before it
# (a copy of build/bin with both tribos and tribos-solver, which the launcher runs from its folder):
#   perf/tools/bit_identity.sh old/bin/tribos > before.txt
#   perf/tools/bit_identity.sh build/bin/tribos > after.txt && diff before.txt after.txt
# Each line: name, ranks, exit status, outer / inner / PFP / F applications (or slip-bound
# updates and contact statuses for the variants), and the first 16 hex digits of the sha256
# of the displacement arrays of the Exodus result. Needs Debian's python3 with netCDF4
# (python3-netcdf4, installed by scripts/setup.sh). About a minute on 2 cores.
set -u
T=$(realpath "$1")
SRC=$(cd "$(dirname "$0")/../.." && pwd)
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
MPIRUN="mpirun -q --allow-run-as-root --oversubscribe --bind-to none -x OMP_NUM_THREADS=1 -np 2"

# one NAME RANKS ARGS...: the line of one run.
one() {
  local name=$1 np=$2
  shift 2
  local pre=""
  [ "$np" = 2 ] && pre=$MPIRUN
  OMP_NUM_THREADS=1 $pre "$T" --set Solver/Verbose=false "$@" --summary "$W/s.json" --output "$W/r.exo" \
    >"$W/log" 2>&1
  local status=$?
  local line
  line=$(/usr/bin/python3 - "$W/s.json" "$W/r.exo" <<'PY'
import sys, json, hashlib, netCDF4
j = json.load(open(sys.argv[1]))
d = netCDF4.Dataset(sys.argv[2])
names = ["".join(c.decode() for c in row if c) for row in d.variables["name_nod_var"][:].data]
h = hashlib.sha256()
for comp in "xyz":
    h.update(d.variables["vals_nod_var%d" % (names.index("displ_" + comp) + 1)][0, :].data.tobytes())
print(j.get("outer_iterations"), j.get("inner_iterations"), j.get("pfp_applications"), j.get("f_applications"),
      j.get("fixed_point_iterations"), j.get("contact_nodes"), h.hexdigest()[:16])
PY
)
  echo "$name np$np status=$status $line"
  rm -f "$W/s.json" "$W/r.exo"
}

B=$SRC/input/two_bricks.xml
for f in two_bricks two_bricks_bonded two_bricks_frictionless two_bricks_orthotropic block_on_plate hertz_cylinder \
         hertz_sphere; do
  one "$f" 1 --input "$SRC/input/$f.xml"
done
for g in 2x1x1 4x2x2 6x3x3 8x4x4; do
  for h in 2 3 4 5; do
    one "cell_${g}_$h" 1 --input "$B" --set "Mesh/Subdomains Per Brick=$g" --set "Mesh/H Over h=$h"
  done
done
for np in 1 2; do
  one tresca $np --input "$B" --set "Contact/Friction Model=Tresca" --set "Contact/Slip Bound=50"
  one exact $np --input "$B" --set "Contact/Fixed Point=Exact"
  one paper $np --input "$B" --set "Contact/Slip Bound Test=Paper" --set "Mesh/Subdomains Per Brick=4x2x2"
  one noPreconditioner $np --input "$B" --set "FETI/Preconditioner=None"
  one lumped $np --input "$B" --set "FETI/Preconditioner=Lumped" --set "Contact/F1=0.1"
  one cylinderCoulomb $np --input "$SRC/input/hertz_cylinder.xml" --set "Contact/Friction Model=Coulomb" \
    --set "Mesh/File=meshes/hertz_cylinder_h0.2.exo"
  one capped $np --input "$B" --set "Solver/Max Outer Iterations=2"
  one openGap $np --input "$B" --set "Mesh/Initial Gap=0.01"
  one orthotropicExact $np --input "$SRC/input/two_bricks_orthotropic.xml" --set "Contact/Fixed Point=Exact"
done
