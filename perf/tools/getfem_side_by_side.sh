#!/usr/bin/env bash
# Side-by-side wall time of Tribos and GetFEM on the Hertz line-contact cylinder
# (input/hertz_cylinder.xml) on the SAME Exodus mesh.
#
#   perf/tools/getfem_side_by_side.sh MESH FRICTION [RUNS]
#     MESH      Exodus file: absolute, relative to the current directory, or relative to input/
#               (e.g. meshes/hertz_cylinder_hex_h0.1.exo)
#     FRICTION  None | Coulomb (Coulomb: friction coefficient 0.2 in both codes)
#     RUNS      number of alternating Tribos / GetFEM runs (default 3)
#   Environment: TRIBOS (default build/bin/tribos), PYTHON (default /usr/bin/python3),
#                TRIBOS_THREADS (OMP_NUM_THREADS of Tribos, default 2).
#
# What it measures: the wall time of each whole process (date +%s.%N before and after), i.e.
# start-up, mesh reading, assembly and solve, for Tribos (FETI + SMALSE-M, OMP_NUM_THREADS=2)
# and for perf/tools/getfem_hertz_cylinder.py (GetFEM nodal contact between non-matching meshes,
# Newton + direct solver, OMP_NUM_THREADS=1); the two alternate RUNS times and the minimum of each
# is reported, with Tribos's pfp_applications and total_normal_force (summary JSON), GetFEM's
# normal force, Newton iterations and in-process set-up+solve seconds, and the ratio tribos/getfem
# of the minimum wall times. Run it from the repository root (or anywhere: it cds there).
# Exit status 77 when python3-getfem is not installed (a CTest can treat that as skipped).
set -u
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
if [ $# -lt 2 ]; then
  sed -n '2,20p' "$0" >&2
  exit 2
fi
mesh_arg=$1
friction=$2
runs=${3:-3}
PYTHON=${PYTHON:-/usr/bin/python3}
TRIBOS=${TRIBOS:-$root/build/bin/tribos}
case "$friction" in None|Coulomb) ;; *) echo "FRICTION must be None or Coulomb" >&2; exit 2;; esac

if ! "$PYTHON" -c 'import getfem' >/dev/null 2>&1; then
  echo "getfem_side_by_side: python3-getfem not available; skipped" >&2
  exit 77
fi
[ -x "$TRIBOS" ] || { echo "tribos not found: $TRIBOS" >&2; exit 1; }

if [ "${mesh_arg#/}" != "$mesh_arg" ]; then mesh=$mesh_arg
elif [ -f "$mesh_arg" ]; then mesh=$(cd "$(dirname "$mesh_arg")" && pwd)/$(basename "$mesh_arg")
elif [ -f "$root/input/$mesh_arg" ]; then mesh=$root/input/$mesh_arg
else echo "mesh not found: $mesh_arg" >&2; exit 1
fi
[ -f "$mesh" ] || { echo "mesh not found: $mesh" >&2; exit 1; }

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$root" || exit 1

now() { date +%s.%N; }
tmin=""; gmin=""
for ((i = 1; i <= runs; i++)); do
  t0=$(now)
  OMP_NUM_THREADS=${TRIBOS_THREADS:-2} "$TRIBOS" --input input/hertz_cylinder.xml \
    --set "Mesh/File=$mesh" --set "Contact/Friction Model=$friction" --set Solver/Verbose=false \
    --summary "$work/s.json" > "$work/tribos.log" 2>&1
  rc=$?
  t1=$(now)
  if [ $rc -ne 0 ]; then echo "tribos failed (rc $rc):" >&2; tail -20 "$work/tribos.log" >&2; exit 1; fi
  tw=$(echo "$t1 - $t0" | bc -l)

  t0=$(now)
  OMP_NUM_THREADS=1 "$PYTHON" "$here/getfem_hertz_cylinder.py" "$mesh" --friction "$friction" \
    > "$work/getfem.log" 2>&1
  rc=$?
  t1=$(now)
  if [ $rc -ne 0 ]; then echo "getfem failed (rc $rc):" >&2; tail -20 "$work/getfem.log" >&2; exit 1; fi
  gw=$(echo "$t1 - $t0" | bc -l)

  read -r pfp tforce < <("$PYTHON" -c 'import json,sys; d=json.load(open(sys.argv[1])); print(d["pfp_applications"], d["total_normal_force"])' "$work/s.json")
  gline=$(grep '^getfem ' "$work/getfem.log")
  printf 'run %d: tribos %.3f s (pfp_applications %s, normal force %.4f) | getfem %.3f s (%s)\n' \
    "$i" "$tw" "$pfp" "$tforce" "$gw" "${gline#getfem }"
  if [ -z "$tmin" ] || [ "$(echo "$tw < $tmin" | bc -l)" = 1 ]; then tmin=$tw; fi
  if [ -z "$gmin" ] || [ "$(echo "$gw < $gmin" | bc -l)" = 1 ]; then gmin=$gw; fi
done
gforce=$(sed -n 's/.* normal_force=\([^ ]*\).*/\1/p' <<< "$gline")
gnewton=$(sed -n 's/.* newton=\([^ ]*\).*/\1/p' <<< "$gline")
nodes=$(sed -n 's/.* nodes=\([^ ]*\).*/\1/p' <<< "$gline")
ratio=$(echo "$tmin / $gmin" | bc -l)
printf 'side-by-side mesh=%s friction=%s nodes=%s runs=%d tribos_min_s=%.3f pfp_applications=%s tribos_force=%.4f getfem_min_s=%.3f getfem_force=%s getfem_newton=%s ratio_tribos/getfem=%.3f\n' \
  "$(basename "$mesh")" "$friction" "$nodes" "$runs" "$tmin" "$pfp" "$tforce" "$gmin" "$gforce" "$gnewton" "$ratio"
