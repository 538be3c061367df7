#!/bin/sh
# CTest integration.pushOut.<kind>: a shaft pushed out of its hub by prescribed displacements
# of its end faces takes the whole friction force F N (issue 42; the box version is
# displacementConditions.aPushOutByPrescribedEndDisplacementsTakesTheWholeFrictionForce).
# The shrink fit of lame_hoop_stress_test.sh, curved and non-matching (shrink_fit_mesh.py:
# 4 layers, 8 mm along z; hexahedra, or 10-node tetrahedra on coarser cells to keep the run
# short), without the plane-strain conditions (push_out.xml): the hub's face z = 0 held along
# z, the shaft's face z = 0 moved by u_z = +0.05 mm, Coulomb F = 0.15. The end rings of both
# bodies at z = 0 are held along z at different values: before the fix their nodes carried no
# friction and the push force fell short by their share of F N (the ring's share of N: about
# 12 % on the hexahedra, 8 % on the tetrahedra).
# Checks: the run converges; every slave node is paired, in contact and slides (the
# interface's counts and contact_status = 2 at every node of shaft_outer); the push force,
# the sum of reaction_z over the shaft's face z = 0 (and the summary's reaction of the
# condition "push"), is F N within 1 %, N the interface's normal force, and the hub's held
# face takes it back. N is only checked to be positive: with free ends the fit is no plane
# strain; Lame's plane-strain and plane-stress forces p pi b T / 2 are printed for reference.
# Needs Debian's python3 with netCDF4 and meshio (python3-netcdf4, python3-meshio); exit 77
# (CTest: skipped) without them.
# Usage: push_out_test.sh TRIBOS SOURCE_DIR hex8|tet10
set -u
tribos=$1 source=$2 kind=$3
here=$source/test/integration
case $kind in
hex8) cells="" ;;
tet10) cells="--hub-cells 5 12 --shaft-cells 3 24" ;;
*) echo "unknown element type $kind (hex8 or tet10)"; exit 1 ;;
esac
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
/usr/bin/python3 -c "import netCDF4, meshio" 2>/dev/null ||
  { echo "skipped: /usr/bin/python3 lacks netCDF4 or meshio (python3-netcdf4, python3-meshio)"; exit 77; }
# shellcheck disable=SC2086 # $cells: separate words
/usr/bin/python3 "$here/shrink_fit_mesh.py" "$dir/mesh.exo" "$kind" --layers 4 --thickness 8 $cells || exit 1
"$tribos" --input "$here/push_out.xml" --set "Mesh/File=$dir/mesh.exo" --set Solver/Verbose=false \
  --output "$dir/r.exo" --summary "$dir/s.json" > "$dir/run.log" 2>&1 ||
  { cat "$dir/run.log"; echo "tribos failed on the push-out ($kind)"; exit 1; }
/usr/bin/python3 - "$dir/r.exo" "$dir/s.json" "$kind" <<'PY'
import json
import sys

import netCDF4
import numpy as np

path, summary_path, kind = sys.argv[1:]
A, B, C, DELTA, T = 10.0, 20.0, 40.0, 0.01, 8.0  # shrink_fit_mesh.py, --thickness 8
E, NU, F = 210000.0, 0.3, 0.15                    # push_out.xml

d = netCDF4.Dataset(path)
text = lambda rows: ["".join(c.decode() for c in row if c) for row in rows]
names = text(d.variables["name_nod_var"][:].data)
var = lambda name: np.array(d.variables["vals_nod_var%d" % (names.index(name) + 1)][-1].data)
sets = text(d.variables["ns_names"][:].data)
node_set = lambda name: np.array(d.variables["node_ns%d" % (sets.index(name) + 1)][:].data) - 1
summary = json.load(open(summary_path))
failures = []


def check(ok, message):
    if not ok:  # NaN fails
        failures.append(message)


interface = summary["interfaces"][0]
N = interface["normal_force"]
slaves = node_set("shaft_outer")
reaction_z = var("reaction_z")
push = reaction_z[node_set("shaft_z0")].sum()
held = reaction_z[node_set("hub_z0")].sum()
push_summary = summary["reactions"]["push"][2]
ratio = push / (F * N)
print("%s: push force %.4f N (summary: %.4f), F N = %.2f x %.4f = %.4f N: push / (F N) = %.6f; hub's face "
      "z = 0 takes %.4f N; interface friction force %.4f N"
      % (kind, push, push_summary, F, N, F * N, ratio, held, interface["friction_force"]))
# Lame's contact pressure, for reference only: plane strain (E' = E / (1 - nu^2); the nu'
# terms cancel for one material) and plane stress (E); the free 8 mm slab lies between.
geometry = B * ((C * C + B * B) / (C * C - B * B) + (B * B + A * A) / (B * B - A * A))
area = np.pi * B * T / 2
for label, modulus in (("plane strain", E / (1 - NU * NU)), ("plane stress", E)):
    p = modulus * DELTA / geometry
    print("  Lame %s (reference, not checked): p = %.3f MPa, p pi b T / 2 = %.2f N; N / that = %.4f"
          % (label, p, p * area, N / (p * area)))
status = var("contact_status")[slaves]
print("  %d slave nodes: %d paired, %d unpaired; interface: %d no contact, %d stick, %d slip; contact_status "
      "2 (slip) at %d; all interfaces' totals: %s; %s"
      % (len(slaves), summary["contact_nodes_paired"], summary["contact_nodes_unpaired"], interface["no_contact"],
         interface["stick"], interface["slip"], np.count_nonzero(status == 2), summary["contact_nodes"],
         summary["message"]))
check(summary["converged"], "not converged: %s" % summary["message"])
check(N > 0, "no normal force (N = %g)" % N)
check(abs(ratio - 1) <= 0.01, "the push force is not F N within 1 %% (push / (F N) = %.6f)" % ratio)
check(abs(push_summary - push) <= 1e-6 * abs(push), "the summary's reaction of \"push\" is not the sum of reaction_z")
check(abs(held + push) <= 0.01 * abs(push), "the hub's held face does not take the push force back")
check(summary["contact_nodes_unpaired"] == 0 and summary["contact_nodes_paired"] == len(slaves),
      "not every node of shaft_outer is paired")
check(interface["slip"] == len(slaves) and interface["stick"] == 0 and interface["no_contact"] == 0,
      "not every contact node slides (interface counts)")
check(np.all(status == 2), "contact_status is not 2 (slip) at every slave node: %d are not"
      % np.count_nonzero(status != 2))
if failures:
    sys.exit("%s: %s" % (kind, "; ".join(failures)))
PY
