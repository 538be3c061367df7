#!/usr/bin/env bash
# Reproduces the paper's Table 1 with build/bin/tribos: one run per cell, one CSV line per
# run (dimensions, SMALSE-M outer iterations, F applications, times) on stdout.
# Usage: perf/tools/table1.sh [max subdomains (default 108)] [extra --set arguments...]
set -euo pipefail
cd "$(dirname "$0")/../.."
max=${1:-108}
shift || true
extra=("$@")
driver=build/bin/tribos
out=$(mktemp -d)
echo "subdomains_total,h_ratio,n,n_d,l,outer,n_pfp,rel_eff,converged,solve_s,total_s"
for cell in "4 2x1x1" "32 4x2x2" "108 6x3x3" "256 8x4x4" "500 10x5x5"; do
  set -- $cell
  s=$1 grid=$2
  [ "$s" -le "$max" ] || continue
  for h in 2 3 4 5; do
    json=$out/cell_${s}_${h}.json
    "$driver" --input input/two_bricks.xml --set "Mesh/Subdomains Per Brick=$grid" --set "Mesh/H Over h=$h" \
      --set "Solver/Verbose=false" --summary "$json" "${extra[@]}" > /dev/null || true
    /usr/bin/python3 - "$json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
nd = j["n_dual"] + j["removed_redundant_rows"]
print(f'{j["n_subdomains"]},{int(round((j["n_primal"] / j["n_subdomains"] / 3) ** (1/3))) - 1},{j["n_primal"]},{nd},'
      f'{j["n_rigid"]},{j["outer_iterations"]},{j["pfp_applications"]},{j["pfp_applications"] / j["n_primal"]:.4f},'
      f'{j["converged"]},{j["times"]["solve_s"]:.2f},{j["times"]["total_s"]:.2f}')
PY
  done
done
rm -rf "$out"
