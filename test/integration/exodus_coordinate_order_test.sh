#!/bin/sh
# CTest integration.badMesh.aCoordinateArrayStoredFirst (issue 44): an Exodus file whose first
# netCDF variable is a coordinate array (valid netCDF: ncgen and scipy write files so) is read by
# Debian's Exodus library 6.02 with that coordinate all zero, and was reported as "element 1 is
# degenerate". input/meshes/block_on_plate.exo rewritten with coordx, coordy, coordz first: exit
# 2 saying what happened and what to do. Needs Debian's python3 with netCDF4; exit 77 (CTest:
# skipped) without it.
# Usage: exodus_coordinate_order_test.sh TRIBOS SOURCE_DIR
set -u
tribos=$1 source=$2
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
/usr/bin/python3 -c "import netCDF4" 2>/dev/null ||
  { echo "skipped: /usr/bin/python3 lacks netCDF4 (python3-netcdf4)"; exit 77; }
/usr/bin/python3 - "$source/input/meshes/block_on_plate.exo" "$dir/reordered.exo" <<'PY' || exit 1
import sys

import netCDF4

src = netCDF4.Dataset(sys.argv[1])
dst = netCDF4.Dataset(sys.argv[2], "w", format=src.data_model)
dst.setncatts({k: src.getncattr(k) for k in src.ncattrs()})
for name, dim in src.dimensions.items():
    dst.createDimension(name, None if dim.isunlimited() else len(dim))
coords = [n for n in src.variables if n in ("coordx", "coordy", "coordz")]
for name in coords + [n for n in src.variables if n not in coords]:
    v = src.variables[name]
    w = dst.createVariable(name, v.datatype, v.dimensions)
    w.setncatts({k: v.getncattr(k) for k in v.ncattrs()})
    v.set_auto_maskandscale(False)
    w.set_auto_maskandscale(False)
    w[:] = v[:]
dst.close()
PY
status=0
"$tribos" --input "$source/input/block_on_plate.xml" --set "Mesh/File=$dir/reordered.exo" --dry-run \
  > "$dir/out.log" 2>&1 || status=$?
cat "$dir/out.log"
[ "$status" -eq 2 ] || { echo "FAILED: exit $status, 2 expected"; exit 1; }
grep -q "reordered.exo: every node has x = 0: a flat mesh, or coordinates this Exodus library could not read" \
  "$dir/out.log" || { echo "FAILED: the message does not say what happened"; exit 1; }
