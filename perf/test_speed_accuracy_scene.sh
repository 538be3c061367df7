#!/usr/bin/env bash
# perf.speedAccuracy.sceneFile: tribos_speed_accuracy --input on a scene file (the Hertz
# cylinder at its coarsest level, non-matching meshes): one CSV row per epsilon, both
# converged, and the error against the tight solve falls with epsilon and stays below it.
# Usage: test_speed_accuracy_scene.sh TOOL SOURCE_DIR
set -euo pipefail
tool=$1 src=$2
csv=$(mktemp)
trap 'rm -f "$csv"' EXIT
OMP_NUM_THREADS=1 "$tool" --input "$src/input/hertz_cylinder.xml" --models Coulomb --epsilons 1e-3,1e-6 \
  --reference-tolerance 1e-9 "Mesh/File=meshes/hertz_cylinder_h0.2.exo" > "$csv"
cat "$csv"
python3 - "$csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert [r["epsilon"] for r in rows] == ["0.001", "1e-06"], rows
assert all(r["model"] == "Coulomb" and r["converged"] == "1" for r in rows), rows
e3, e6 = (float(r["relative_error"]) for r in rows)
assert 0.0 < e6 < e3 < 1e-3 and e6 < 1e-6, (e3, e6)
print("ok: errors", e3, e6)
PY
