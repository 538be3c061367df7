#!/bin/sh
# CTest integration.cattaneoMindlin.sphereLoadCycle: input/cattaneo_sphere.xml pressed, then
# sheared to Q*/(F P) = 0.9, reversed to -Q* and back to Q* (21 steps: 4 up, 8 per reversal),
# and doc/tools/mindlin_loop.py on its summary: the energy one cycle dissipates against
# Mindlin-Deresiewicz within 10 % (the solver's dissipated energy and the Q-delta loop area),
# and the non-linear part of the first loading's compliance against Johnson's within 5 %.
# Measured (sphere h0.15, 2026-11-28): 52.68 N mm analytic, 55.49 dissipated (+5.3 %), loop
# area 54.70 (+3.8 %); K 0.03706 against 0.03628 mm (+2.2 %).
# Usage: mindlin_loop_test.sh TRIBOS PYTHON SOURCE_DIR
set -u
tribos=$1
python=$2
source=$3
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
ones="1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1"
shear="0, 0.25, 0.5, 0.75, 1, 0.75, 0.5, 0.25, 0, -0.25, -0.5, -0.75, -1, -0.75, -0.5, -0.25, 0, 0.25, 0.5, 0.75, 1"
"$tribos" --input "$source/input/cattaneo_sphere.xml" --set Solver/Verbose=false \
  --set 'Load Steps/Number Of Steps=21' --set "Load Steps/top normal/Factors={$ones}" \
  --set "Load Steps/top shear/Factors={$shear}" --summary "$dir/r.json" || exit 1
"$python" "$source/doc/tools/mindlin_loop.py" "$dir/r.json" --scene "$source/input/cattaneo_sphere.xml" || exit 1
"$python" "$source/doc/tools/mindlin_loop.py" "$dir/r.json" --scene "$source/input/cattaneo_sphere.xml" --json \
  > "$dir/loop.json" || exit 1
"$python" - "$dir/loop.json" <<'PY' || exit 1
import json
import sys

r = json.load(open(sys.argv[1]))
W = r["energy_analytic"]
checks = ((r["converged"], "a step did not converge"),
          (abs(r["load_ratio"] - 0.9) < 0.02, "Q*/(F P) = %.4f, expected 0.9" % r["load_ratio"]),
          (abs(r["energy_dissipated"] - W) < 0.10 * W, "dissipated %.4f against %.4f" % (r["energy_dissipated"], W)),
          (abs(r["energy_loop_area"] - W) < 0.10 * W, "loop area %.4f against %.4f" % (r["energy_loop_area"], W)),
          (abs(r["K_fitted"] - r["K_analytic"]) < 0.05 * r["K_analytic"],
           "compliance K %.5f against %.5f" % (r["K_fitted"], r["K_analytic"])))
failed = [message for ok, message in checks if not ok]
if failed:
    sys.exit("; ".join(failed))
PY
