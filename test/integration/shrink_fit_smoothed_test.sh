#!/bin/sh
# CTest integration.shrinkFitSmoothed.<kind> (issue 41): the plane-strain shrink fit of
# shrink_fit.xml meshed as from CAD (input/meshes/shrink_fit.geo: both contact surfaces true
# circles, the shaft's elements 1 mm, the hub's 1.3 mm, linear elements). The facets sag by
# h^2 / (8 R) = 0.006 mm between their nodes, as much as the 0.01 mm interference: measured
# between the faces as meshed (Contact/Surface Geometry = Faceted) the fit force is 43 % (tet4)
# and 26 % (hex8) above Lame's, with nodes out of contact; between the smoothed surfaces (Nagata,
# geometry/SmoothedFaces.hpp) 0.21 % and 0.10 %.
# Checks, Coulomb F = 0.3: Faceted is off by more than 5 % (9.6 % on tet4fine; what the option
# is for) and its report points to the option (the master's facets sag by most of the initial overlap); the default
# (Surface Geometry = Automatic) chooses the smoothed surfaces, says so, and gives the answer of
# Smoothed: converged, every contact node sticks, the normal force within 1 % of Lame's, sum |f_t| / (F N)
# and the nodal pressure spread (max - min) / mean within the kind's bounds (measured: tet4
# 4.6 % and 8.0 %, hex8 0.51 % and 1.9 %).
# Two more meshes hold the issue's acceptance bounds (spread 5 %, friction 2 %):
# - tet4fine: 4-node tetrahedra at half the sizes with 4 layers through T (hs 0.5, hh 0.65, nl 4;
#   measured 4.7 % and 1.77 %; at h = 1 the tetrahedra's own tangential displacements exceed them:
#   doc/contact_surfaces.md);
# - tet10: gmsh's 10-node tetrahedra (-order 2, mid-edge nodes on the circles, h = 1): their 6-node
#   faces keep their quadratic geometry, so the default stays faceted (measured 2.4 %, 0.65 %).
# Needs Debian's python3 with netCDF4 (the nodal pressures); exit 77 (CTest: skipped) without.
# Usage: shrink_fit_smoothed_test.sh TRIBOS SOURCE_DIR tet4|hex8|tet4fine|tet10
set -u
tribos=$1 source=$2 kind=$3
meshes=$source/input/meshes
# the mesh, the bounds on friction and spread, the surfaces the default chooses
case $kind in
tet4) mesh=$meshes/shrink_fit_gmsh_tet4_h1.exo friction=0.06 spread=0.10 chosen=Smoothed ;;
hex8) mesh=$meshes/shrink_fit_gmsh_hex8_h1.exo friction=0.01 spread=0.03 chosen=Smoothed ;;
tet4fine) mesh=$meshes/shrink_fit_gmsh_tet4_h0.5.exo friction=0.02 spread=0.05 chosen=Smoothed ;;
tet10) mesh=$meshes/shrink_fit_gmsh_tet10_h1.exo friction=0.02 spread=0.05 chosen=Faceted ;;
*) echo "unknown mesh $kind (tet4, hex8, tet4fine or tet10)"; exit 1 ;;
esac
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
/usr/bin/python3 -c "import netCDF4" 2>/dev/null ||
  { echo "skipped: /usr/bin/python3 lacks netCDF4 (python3-netcdf4)"; exit 77; }
for geometry in Faceted Smoothed Automatic; do
  "$tribos" --input "$source/test/integration/shrink_fit.xml" --set "Mesh/File=$mesh" --set Solver/Verbose=false \
    --set "Contact/Friction Model=Coulomb" --set "Contact/F1=0.3" \
    --set "$([ $geometry = Automatic ] && echo Solver/Verbose=false || echo "Contact/Surface Geometry=$geometry")" \
    --summary "$dir/$geometry.json" --output "$dir/$geometry.exo" > "$dir/$geometry.log" 2>&1 ||
    { cat "$dir/$geometry.log"; echo "tribos failed on the gmsh shrink fit ($kind, $geometry)"; exit 1; }
done
# Linear faces: the faceted run says what to set (the master's sag is most of the interference);
# the smoothed one does not; the default says it chose the smoothed surfaces.
if [ $chosen = Smoothed ]; then
  grep -q "sag counts as gap; set Contact/Surface Geometry = Smoothed" "$dir/Faceted.log" ||
    { echo "the faceted run does not point to Surface Geometry = Smoothed"; exit 1; }
  if grep -q "sag counts as gap" "$dir/Smoothed.log"; then echo "the smoothed run reports a facet sag"; exit 1; fi
  grep -q "gaps measured on the smoothed surfaces (Contact/Surface Geometry = Automatic" "$dir/Automatic.log" ||
    { echo "the default run does not say it chose the smoothed surfaces"; exit 1; }
fi
/usr/bin/python3 - "$dir" "$kind" "$friction" "$spread" "$chosen" <<'PY'
import json
import math
import sys

import netCDF4
import numpy

folder, kind, chosen = sys.argv[1], sys.argv[2], sys.argv[5]
friction_bound, spread_bound = float(sys.argv[3]), float(sys.argv[4])
LAME_FORCE = 34.615 * 0.5 * math.pi * 20.0 * 2.0  # Lame's pressure on the quarter bore, T = 2
F = 0.3


def outcome(geometry):
    summary = json.load(open("%s/%s.json" % (folder, geometry)))
    interface = summary["interfaces"][0]
    exo = netCDF4.Dataset("%s/%s.exo" % (folder, geometry))
    names = ["".join(c.decode() for c in name if c) for name in exo.variables["name_nod_var"][:].filled(b"")]
    pressure = numpy.array(exo.variables["vals_nod_var%d" % (names.index("contact_pressure") + 1)][-1, :])
    pressure = pressure[pressure > 0.0]
    normal = interface["normal_force"]
    result = {"converged": summary["converged"], "geometry": summary["contact_search"][0]["surface_geometry"], "force": normal / LAME_FORCE - 1,
              "friction": interface["friction_force"] / (F * normal),
              "spread": (pressure.max() - pressure.min()) / pressure.mean(),
              "stick": interface["stick"], "slip": interface["slip"], "open": interface["no_contact"]}
    print("%s %s: %d stick, %d slip, %d no contact; force %+.2f %% of Lame's, sum |f_t| / (F N) %.3g %%, "
          "nodal pressure spread %.3g %%" % (kind, geometry, result["stick"], result["slip"], result["open"],
                                               100 * result["force"], 100 * result["friction"], 100 * result["spread"]))
    return result


faceted, smoothed, automatic = outcome("Faceted"), outcome("Smoothed"), outcome("Automatic")
ok = automatic["geometry"] == chosen and automatic["force"] == (smoothed if chosen == "Smoothed" else faceted)["force"]
if chosen == "Smoothed":
    ok &= abs(faceted["force"]) > 0.05
else:  # 6-node faces: the option changes nothing
    ok &= faceted["force"] == smoothed["force"]
ok &= smoothed["converged"] and smoothed["slip"] == 0 and smoothed["open"] == 0 and smoothed["stick"] > 0
ok &= abs(smoothed["force"]) <= 0.01 and smoothed["friction"] <= friction_bound and smoothed["spread"] <= spread_bound
sys.exit(0 if ok else "%s: the smoothed shrink fit is not Lame's (bounds: force 1 %%, friction %.3g %%, spread %.3g %%)"
         % (kind, 100 * friction_bound, 100 * spread_bound))
PY
