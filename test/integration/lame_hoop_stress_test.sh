#!/bin/sh
# CTest integration.lameHoopStress.<kind>: the nodal stresses at a boundary follow the field,
# not the means of the elements beside it. A plane-strain shrink fit (shrink_fit.xml; the mesh
# from shrink_fit_mesh.py, hexahedra or 10-node tetrahedra, 2 mm radially, non-matching on the
# interface): the hub's nodal hoop stress at every node of its bore and of its outer radius
# against Lame's, within 2 %. A node on a surface has its elements on one side only: the mean
# of their element stresses is the stress about half an element inside, 7 to 8 % below Lame's at
# the bore, where the hoop stress falls fastest (1/r^2). The 10-node tetrahedra extrapolate
# from their quadrature points (linear strains fitted at 4 points: 0.6 % here). The
# hexahedra's 2 x 2 x 2 Gauss points are no Barlow points: extrapolated from them the stress
# is 5.3 % above Lame's at the bore; the patch recovery (a quadratic fitted to the
# displacements of the nodes around, stack/PatchRecovery.hpp) is within 0.5 %.
#
# Lame, plane strain (E' = E / (1 - nu^2), nu' = nu / (1 - nu) in the plane-stress formulas),
# a hollow shaft (a, b) in a hub (b, c), the same material, radial interference delta: the
# pressure p moves the hub's bore out by u_hub = (b p / E') ((c^2 + b^2) / (c^2 - b^2) + nu')
# and the shaft's surface in by u_shaft = (b p / E') ((b^2 + a^2) / (b^2 - a^2) - nu'); their
# sum is delta (nu' cancels):
#   p = E' delta / (b [(c^2 + b^2) / (c^2 - b^2) + (b^2 + a^2) / (b^2 - a^2)])  = 34.615 MPa
# and in the hub sigma_theta(r) = p b^2 / (c^2 - b^2) (1 + c^2 / r^2): 57.69 MPa at r = b,
# 2 p b^2 / (c^2 - b^2) = 23.08 MPa at r = c (each node is compared at its own radius: the
# midside nodes of the tetrahedra lie on the straight edges, inside the circles).
# Needs Debian's python3 with netCDF4 and meshio (python3-netcdf4, python3-meshio); exit 77
# (CTest: skipped) without them.
# Usage: lame_hoop_stress_test.sh TRIBOS SOURCE_DIR hex8|tet10
set -u
tribos=$1 source=$2 kind=$3
here=$source/test/integration
case $kind in
hex8) tolerance=0.02 ;;
tet10) tolerance=0.02 ;;
*) echo "unknown element type $kind (hex8 or tet10)"; exit 1 ;;
esac
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
/usr/bin/python3 -c "import netCDF4, meshio" 2>/dev/null ||
  { echo "skipped: /usr/bin/python3 lacks netCDF4 or meshio (python3-netcdf4, python3-meshio)"; exit 77; }
/usr/bin/python3 "$here/shrink_fit_mesh.py" "$dir/mesh.exo" "$kind" || exit 1
"$tribos" --input "$here/shrink_fit.xml" --set "Mesh/File=$dir/mesh.exo" --set Solver/Verbose=false \
  --output "$dir/r.exo" --summary "$dir/s.json" > "$dir/run.log" 2>&1 ||
  { cat "$dir/run.log"; echo "tribos failed on the shrink fit ($kind)"; exit 1; }
/usr/bin/python3 - "$dir/r.exo" "$dir/s.json" "$kind" "$tolerance" <<'PY'
import json
import sys

import netCDF4
import numpy as np

path, summary_path, kind, tolerance = sys.argv[1:]
TOLERANCE = float(tolerance)
A, B, C, DELTA, T = 10.0, 20.0, 40.0, 0.01, 2.0  # shrink_fit_mesh.py
E, NU = 210000.0, 0.3                            # shrink_fit.xml

