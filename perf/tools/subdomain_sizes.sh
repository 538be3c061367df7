#!/usr/bin/env bash
# How the subdomain size moves a scene's time: runs SCENE with Mesh/Subdomains = 0 (the count
# from the mesh) for each Mesh/Nodes Per Subdomain T given, and prints per run the subdomain
# count and F applications of the JSON summary and the process's wall seconds (one run each:
# repeat on a quiet machine). The table behind the default of Nodes Per Subdomain is in
# doc/measurements/curved_iterations.md ("How many subdomains").
# Usage: perf/tools/subdomain_sizes.sh TRIBOS SCENE.xml T... [-- extra tribos arguments]
set -uo pipefail
[ $# -ge 3 ] || { echo "usage: $0 TRIBOS SCENE.xml T... [-- --set ...]" >&2; exit 2; }
tribos=$1 scene=$2
shift 2
sizes=()
while [ $# -gt 0 ] && [ "$1" != "--" ]; do sizes+=("$1"); shift; done
[ "${1:-}" = "--" ] && shift
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for t in "${sizes[@]}"; do
  start=$(date +%s.%N)
  "$tribos" --input "$scene" --set Mesh/Subdomains=0 --set "Mesh/Nodes Per Subdomain=$t" "$@" \
    --summary "$work/s.json" >"$work/log" 2>&1
  status=$?
  end=$(date +%s.%N)
  python3 - "$t" "$status" "$start" "$end" "$work/s.json" <<'P'
import json, sys
t, status, start, end, path = sys.argv[1:]
try:
    summary = json.load(open(path))
except (OSError, ValueError):
    summary = {}
print(f"T {t:>6} subdomains {summary.get('n_subdomains')} PFP {summary.get('pfp_applications')} "
      f"exit {status} wall {float(end) - float(start):.2f} s", flush=True)
P
done
