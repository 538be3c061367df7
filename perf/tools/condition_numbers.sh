#!/usr/bin/env bash
# kappa(PFP | Ker G) of the bonded two bricks (linear T-FETI, Lanczos estimate from
# projected CG at tolerance 1e-10) for growing numbers of subdomains at fixed H/h.
# Usage: perf/tools/condition_numbers.sh   (prints a CSV)
set -euo pipefail
cd "$(dirname "$0")/../.."
out=$(mktemp -d)
echo "subdomains_total,h_ratio,preconditioner,kappa,cg_iterations"
for pc in None Dirichlet; do
  for h in 2 3; do
    for cell in "4 2x1x1" "32 4x2x2" "108 6x3x3" "256 8x4x4"; do
      set -- $cell
      build/bin/tribos --input input/two_bricks.xml --set "Contact/Friction Model=Bonded" --set "Mesh/Subdomains Per Brick=$2" \
        --set "Mesh/H Over h=$h" --set "Solver/Tolerance=1e-10" --set "FETI/Preconditioner=$pc" --summary "$out/s.json" > /dev/null
      /usr/bin/python3 -c "import json; j=json.load(open('$out/s.json')); print(f'$1,$h,$pc,{j[\"condition_estimate\"]:.2f},{j[\"outer_iterations\"]}')"
    done
  done
done
rm -rf "$out"
