#!/bin/sh
# CTest integration.plotResults.<type>: doc/tools/plot_results.py on a result of one element
# type (issue 42: the tool knew tetrahedron faces only and stopped with an IndexError on
# hexahedra): the Hertz cylinder on its hexahedral or 10-node tetrahedral mesh (every picture
# of a contact run), the prism cantilever (the deformed shape; no contact). Every picture must
# be a non-empty PNG. Exit 77 (CTest: skipped) without matplotlib or ncdump, as
# plot_results_test.sh.
# Usage: plot_element_types_test.sh TRIBOS PYTHON SOURCE_DIR hex8|tet10|wedge6
set -u
tribos=$1 python=$2 source=$3 kind=$4
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$python" -c "import matplotlib" 2>/dev/null && command -v ncdump >/dev/null ||
  { echo "skipped: $python lacks matplotlib or ncdump is missing (apt-get install python3-matplotlib netcdf-bin)"; exit 77; }
case $kind in
hex8) scene=hertz_cylinder.xml mesh=meshes/hertz_cylinder_hex_h0.4.exo pictures="contact_stress convergence deformed" ;;
tet10) scene=hertz_cylinder.xml mesh=meshes/hertz_cylinder_tet10_h0.4.exo pictures="contact_stress convergence deformed" ;;
wedge6) scene=cantilever_wedge6.xml mesh= pictures="deformed" ;;
*) echo "unknown element type $kind"; exit 1 ;;
esac
set -- --input "$source/input/$scene" --set Solver/Verbose=false --output "$dir/r.exo" --summary "$dir/s.json"
[ -n "$mesh" ] && set -- "$@" --set "Mesh/File=$mesh"
"$tribos" "$@" > "$dir/run.log" 2>&1 || { cat "$dir/run.log"; echo "tribos failed on $scene ($kind)"; exit 1; }
"$python" "$source/doc/tools/plot_results.py" "$dir/r.exo" "$dir/s.json" "$dir/pictures" || exit 1
. "$(dirname "$0")/png_check.sh"
# shellcheck disable=SC2086 # the names are words
png "$dir/pictures" $pictures
