#!/bin/sh
# CTest integration.shrinkFitFriction.<kind> (issue 41): the plane-strain shrink fit of
# lame_hoop_stress_test.sh (shrink_fit.xml, non-matching faceted interface: the shaft's faces are
# halves of the hub's) with Coulomb friction, F = 0.3. Lame's solution slips nowhere and has no
# tangential traction; a frame whose normal leans away from the direction in which the
# interference closes reads that closing as a slip of the interference times the lean, which
# the stick condition then holds with spurious friction (it was 6.7 % of F N on hexahedra,
# 61 % on 4-node tetrahedra, 68 % on 10-node ones, with 4 to 14 nodes reported slipping).
# Checks: converged; every contact node sticks; the normal force within 1 % of Lame's
# (34.615 MPa on the bore, lame_hoop_stress_test.sh); sum |f_t| / (F N) within the kind's bound
# (measured with the angle-weighted nodal normals in symmetry planes: 0.05 % hex8, 4.6 %
# tet10, 11.8 % tet4, whose coarse one-layer tetrahedra deform tangentially by 1e-5 mm
# without friction). tet10curved: 10-node tetrahedra whose faces follow the circles
# (shrink_fit_mesh.py --curved, as gmsh's second-order meshes), 8.5 % (the chord normals
# before: 68 %, 146 of 291 nodes slipping).
# Needs Debian's python3 with meshio and netCDF4 (its Exodus writer); exit 77 (CTest: skipped)
# without them.
# Usage: shrink_fit_friction_test.sh TRIBOS SOURCE_DIR hex8|tet4|tet10|tet10curved
set -u
tribos=$1 source=$2 kind=$3
here=$source/test/integration
case $kind in
hex8) bound=0.002 ;;
tet10) bound=0.06 ;;
tet4) bound=0.15 ;;
tet10curved) bound=0.12 ;;
*) echo "unknown element type $kind (hex8, tet4, tet10 or tet10curved)"; exit 1 ;;
esac
mesh_options=$kind
[ "$kind" = tet10curved ] && mesh_options="tet10 --curved"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
/usr/bin/python3 -c "import netCDF4, meshio" 2>/dev/null ||
  { echo "skipped: /usr/bin/python3 lacks netCDF4 or meshio (python3-netcdf4, python3-meshio)"; exit 77; }
# shellcheck disable=SC2086 # the element type and its option
/usr/bin/python3 "$here/shrink_fit_mesh.py" "$dir/mesh.exo" $mesh_options || exit 1
"$tribos" --input "$here/shrink_fit.xml" --set "Mesh/File=$dir/mesh.exo" --set Solver/Verbose=false \
  --set "Contact/Friction Model=Coulomb" --set "Contact/F1=0.3" \
  --summary "$dir/s.json" > "$dir/run.log" 2>&1 ||
  { cat "$dir/run.log"; echo "tribos failed on the shrink fit with Coulomb friction ($kind)"; exit 1; }
/usr/bin/python3 - "$dir/s.json" "$kind" "$bound" <<'PY'
import json
import math
import sys

summary = json.load(open(sys.argv[1]))
kind, bound = sys.argv[2], float(sys.argv[3])
B, T, LAME, F = 20.0, 2.0, 34.615, 0.3  # shrink_fit_mesh.py; Lame's pressure; the coefficient set
interface = summary["interfaces"][0]
normal, friction = interface["normal_force"], interface["friction_force"]
lame_force = LAME * 0.5 * math.pi * B * T
ratio = friction / (F * normal)
print("%s: %d stick, %d slip, %d no contact; normal force %.6g (Lame %.6g, %+.3f %%), sum |f_t| / (F N) = %.3g %% "
      "(bound %.3g %%)" % (kind, interface["stick"], interface["slip"], interface["no_contact"], normal, lame_force,
                           100 * (normal / lame_force - 1), 100 * ratio, 100 * bound))
ok = summary["converged"] and interface["slip"] == 0 and interface["no_contact"] == 0 and interface["stick"] > 0
ok &= abs(normal / lame_force - 1) <= 0.01 and ratio <= bound
sys.exit(0 if ok else "%s: the shrink fit with Coulomb friction is not Lame's (no slip, no friction)" % kind)
PY
