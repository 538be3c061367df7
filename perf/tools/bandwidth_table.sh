#!/usr/bin/env bash
# Time per PFP application against the memory-bandwidth bound, per Table 1 cell
# (doc/measurements/performance.md). For each cell: one run of build/bin/tribos (threads: OMP_NUM_THREADS,
# default 2), then
#   time per PFP application = solve_s / pfp_applications   (the whole SMALSE-M iteration:
#                              F, the projections, the MPGP vector work)
#   bound                    = bytes_per_f_application / triad bandwidth
#   ratio                    = time / bound                 (issue 9's goal: <= 2 on 10x5x5/5)
#   iteration bound          = every byte the run's operators must move, per PFP application:
#                              the F applications (bytes_per_f_application, their two
#                              projections' G passes included), the preconditioner
#                              applications, the other projections' G passes and every coarse
#                              solve (its factor's values, 8 or 4 bytes each (the reciprocal diagonal, 8 in
#                              both, counted as the rest: a slight underestimate for a single factor), both
#                              substitutions), / triad
#   iteration ratio          = time / iteration bound       (how near the whole iteration runs
#                              to the bandwidth; MPGP's vector work is not counted)
#   F ratio                  = (f_s / f_applications) / (F's own bytes / triad): F alone (the
#                              subdomain solves and B_s, without the projections) against its bytes
#   product ratio            = (products_s / pfp_applications) / bound: the PFP product itself
#                              (F with its two projections, the coarse solves included; SMALSE-M's
#                              products with A_rho and the norm estimate's), without the inner
#                              preconditioner and MPGP's vector work, against the bound above
# The triad (build/bin/tribos_stream_triad, best of 20 sweeps over 400 MB arrays, with the same
# number of threads) is measured before every cell, so that both figures see the same machine
# state: on a shared machine the bandwidth moves by 2x within minutes.
# Usage: perf/tools/bandwidth_table.sh [max subdomains (default 500)] [H/h list (default "2 3 4 5")]
#        [extra --set arguments...]
set -euo pipefail
cd "$(dirname "$0")/../.."
max=${1:-500}
hs=${2:-"2 3 4 5"}
shift 2 || shift $# || true
extra=("$@")
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-2}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
triad() {
  build/bin/tribos_stream_triad 400 20 | awk -F, -v t="$OMP_NUM_THREADS" '$1 == t { print $3 }'
}
echo "subdomains,h_ratio,threads,pfp_applications,solve_s,total_s,factor_nonzeros,bytes_per_pfp_MB,triad_GB_s,ms_per_pfp,bound_ms,ratio,iteration_MB_per_pfp,iteration_bound_ms,iteration_ratio,f_ms,f_bound_ms,f_ratio,product_ms,product_ratio"
for cell in "4 2x1x1" "32 4x2x2" "108 6x3x3" "256 8x4x4" "500 10x5x5"; do
  set -- $cell
  s=$1 grid=$2
  [ "$s" -le "$max" ] || continue
  for h in $hs; do
    bandwidth=$(triad)
    json=$out/cell_${s}_${h}.json
    build/bin/tribos --input input/two_bricks.xml --set "Mesh/Subdomains Per Brick=$grid" --set "Mesh/H Over h=$h" \
      --set "Solver/Verbose=false" --summary "$json" "${extra[@]}" > /dev/null || true
    /usr/bin/python3 - "$json" "$h" "$bandwidth" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
h, gbs = sys.argv[2], float(sys.argv[3])
t = j["times"]
per = t["solve_s"] / j["pfp_applications"]
bound = j["bytes_per_f_application"] / (gbs * 1e9)
p = j["operator_profile"]
other_projections = max(0, p["projections"] - 2 * p["f_applications"])
total = (p["f_applications"] * j["bytes_per_f_application"] + p["preconditioner_applications"] * p["preconditioner_bytes"]
         + other_projections * p["projection_bytes"] + p["coarse_solves"] * p["coarse_values_per_solve"] * (8.0 if p.get("coarse_single") else 16.0))
iteration = total / j["pfp_applications"]
iteration_bound = iteration / (gbs * 1e9)
product = t["products_s"] / j["pfp_applications"]
f_ms = 1e3 * p["f_s"] / p["f_applications"]
f_bound_ms = 1e3 * (j["bytes_per_f_application"] - 2 * p["projection_bytes"]) / (gbs * 1e9)
print(f'{j["n_subdomains"]},{h},{j["n_threads"]},{j["pfp_applications"]},{t["solve_s"]:.2f},{t["total_s"]:.2f},'
      f'{j["factor_nonzeros"]},{j["bytes_per_f_application"] / 1e6:.1f},{gbs:.1f},{1e3 * per:.2f},{1e3 * bound:.2f},'
      f'{per / bound:.2f},{iteration / 1e6:.1f},{1e3 * iteration_bound:.2f},{per / iteration_bound:.2f},'
      f'{f_ms:.2f},{f_bound_ms:.2f},{f_ms / f_bound_ms:.2f},{1e3 * product:.2f},{product / bound:.2f}')
PY
  done
done
