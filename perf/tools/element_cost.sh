#!/usr/bin/env bash
# Cost to accuracy per element type (issue 32, doc/elements.md): the slender cantilever of
# input/cantilever_<type>.xml (L = 10, 1 x 1 mm, clamped at x = 0, P = 1 N in -z at x = L)
# meshed by gmsh (input/meshes/cantilever.geo) at the element sizes h = 1/N, each solved by
# tribos (linear T-FETI, the scene's 4 subdomains), one Markdown row per run: nodes, dofs (3 x
# nodes, clamped ones included), elements, the tip deflection (mean u_z over the "tip" nodes),
# its error against Timoshenko (doc/tools/cantilever_compare.py), 2U/P's error, the error
# against the 3D reference (the finest tet10 run: the 3D problem's own answer is not the beam
# theory's), F applications (pfp_applications), factor nonzeros (factor_nonzeros), tribos's
# total time (times/total_s, "tribos s") and the process's wall time. Then, per type, the
# cheapest mesh (fewest dofs) whose tip-deflection error is within 5 % and 1 %, against
# Timoshenko and against the 3D reference (the reference run itself excluded).
# The meshes go to a temporary folder (not committed). Needs gmsh (4.8.4 measured) and ncdump.
# Progress goes to stderr, the tables to stdout.
# Usage: perf/tools/element_cost.sh            (from a built tree)
#   TRIBOS=/abs/path/tribos MSH2EXO=/abs/path/tribos-msh2exo PYTHON=python3   other programs
#   LEVELS_HEX8="2 4" LEVELS_WEDGE6=... LEVELS_TET4=... LEVELS_TET10=...      other levels (N)
#   TRIBOS_RUN_TIMEOUT=600                     seconds per run (a run stopped is a row "exit 124")
set -euo pipefail
cd "$(dirname "$0")/../.."
tribos=${TRIBOS:-build/bin/tribos}
msh2exo=${MSH2EXO:-build/bin/tribos-msh2exo}
python=${PYTHON:-python3}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
declare -A gmsh_args=([hex8]="-setnumber Hex 1" [wedge6]="-setnumber Prism 1"
                      [tet4]="-setnumber Degree 1" [tet10]="-setnumber Degree 2")
declare -A levels=([hex8]=${LEVELS_HEX8:-"2 3 4 6 8 12 16"} [wedge6]=${LEVELS_WEDGE6:-"2 3 4 6 8 12 16"}
                   [tet4]=${LEVELS_TET4:-"2 3 4 6 8 10 12 16"} [tet10]=${LEVELS_TET10:-"1 2 3 4 6 8"})
rows=$out/rows.txt
: > "$rows"
for type in hex8 wedge6 tet4 tet10; do
  for n in ${levels[$type]}; do
    mesh=$out/${type}_n$n
    # shellcheck disable=SC2086
    gmsh -3 -format msh41 ${gmsh_args[$type]} -setnumber N "$n" input/meshes/cantilever.geo -o "$mesh.msh" \
      > "$mesh.gmsh.log" 2>&1 || { echo "gmsh failed on $type N = $n:" >&2; grep -i error "$mesh.gmsh.log" >&2; continue; }
    "$msh2exo" "$mesh.msh" "$mesh.exo" > /dev/null
    rm -f "$mesh.msh" "$out/r.exo" "$out/s.json"
    echo "$type N = $n ..." >&2
    start=$(date +%s.%N)
    status=0
    timeout "${TRIBOS_RUN_TIMEOUT:-600}" "$tribos" --input input/cantilever_$type.xml --set "Mesh/File=$mesh.exo" \
      --set Solver/Verbose=false --output "$out/r.exo" --summary "$out/s.json" > "$mesh.log" 2>&1 || status=$?
    stop=$(date +%s.%N)
    rm -f "$mesh.exo"
    if [ $status -ne 0 ]; then
      echo "$type N = $n: tribos exit $status: $(tail -1 "$mesh.log")" >&2
      echo "[\"$type\", $n, null, \"exit $status\"]" >> "$rows"
      continue
    fi
    "$python" doc/tools/cantilever_compare.py "$out/r.exo" "$out/s.json" --json > "$out/c.json"
    "$python" - "$type" "$n" "$out/c.json" "$out/s.json" "$start" "$stop" >> "$rows" <<'PY'