d = netCDF4.Dataset(path)
text = lambda rows: ["".join(c.decode() for c in row if c) for row in rows]
names = text(d.variables["name_nod_var"][:].data)
var = lambda name: np.array(d.variables["vals_nod_var%d" % (names.index(name) + 1)][-1].data)
x, y, z = (np.array(d.variables["coord" + k][:].data) for k in "xyz")
r, theta = np.hypot(x, y), np.arctan2(y, x)
s, c = np.sin(theta), np.cos(theta)
sxx, syy, sxy = var("nodal_stress_xx"), var("nodal_stress_yy"), var("nodal_stress_xy")
hoop = sxx * s * s + syy * c * c - 2 * sxy * s * c
radial = sxx * c * c + syy * s * s + 2 * sxy * s * c
blocks = text(d.variables["eb_names"][:].data) if "eb_names" in d.variables else []
# The hub: the nodes of block_1 (shrink_fit_mesh.py writes the shaft first).
hub_block = blocks.index("block_1") + 1 if "block_1" in blocks else 2
hub = np.unique(np.array(d.variables["connect%d" % hub_block][:].data).ravel() - 1)
shaft = np.unique(np.array(d.variables["connect%d" % (3 - hub_block)][:].data).ravel() - 1)
sets = text(d.variables["ns_names"][:].data)
node_set = lambda name: np.array(d.variables["node_ns%d" % (sets.index(name) + 1)][:].data) - 1
bore = node_set("hub_bore")
outer = node_set("hub_outer")
inner = shaft[r[shaft] < A + 1e-9]
if not (np.isin(bore, hub).all() and np.isin(outer, hub).all() and len(np.intersect1d(hub, shaft)) == 0):
    sys.exit("block_1 is not the hub")

E1 = E / (1 - NU * NU)
p = E1 * DELTA / (B * ((C * C + B * B) / (C * C - B * B) + (B * B + A * A) / (B * B - A * A)))
lame_hub = lambda rr: p * B * B / (C * C - B * B) * (1 + C * C / (rr * rr))
lame_shaft = lambda rr: -p * B * B / (B * B - A * A) * (1 + A * A / (rr * rr))
print("%s: %d nodes; Lame: contact pressure %.4f MPa, hub hoop stress %.4f MPa at r = b, %.4f at r = c"
      % (kind, len(r), p, lame_hub(B), lame_hub(C)))


def compare(label, nodes, lame):
    expected = lame(r[nodes])
    error = np.abs(hoop[nodes] - expected) / np.abs(expected)
    worst = nodes[np.argmax(error)]
    print("%s: %d nodes, nodal hoop stress %.4f .. %.4f (Lame %.4f .. %.4f); relative error max %.2f %% "
          "(r = %.4f, theta = %.2f deg, z = %.2f), mean %.2f %%"
          % (label, len(nodes), hoop[nodes].min(), hoop[nodes].max(), expected.min(), expected.max(),
             100 * error.max(), r[worst], np.degrees(theta[worst]),
             z[worst], 100 * error.mean()))
    return error.max()


errors = {"hub bore": compare("hub bore (r = b)", bore, lame_hub),
          "hub outside": compare("hub outside (r = c)", outer, lame_hub)}
compare("shaft bore (r = a), not checked", inner, lame_shaft)
implied = hoop[bore] * (C * C - B * B) / (C * C + B * B)
print("contact pressure: from the bore's hoop stress %.4f (Lame %.4f); hub's nodal radial stress at the bore "
      "%.4f .. %.4f" % (implied.mean(), p, -radial[bore].max(), -radial[bore].min()))
if "contact_pressure" in names:
    slaves = node_set("shaft_outer")
    pressure = var("contact_pressure")[slaves]
    print("contact_pressure at the %d shaft_outer nodes: %.4f .. %.4f, mean %.4f"
          % (len(slaves), pressure.min(), pressure.max(), pressure.mean()))
# The contact itself, whatever the stresses: the interface's normal force is p times the
# bore's area on the quarter model, pi b / 2 x T (all slave nodes paired and pressed).
summary = json.load(open(summary_path))
force = sum(i["normal_force"] for i in summary["interfaces"])
expected_force = p * np.pi * B * T / 2
force_error = abs(force - expected_force) / expected_force
print("normal contact force %.2f N (Lame: p pi b T / 2 = %.2f N, %.2f %% off); %d slave nodes, %d without contact"
      % (force, expected_force, 100 * force_error, summary["contact_nodes_paired"],
         summary["contact_nodes"]["no_contact"]))
if not force_error <= 0.02:
    sys.exit("%s: the normal contact force is off Lame's by more than 2 %%" % kind)
failed = [label for label, error in errors.items() if not error <= TOLERANCE]  # NaN fails
if failed:
    sys.exit("%s: the nodal hoop stress is off Lame's by more than %g %%: %s"
             % (kind, 100 * TOLERANCE, ", ".join(failed)))
PY
