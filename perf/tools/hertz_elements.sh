#!/usr/bin/env bash
# Hertz contact per element type (issue 32, doc/elements.md): the line contact of
# input/hertz_cylinder.xml meshed by gmsh (input/meshes/hertz_cylinder.geo) with linear and
# quadratic (-order 2) tetrahedra and with hexahedra (-setnumber Hex 1) at the contact element
# sizes hc, and the point contact of input/hertz_sphere.xml (input/meshes/hertz_sphere.geo)
# with linear and quadratic tetrahedra and with a graded hexahedral block (-setnumber HexBlock
# 1; the sphere stays tetrahedral). One Markdown row per run: nodes, elements, the peak nodal pressure against
# Hertz's p0, the edge of the contact zone (last node in contact, first node out) against b or
# a, the rms residual of a least-squares Hertz fit (doc/tools/hertz_compare.py), F
# applications, factor nonzeros, bytes moved per F application, tribos's total time.
# The meshes go to a temporary folder. Needs gmsh (4.8.4 measured) and ncdump.
# Usage: perf/tools/hertz_elements.sh        (from a built tree)
#   TRIBOS=/abs/path/tribos MSH2EXO=/abs/path/tribos-msh2exo PYTHON=python3   other programs
set -euo pipefail
cd "$(dirname "$0")/../.."
tribos=${TRIBOS:-build/bin/tribos}
msh2exo=${MSH2EXO:-build/bin/tribos-msh2exo}
python=${PYTHON:-python3}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# run KIND SCENE LABEL GMSH-ARGS...: one row.
run() {
  local kind=$1 scene=$2 label=$3
  shift 3
  local geo=input/meshes/hertz_$kind.geo mesh=$out/mesh
  gmsh -3 -format msh41 "$@" "$geo" -o "$mesh.msh" > "$out/gmsh.log" 2>&1 || { echo "gmsh failed: $label" >&2; return; }
  "$msh2exo" "$mesh.msh" "$mesh.exo" > /dev/null
  echo "$label ..." >&2
  "$tribos" --input "input/$scene.xml" --set "Mesh/File=$mesh.exo" --set Solver/Verbose=false \
    --output "$out/r.exo" --summary "$out/s.json" > "$out/run.log" 2>&1 || { echo "| $label | exit $? |"; return; }
  "$python" - "$out/s.json" "$label" "$kind" "$out/r.exo" "$python" <<'PY'
import json, re, subprocess, sys
summary, label, kind, result, python = sys.argv[1:6]
s = json.load(open(summary))
text = subprocess.run([python, "doc/tools/hertz_compare.py", kind, result], capture_output=True, text=True).stdout
def grab(pattern):
    m = re.search(pattern, text, re.M)
    return m.groups() if m else ("?",) * re.compile(pattern).groups
nodes, = grab(r": (\d+) nodes")
peak, = grab(r"peak nodal pressure .*: ([+-][\d.]+ %)")
if kind == "cylinder":
    last, first = grab(r"^0 +\d+ +[\d.]+ +([\d.]+) +([\d.]+)")
else:
    last, first = grab(r"largest r with p > 0: ([\d.]+), smallest r with p = 0: ([\d.]+)")
rms, = grab(r"rms residual [\d.]+ \(([\d.]+ %) of p0\)")
print("| %s | %s | %s | %s | [%s, %s] | %s | %s | %s | %s | %.2f |" % (
    label, nodes, s.get("n_elements", "?"), peak, last, first, rms, s.get("pfp_applications", "?"),
    s.get("factor_nonzeros", "?"), s.get("bytes_per_f_application", "?"), s.get("times", {}).get("total_s", float("nan"))))
PY
}

echo "| mesh | nodes | elements | peak vs p0 | contact edge (last in, first out) | Hertz fit rms | F applications | factor nonzeros | bytes per F | tribos s |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for hc in 0.4 0.3 0.2; do
  run cylinder hertz_cylinder "cylinder tet4 hc $hc" -setnumber hc "$hc"
  run cylinder hertz_cylinder "cylinder hex8 hc $hc" -setnumber hc "$hc" -setnumber Hex 1
  run cylinder hertz_cylinder "cylinder tet10 hc $hc" -setnumber hc "$hc" -order 2
done
for hc in 0.3 0.15; do
  run sphere hertz_sphere "sphere tet4 hc $hc" -setnumber hc "$hc"
  run sphere hertz_sphere "sphere tet10 hc $hc" -setnumber hc "$hc" -order 2
done
# The graded hexahedral block: first cell 10 (growth - 1) / (growth^n - 1) = 0.39 and 0.20.
run sphere hertz_sphere "sphere hex8 block, first cell 0.39" -setnumber hc 0.3 -setnumber HexBlock 1 \
  -setnumber nblock 14 -setnumber growth 1.09
run sphere hertz_sphere "sphere hex8 block, first cell 0.20" -setnumber hc 0.15 -setnumber HexBlock 1
