#!/usr/bin/env bash
# F applications of the default stack (or of the --set arguments given) on an ensemble of
# Coulomb scenes, each solved three times with its friction coefficient multiplied by 1,
# 1 + 1e-7 and 1 - 1e-7. On the curved scenes one count moves by 10-20 % under such a
# perturbation (the Hertz cylinder h0.1: 675-906, doc/parameters.md), so a change of the solver
# is judged by the ensemble's sums, not by single runs. Prints one CSV line per run
# (scene,factor,f_applications,outer_iterations,converged), then the sum per scene and in all.
# Usage: perf/tools/count_ensemble.sh [extra --set arguments...]   (from a built tree, ~40 s on 2 cores)
set -euo pipefail
cd "$(dirname "$0")/../.."
driver=build/bin/tribos
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
extra=("$@")
echo "scene,factor,f_applications,outer_iterations,converged"
run() {
  local name=$1 friction=$2
  shift 2
  for factor in 1 1.0000001 0.9999999; do
    local f
    f=$(python3 -c "print(repr($friction * $factor))")
    "$driver" "$@" --set "Contact/F1=$f" --set "Contact/F2=$f" --set Solver/Verbose=false \
      --summary "$out/s.json" "${extra[@]}" > /dev/null || true
    python3 -c "
import json, sys
j = json.load(open('$out/s.json'))
print('$name,$factor', j['f_applications'], j['outer_iterations'], j['converged'], sep=',')" | tee -a "$out/runs.csv"
    rm -f "$out/s.json"
  done
}
for cell in 2x1x1:2 2x1x1:3 4x2x2:3 6x3x3:2 6x3x3:4 8x4x4:3 10x5x5:3; do
  run "bricks ${cell/:/ H\/h }" 0.3 --input input/two_bricks.xml --set "Mesh/Subdomains Per Brick=${cell%:*}" \
    --set "Mesh/H Over h=${cell#*:}"
done
run "cylinder h0.2" 0.2 --input input/hertz_cylinder.xml --set Mesh/File=meshes/hertz_cylinder_h0.2.exo \
  --set "Contact/Friction Model=Coulomb"
run "cylinder h0.1" 0.2 --input input/hertz_cylinder.xml --set "Contact/Friction Model=Coulomb"
run "sphere h0.3" 0.3 --input input/hertz_sphere.xml --set Mesh/File=meshes/hertz_sphere_h0.3.exo \
  --set "Contact/Friction Model=Coulomb"
run "sphere h0.15" 0.3 --input input/hertz_sphere.xml --set Mesh/File=meshes/hertz_sphere_h0.15.exo \
  --set "Contact/Friction Model=Coulomb"
run "block on plate" 0.3 --input input/block_on_plate.xml
run "block traction 5 0 -20" 0.3 --input input/block_on_plate.xml --set "Loads/press/Traction={5,0,-20}"
python3 - "$out/runs.csv" <<'PY'
import collections, sys
sums, ok = collections.OrderedDict(), True
for line in open(sys.argv[1]):
    scene, factor, f, outer, converged = line.strip().split(",")
    sums[scene] = sums.get(scene, 0) + int(f)
    ok = ok and converged == "True"
print("sums: " + "; ".join(f"{k} {v}" for k, v in sums.items()))
print(f"total {sum(sums.values())}, every run converged: {ok}")
PY