import json, sys
kind, n, compare, summary, start, stop = sys.argv[1:]
c = json.load(open(compare))
s = json.load(open(summary))
print(json.dumps([kind, int(n), c["timoshenko"], c["n_nodes"], c["n_dofs"], c["n_elements"], c["tip_mean"],
                  c["error_tip_mean"], c["error_energy"], c["f_applications"], c["factor_nonzeros"],
                  s["times"]["total_s"], float(stop) - float(start)]))
PY
  done
done
"$python" - "$rows" <<'PY'
import json, sys
rows = [json.loads(line) for line in open(sys.argv[1])]
done = [r for r in rows if r[2] is not None]
# The 3D problem's own answer differs from the beam theory (the clamp holds the section): the
# finest 10-node tetrahedral mesh of the run is the reference of the "error vs 3D ref" column.
tet10 = sorted((r for r in done if r[0] == "tet10"), key=lambda r: r[1])
reference = tet10[-1] if tet10 else None
if not done:
    sys.exit("no run finished: " + "; ".join("%s N = %d: %s" % (r[0], r[1], r[3]) for r in rows))
print("Timoshenko tip deflection %.6f; 3D reference (finest tet10, N = %s) %s\n"
      % (done[0][2], reference[1] if reference else "-",
         "%.6f (%+.2f %% from Timoshenko)" % (reference[6], 100 * reference[7]) if reference else "-"))
print("| type | N | h | nodes | dofs | elements | tip deflection | error | 2U/P error | error vs 3D ref | "
      "F applications | factor nonzeros | tribos s | wall s |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
for r in rows:
    if r[2] is None:
        print("| %s | %d | | | | | %s | | | | | | | |" % (r[0], r[1], r[3]))
        continue
    vs_ref = "%+.2f %%" % (100 * (r[6] - reference[6]) / reference[6]) if reference else "-"
    print("| %s | %d | %.3g | %d | %d | %d | %.6f | %+.2f %% | %+.2f %% | %s | %d | %d | %.2f | %.2f |"
          % (r[0], r[1], 1.0 / r[1], r[3], r[4], r[5], r[6], 100 * r[7], 100 * r[8], vs_ref, r[9], r[10], r[11],
             r[12]))
for against in ("Timoshenko", "the 3D reference"):
    if against != "Timoshenko" and not reference:
        continue
    print("\nThe cheapest mesh (fewest dofs) per type within the bound on |tip deflection error| against %s:\n"
          % against)
    print("| type | bound | N | dofs | elements | error | F applications | factor nonzeros | tribos s | wall s |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for kind in ("hex8", "wedge6", "tet4", "tet10"):
        for bound in (0.05, 0.01):
            error = (lambda r: r[7]) if against == "Timoshenko" else (lambda r: (r[6] - reference[6]) / reference[6])
            ok = sorted((r for r in done if r[0] == kind and abs(error(r)) <= bound
                         and (against == "Timoshenko" or r is not reference)),
                        key=lambda r: r[4])
            if ok:
                r = ok[0]
                print("| %s | %g %% | %d | %d | %d | %+.2f %% | %d | %d | %.2f | %.2f |"
                      % (kind, 100 * bound, r[1], r[4], r[5], 100 * error(r), r[9], r[10], r[11], r[12]))
            else:
                print("| %s | %g %% | not reached (finest N = %s) | | | | | | | |"
                      % (kind, 100 * bound, max((r[1] for r in done if r[0] == kind), default="-")))
PY
