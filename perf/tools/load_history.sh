#!/usr/bin/env bash
# The cost of load histories (issue 31, doc/load_history.md "Cost"): PFP applications per step
# and per history, and wall time, for
#   - the paper's scene (input/two_bricks.xml) in a 20-step cyclic history (load_top held,
#     load_end 0 -> 1 -> -1 -> 1 in steps of 0.25), warm (each step from the last) and cold
#     (Load Steps/Warm Start = false), and its one-step solve;
#   - the Cattaneo-Mindlin scenes input/cattaneo_sphere.xml and input/cattaneo_cylinder.xml
#     (4 steps: the normal approach, then the shear to Q/(F P) = 0.3, 0.6, 0.9), warm and cold.
# Prints one CSV line per run: scene,start,steps,pfp_total,outer_total,pfp_per_step,seconds,converged.
# Usage: perf/tools/load_history.sh [extra --set arguments...]   (from a built tree, ~4 min on 2 cores)
set -euo pipefail
cd "$(dirname "$0")/../.."
driver=build/bin/tribos
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
extra=("$@")
cycle="0.25, 0.5, 0.75, 1, 0.75, 0.5, 0.25, 0, -0.25, -0.5, -0.75, -1, -0.75, -0.5, -0.25, 0, 0.25, 0.5, 0.75, 1"
held="1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1"
echo "scene,start,steps,pfp_total,outer_total,pfp_per_step,seconds,converged"
run() {
  local name=$1 start=$2
  shift 2
  local begin end
  begin=$(date +%s.%N)
  "$driver" "$@" --set Solver/Verbose=false --summary "$out/s.json" "${extra[@]}" > /dev/null || true
  end=$(date +%s.%N)
  python3 - "$out/s.json" "$name" "$start" "$begin" "$end" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
steps = j.get("steps", [])
per = " ".join(str(k["pfp_applications"]) for k in steps) or str(j["pfp_applications"])
print(sys.argv[2], sys.argv[3], max(len(steps), 1), j["pfp_applications"], j["outer_iterations"], per,
      "%.1f" % (float(sys.argv[5]) - float(sys.argv[4])), j["converged"], sep=",")
PY
  rm -f "$out/s.json"
}
run two_bricks one-step --input input/two_bricks.xml
for start in true false; do
  run two_bricks_cycle "warm=$start" --input input/two_bricks.xml --set "Load Steps/Number Of Steps=20" \
    --set "Load Steps/load_end/Factors={$cycle}" --set "Load Steps/load_top/Factors={$held}" \
    --set "Load Steps/Warm Start=$start"
done
for scene in cattaneo_sphere cattaneo_cylinder; do
  for start in true false; do
    run "$scene" "warm=$start" --input "input/$scene.xml" --set "Load Steps/Warm Start=$start"
  done
done
