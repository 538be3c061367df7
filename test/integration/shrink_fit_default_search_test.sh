#!/bin/sh
# CTest integration.shrinkFitAtTheDefaultSearchDistance.<kind> (issue 41): the plane-strain shrink
# fit of lame_hoop_stress_test.sh (shrink_fit.xml, its 0.01 mm interference an initial overlap)
# at Contact/Search Distance 1e-6 (the default until 2026-12-08), far below the interference, gives
# the answer of Search Distance 0.1: every slave node lies inside the hub and is paired whatever
# the distance (it was "0 slave nodes paired", no contact force, exit 0 with the bodies
# overlapping); so does today's default (0: the slave surface's largest face). Checks: the runs
# converge, the same pairs, every one of them beyond 1e-6, the same normal force to 1e-9.
# And the same fit on nominal geometry (the shaft's surface on the bore, shrink_fit_mesh.py
# --delta 0) with Contact/Interference = 0.01: the mean contact pressure within 1 % of Lame's
# (34.615 MPa, lame_hoop_stress_test.sh) and of the overlapping geometry's.
# Needs Debian's python3 with netCDF4 and meshio; exit 77 (CTest: skipped) without them.
# Usage: shrink_fit_default_search_test.sh TRIBOS SOURCE_DIR hex8|tet10
set -u
tribos=$1 source=$2 kind=$3
here=$source/test/integration
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
/usr/bin/python3 -c "import netCDF4, meshio" 2>/dev/null ||
  { echo "skipped: /usr/bin/python3 lacks netCDF4 or meshio (python3-netcdf4, python3-meshio)"; exit 77; }
/usr/bin/python3 "$here/shrink_fit_mesh.py" "$dir/mesh.exo" "$kind" || exit 1
for distance in 0.1 1e-6 0; do
  "$tribos" --input "$here/shrink_fit.xml" --set "Mesh/File=$dir/mesh.exo" --set Solver/Verbose=false \
    --set "Contact/Search Distance=$distance" --summary "$dir/s$distance.json" > "$dir/run$distance.log" 2>&1 ||
    { cat "$dir/run$distance.log"; echo "tribos failed on the shrink fit ($kind) at Search Distance $distance"; exit 1; }
done
/usr/bin/python3 "$here/shrink_fit_mesh.py" "$dir/nominal.exo" "$kind" --delta 0 || exit 1
"$tribos" --input "$here/shrink_fit.xml" --set "Mesh/File=$dir/nominal.exo" --set Solver/Verbose=false \
  --set "Contact/Interference=0.01" --summary "$dir/nominal.json" > "$dir/nominal.log" 2>&1 ||
  { cat "$dir/nominal.log"; echo "tribos failed on the nominal shrink fit ($kind) with Interference 0.01"; exit 1; }
grep "slave nodes paired" "$dir/run1e-6.log" "$dir/nominal.log"
/usr/bin/python3 - "$dir/s0.1.json" "$dir/s1e-6.json" "$kind" "$dir/nominal.json" "$dir/s0.json" <<'PY'
import json
import math
import sys

wide, default = (json.load(open(p)) for p in sys.argv[1:3])
kind = sys.argv[3]
nominal = json.load(open(sys.argv[4]))
derived = json.load(open(sys.argv[5]))
w, d = wide["contact_search"][0], default["contact_search"][0]
force = (wide["total_normal_force"], default["total_normal_force"])
print("%s: Search Distance 0.1: %d paired, normal force %.9g; 1e-6: %d paired (%d inside beyond the "
      "distance), normal force %.9g" % (kind, w["paired"], force[0], d["paired"], d["paired_inside_beyond_search_distance"],
                                        force[1]))
ok = wide["converged"] and default["converged"]
ok &= w["paired"] == d["paired"] > 0 and d["unpaired"] == 0
ok &= d["paired_inside_beyond_search_distance"] == d["paired"]
ok &= abs(force[1] - force[0]) <= 1e-9 * abs(force[0]) and force[0] > 0
print("%s: the default Search Distance (0: derived): %d paired, normal force %.9g"
      % (kind, derived["contact_search"][0]["paired"], derived["total_normal_force"]))
ok &= derived["converged"] and derived["contact_search"][0]["paired"] == w["paired"]
ok &= abs(derived["total_normal_force"] - force[0]) <= 1e-9 * abs(force[0])
if not ok:
    sys.exit("%s: the default Search Distance does not give the answer of 0.1" % kind)
B, T, LAME = 20.0, 2.0, 34.615  # shrink_fit_mesh.py; Lame's plane-strain pressure (lame_hoop_stress_test.sh)
area = 0.5 * math.pi * B * T    # the quarter of the bore
mean = {name: run["total_normal_force"] / area for name, run in (("overlap", wide), ("interference", nominal))}
print("%s: mean contact pressure, geometric overlap %.4f MPa, Interference on nominal geometry %.4f MPa, Lame %.3f"
      % (kind, mean["overlap"], mean["interference"], LAME))
if not nominal["converged"] or nominal["contact_search"][0]["interference"] != 0.01:
    sys.exit("%s: the nominal fit with Interference 0.01 did not converge or does not report it" % kind)
for name, p in mean.items():
    if abs(p / LAME - 1.0) > 0.01:
        sys.exit("%s: the mean pressure with the %s is %.4f, more than 1 %% from Lame's %.3f" % (kind, name, p, LAME))
PY
