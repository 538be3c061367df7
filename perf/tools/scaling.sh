#!/usr/bin/env bash
# Strong and weak scaling of tribos on the paper's two bricks (input/two_bricks.xml): one run
# per (cell, layout), then a table of times, F applications, time per F application (per
# 1 000 dofs) and peak memory per rank (max_rss_per_rank_kb of the JSON summary).
#
# Usage: perf/tools/scaling.sh "LAYOUTS" "CELLS" [H/h (default 5)] [extra tribos arguments...]
#   LAYOUTS  ranks or RANKSxTHREADS, e.g. "1 2 4 8 16 1x16"
#   CELLS    subdomains per brick, e.g. "10x5x5" or "6x3x3 8x4x4 10x5x5 14x7x7 20x10x10"
#   perf/tools/scaling.sh --report DIR   only print the table of the summaries kept in DIR
# Environment: TRIBOS (driver, default build/bin/tribos), MPIRUN (default mpirun),
#   TIMEOUT (seconds per run, default 600), KEEP (folder that keeps the JSON summaries;
#   default a temporary one), PYTHON (default python3), SOURCE_DIR (the checkout holding
#   input/, default the one of this script).
# Ranks are bound to cores (--bind-to core) with one thread each; a layout with threads is
# not bound (--bind-to none), as Open MPI would pin all of a rank's threads to one core.
# Speed-up: against the cell's first layout (list 1 first for speed-ups over one core).
# Table columns: subdomains, n (primal dofs), ranks x threads, outer iterations, F
# applications, total and solve seconds, speed-up (total, solve), ms per F application,
# µs per F application per 1 000 dofs, milliseconds per coarse solve with the leaves and depth
# of its spread over the ranks (DistributedCoarseSolve; 0, 0: on rank 0 alone), peak memory per
# rank (largest, mean; MiB), exit status.
set -uo pipefail
cd "${SOURCE_DIR:-$(dirname "$0")/../..}"
python=${PYTHON:-python3}

report() {
  "$python" - "$1" <<'PY'
import glob, json, os, sys
rows = []
for path in sorted(glob.glob(os.path.join(sys.argv[1], "*.json"))):
    with open(path) as f:
        rows.append(json.load(f))
rows.sort(key=lambda j: (j["run"]["order"]))
first = {}
print("| cell | subdomains | n | ranks x threads | outer | F appl. | total s | solve s | speed-up total | "
      "speed-up solve | ms / F | µs / F / 1000 dofs | coarse solve ms (leaves, depth) | "
      "max RSS per rank MiB (max / mean) | exit |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
for j in rows:
    r = j["run"]
    cell = f'{r["cell"]}, H/h={r["h"]}'
    if "times" not in j or "n_primal" not in j:
        print(f'| {cell} | | | {r["ranks"]} x {r["threads"]} | | | | | | | | | | | {r["status"]} (wall {r["wall_s"]:.0f} s) |')
        continue
    f = j.get("f_applications", j.get("pfp_applications", 0)) or 0
    total, solve = j["times"]["total_s"], j["times"].get("solve_s", 0.0)
    base = first.setdefault(cell, (total, solve))
    rss = [kb / 1024 for kb in j.get("max_rss_per_rank_kb", [])]
    rss_text = f"{max(rss):.0f} / {sum(rss) / len(rss):.0f}" if rss else "n/a"
    per_f = solve / f if f else float("nan")
    p = j.get("operator_profile", {})
    solves = p.get("coarse_solves", 0)
    coarse = (f'{1e3 * p["coarse_solve_s"] / solves:.3f} ({p.get("coarse_rank_subtrees", 0)}, '
              f'{p.get("coarse_split_depth", 0)})') if solves else "n/a"
    print(f'| {cell} | {j["n_subdomains"]} | {j["n_primal"]} | {r["ranks"]} x {r["threads"]} | '
          f'{j.get("outer_iterations", "")} | {f} | {total:.2f} | {solve:.2f} | {base[0] / total:.2f} | '
          f'{(base[1] / solve) if solve else float("nan"):.2f} | {1e3 * per_f:.2f} | '
          f'{1e6 * per_f / (j["n_primal"] / 1000):.1f} | {coarse} | {rss_text} | {r["status"]} |')
PY
}

if [ "${1:-}" = "--report" ]; then
  report "$2"
  exit
fi
[ $# -ge 2 ] || { sed -n '2,20p' "$0"; exit 2; }
layouts=$1 cells=$2 h=${3:-5}
shift $(( $# >= 3 ? 3 : 2 ))
extra=("$@")
driver=${TRIBOS:-build/bin/tribos}
mpirun=${MPIRUN:-mpirun}
keep=${KEEP:-$(mktemp -d)}
mkdir -p "$keep"
order=0
for cell in $cells; do
  for layout in $layouts; do
    ranks=${layout%x*} threads=1
    [[ $layout == *x* ]] && threads=${layout#*x}
    bind=core
    [ "$threads" -gt 1 ] && bind=none
    order=$((order + 1))
    json=$keep/$(printf %03d $order)_${cell}_h${h}_${ranks}x${threads}.json
    start=$(date +%s%N)
    timeout "${TIMEOUT:-600}" "$mpirun" --allow-run-as-root --oversubscribe --bind-to $bind \
      -x OMP_NUM_THREADS="$threads" -x OMP_WAIT_POLICY=PASSIVE ${LD_LIBRARY_PATH:+-x LD_LIBRARY_PATH} -np "$ranks" \
      "$driver" --input input/two_bricks.xml --set "Mesh/Subdomains Per Brick=$cell" --set "Mesh/H Over h=$h" \
      --set "Solver/Verbose=false" --summary "$json" "${extra[@]}" > "$json.log" 2>&1
    status=$?
    wall=$(( ($(date +%s%N) - start) / 1000000 ))e-3
    # The run's description goes into its summary (or a stub when no summary was written).
    "$python" - "$json" "$cell" "$h" "$ranks" "$threads" "$status" "$wall" "$order" <<'PY'
import json, os, sys
path, cell, h, ranks, threads, status, wall, order = sys.argv[1:]
j = {}
if os.path.exists(path):
    with open(path) as f:
        j = json.load(f)
j["run"] = {"cell": cell, "h": int(h), "ranks": int(ranks), "threads": int(threads), "status": int(status),
            "wall_s": float(wall), "order": int(order)}
with open(path, "w") as f:
    json.dump(j, f, indent=1)
PY
    echo "scaling: $cell H/h=$h ${ranks}x${threads}: exit $status, $((${wall%e-3} / 1000)) s" >&2
  done
done
report "$keep"
