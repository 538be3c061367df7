#!/bin/sh
# CTest integration.cattaneoMindlin.<kind>: the Cattaneo-Mindlin scene input/cattaneo_<kind>.xml
# (kind: sphere or cylinder; doc/load_history.md, "Cattaneo-Mindlin") solved as its 4-step
# history (step 1 the normal approach alone, steps 2-4 the shear raised to Q/(F P) = 0.3, 0.6,
# 0.9 with the approach held), then doc/tools/cattaneo_compare.py on each step. Checked per
# step: the load ratio reached, the stick size against Johnson's c within one slave element,
# and the rms errors of the tangential traction (relative to F p0) and of the pressure
# (relative to p0) within bounds above what was measured (the measured values are in the
# comments below and in doc/load_history.md). Exit 77 (CTest: skipped) without ncdump.
# KIND sphereQuadraticTetrahedra: the sphere scene on 10-node tetrahedra
# (meshes/cattaneo_sphere_tet10_h0.3.exo, non-matching, curved faces; issue 41 asks for a
# tangential traction within 8 % rms of F p0 on non-matching tetrahedra, which the 4-node ones
# miss: 0.10-0.17 above).
# Usage: cattaneo_mindlin_test.sh TRIBOS PYTHON SOURCE_DIR KIND
set -u
tribos=$1
python=$2
source=$3
kind=$4
if ! command -v ncdump > /dev/null 2>&1; then
  echo "skipped: ncdump is missing (Debian: apt-get install netcdf-bin)"
  exit 77
fi
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
scene=$kind mesh=
if [ "$kind" = sphereQuadraticTetrahedra ]; then
  scene=sphere mesh="Mesh/File=meshes/cattaneo_sphere_tet10_h0.3.exo"
fi
"$tribos" --input "$source/input/cattaneo_$scene.xml" --set Solver/Verbose=false ${mesh:+--set "$mesh"} \
  --output "$dir/r.exo" --summary "$dir/r.json" || exit 1
for step in 1 2 3 4; do
  "$python" "$source/doc/tools/cattaneo_compare.py" "$scene" "$dir/r.exo" --step $step --json > "$dir/step$step.json" ||
    exit 1
done
"$python" - "$dir" "$kind" <<'PY' || exit 1
import json
import sys

folder, kind = sys.argv[1], sys.argv[2]
# Bounds above the measured values (sphere h0.15 / cylinder hc 0.1, 2026-11-28):
#   sphere:   q rms 0.148, 0.173, 0.141, 0.104 of F p0; p rms 0.067-0.069 of p0;
#             |c computed - c| <= 0.025 against a slave element of 0.136
#   cylinder: q rms 0.048, 0.062, 0.068, 0.057; p rms 0.037-0.039; |c - c| <= 0.028 against 0.099
#   sphere on 10-node tetrahedra (hc 0.3; 2026-12-07): q rms 0.056, 0.055, 0.067, 0.053; p rms
#             0.040-0.042; |c computed - c| <= 0.018 against a slave element of 0.268
q_bound, p_bound = {"sphere": (0.22, 0.09), "cylinder": (0.10, 0.06), "sphereQuadraticTetrahedra": (0.08, 0.06)}[kind]
failed = []
for step, target in ((1, 0.0), (2, 0.3), (3, 0.6), (4, 0.9)):
    with open("%s/step%d.json" % (folder, step)) as f:
        r = json.load(f)
    print("step %d: Q/(F P) %.4f, c analytic %.4f, c computed %.4f (element %.3f), q rms %.3f, p rms %.3f"
          % (step, r["load_ratio"], r["c_analytic"], r["c_computed"], r["slave_element_size"], r["q_rms"],
             r["p_rms"]))
    checks = ((abs(r["load_ratio"] - target) < 0.02, "load ratio %.4f, expected %.1f" % (r["load_ratio"], target)),
              (abs(r["c_computed"] - r["c_analytic"]) < r["slave_element_size"],
               "stick size %.4f against %.4f: more than one slave element (%.3f) apart"
               % (r["c_computed"], r["c_analytic"], r["slave_element_size"])),
              (r["q_rms"] < q_bound, "tangential traction rms %.3f >= %.2f F p0" % (r["q_rms"], q_bound)),
              (r["p_rms"] < p_bound, "pressure rms %.3f >= %.2f p0" % (r["p_rms"], p_bound)))
    failed += ["step %d: %s" % (step, message) for ok, message in checks if not ok]
if failed:
    sys.exit("; ".join(failed))
PY
