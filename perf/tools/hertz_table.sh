#!/usr/bin/env bash
# The Hertz tables of input/README.md: every mesh level of input/hertz_cylinder.xml and
# input/hertz_sphere.xml, frictionless and Coulomb F = 0.2, one Markdown row per run:
# element size at the contact, nodes, peak nodal pressure against Hertz's p0, the edge of
# the contact zone against b or a, SMALSE-M outer iterations, F applications, solve time.
# Usage: perf/tools/hertz_table.sh [extra --set arguments...]   (from a built tree; each run is
# stopped after TRIBOS_RUN_TIMEOUT seconds, default 900: its row then says "False")
set -euo pipefail
cd "$(dirname "$0")/../.."
driver=build/bin/tribos
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "| scene | hc | nodes | friction | peak / p0 - 1 | edge in | Hertz | outer | F applications | solve s | converged |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for scene in cylinder:0.2 cylinder:0.1 cylinder:0.05 sphere:0.3 sphere:0.15 sphere:0.075; do
  kind=${scene%%:*} hc=${scene##*:}
  for friction in None Coulomb; do
    rm -f "$out/s.json" "$out/r.exo"
    timeout "${TRIBOS_RUN_TIMEOUT:-900}" "$driver" --input input/hertz_$kind.xml --set "Mesh/File=meshes/hertz_${kind}_h$hc.exo" \
      --set "Contact/Friction Model=$friction" --set Solver/Verbose=false \
      --output "$out/r.exo" --summary "$out/s.json" "$@" > /dev/null || true
    python3 doc/tools/hertz_compare.py "$kind" "$out/r.exo" > "$out/compare.txt" || true
    [ -f "$out/s.json" ] && python3 - "$kind" "$hc" "$friction" "$out/s.json" "$out/compare.txt" <<'PY'
import json, re, sys
kind, hc, friction, summary, compare = sys.argv[1:]
j = json.load(open(summary))
text = open(compare).read()
peak = re.search(r"peak nodal pressure [-0-9.]+ at .*: ([-+0-9.]+ %)", text)
if kind == "cylinder":
    rows = re.findall(r"^[0-9.]+\s+\d+\s+[0-9.]+\s+([0-9.]+)\s+([0-9.]+)", text, re.M)
    edge = "[%s, %s]" % (min(r[0] for r in rows), max(r[1] for r in rows)) if rows else "-"
    hertz = re.search(r"b = ([0-9.]+)", text).group(1)
else:
    m = re.search(r"largest r with p > 0: ([0-9.]+), smallest r with p = 0: ([0-9.]+)", text)
    edge = "[%s, %s]" % (m.group(1), m.group(2)) if m else "-"
    hertz = re.search(r"a = ([0-9.]+)", text).group(1)
print("| %s | %s | %d | %s | %s | %s | %s | %d | %d | %.1f | %s |" % (
    kind, hc, j["n_nodes"], friction, peak.group(1) if peak else "-", edge, hertz, j["outer_iterations"],
    j["pfp_applications"], j["times"]["solve_s"], j["converged"]))
PY
    [ -f "$out/s.json" ] || echo "| $kind | $hc | - | $friction | stopped after ${TRIBOS_RUN_TIMEOUT:-900} s | | | | | | False |"
  done
done
