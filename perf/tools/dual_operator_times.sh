#!/usr/bin/env bash
# Time of one F application (implicit: two triangular solves per subdomain; explicit: dense
# local F_s) and the factorisation time, from bonded linear T-FETI runs (1 rank, threads =
# OMP_NUM_THREADS). Prints a CSV; times are wall-clock on this machine (noisy VM).
set -euo pipefail
cd "$(dirname "$0")/../.."
out=$(mktemp -d)
echo "subdomains_total,h_ratio,subdomain_dofs,dual_operator,factorization_s,solve_s,f_applications,seconds_per_F"
for cell in "4 2x1x1" "32 4x2x2" "108 6x3x3" "256 8x4x4"; do
  set -- $cell
  for h in 2 3 4; do
    for op in Implicit Explicit; do
      build/bin/tribos --input input/two_bricks.xml --set "Contact/Friction Model=Bonded" --set "Mesh/Subdomains Per Brick=$2" \
        --set "Mesh/H Over h=$h" --set "Solver/Tolerance=1e-8" --set "FETI/Dual Operator=$op" --summary "$out/s.json" > /dev/null
      /usr/bin/python3 -c "
import json; j=json.load(open('$out/s.json')); t=j['times']
print(f'$1,$h,{3*($h+1)**3},$op,{t[\"factorization_s\"]:.4f},{t[\"solve_s\"]:.4f},{j[\"pfp_applications\"]},{t[\"solve_s\"]/j[\"pfp_applications\"]:.2e}')"
    done
  done
done
rm -rf "$out"
