#!/usr/bin/env bash
# The failure map of doc/stability.md: sweeps of friction, material contrast, H/h, load scale,
# initial gap, bodies held by friction only, and absurd magnitudes on small scenes. Prints the
# markdown tables (doc/tools/stability_table.py) to stdout; the runs' summaries, logs and
# results stay in OUTDIR (default: a fresh mktemp directory, named on stderr).
#   doc/tools/stability_sweeps.sh build/bin/tribos [OUTDIR]
# About 5 minutes on 2 cores. Each run is limited to 120 s (exit 124 in the tables: "no end").
set -uo pipefail
cd "$(dirname "$0")/../.."
tribos=$(realpath "${1:?usage: stability_sweeps.sh TRIBOS [OUTDIR]}")
out=${2:-$(mktemp -d)}
mkdir -p "$out"
echo "stability_sweeps: runs in $out" >&2
manifest=$out/manifest.tsv
: > "$manifest"
n=0

# run SECTION LABEL SCENE [--set ...]: one run, its exit status, summary and log in the manifest.
run() {
  local section=$1 label=$2 scene=$3
  shift 3
  n=$((n + 1))
  local base=$out/run$n
  OMP_NUM_THREADS=1 timeout 120 "$tribos" --input "$scene" --set Solver/Verbose=false --summary "$base.json" \
    --output "$base.exo" "$@" > "$base.log" 2>&1
  printf '%s\t%s\t%s\t%s\n' "$section" "$label" "$?" "$base" >> "$manifest"
}

bricks=input/two_bricks.xml
# Option arrays (names with spaces): ISO=(F1 = F2 = $1), MAT=(steel's E = $1), MESH=(grid $1, H/h $2).
iso() { ISO=(--set "Contact/F1=$1" --set "Contact/F2=$1"); }
# The paper's materials as (E, nu) so that the steel's E can change.
materials() {
  MAT=(--set "Materials/aluminium/Young Modulus=70000" --set "Materials/aluminium/Poisson Ratio=0.35"
    --set "Materials/steel/Young Modulus=$1" --set "Materials/steel/Poisson Ratio=0.3")
}
mesh() { MESH=(--set "Mesh/Subdomains Per Brick=$1" --set "Mesh/H Over h=$2"); }

for h in 2 8; do
  for F in 0 0.1 0.3 0.6 1 2 5 10; do
    iso $F; mesh 2x1x1 $h; run friction "F = $F, 2x1x1, H/h = $h" $bricks "${MESH[@]}" "${ISO[@]}"
  done
done
for pair in "0.1 0.05" "0.3 0.1" "0.6 0.2" "1 0.3" "2 0.5" "5 1" "10 2" "10 0" "0 10"; do
  set -- $pair
  mesh 2x1x1 4; run orthotropic "F1 = $1, F2 = $2, H/h = 4" $bricks "${MESH[@]}" --set "Contact/F1=$1" --set "Contact/F2=$2"
done
for F in 0.3 2 10; do
  iso $F; mesh 2x1x1 4; run exact "Exact fixed point, F = $F, H/h = 4" $bricks "${MESH[@]}" "${ISO[@]}" --set "Contact/Fixed Point=Exact"
done
for c in 1e-6 1e-4 1e-2 1 1e2 1e4 1e6 1e8 1e12 1e14; do
  E=$(awk -v c="$c" 'BEGIN { printf "%.6g", 70000 * c }')
  materials "$E"; run contrast "E_steel / E_aluminium = $c" $bricks "${MAT[@]}"
done
for grid in "2x1x1 1" "2x1x1 2" "2x1x1 4" "2x1x1 6" "2x1x1 8" "2x1x1 10" "4x2x2 2" "4x2x2 4"; do
  set -- $grid
  mesh "$1" "$2"; run mesh "$1, H/h = $2" $bricks "${MESH[@]}"
done
for model in "Coulomb 0.3" "None 0"; do
  set -- $model
  for s in 1 1e-6 1e-3 1e3 1e6; do  # the unit load first: the reference
    iso "$2"; run scaling "$1, load x $s" $bricks "${ISO[@]}" --set "Contact/Friction Model=$1" \
      --set "Loads/end/Side Set=load_end" --set "Loads/end/Traction={$s,0,$(awk -v s="$s" 'BEGIN{print 20*s}')}" \
      --set "Loads/top/Side Set=load_top" --set "Loads/top/Traction={0,0,$(awk -v s="$s" 'BEGIN{print -30*s}')}"
  done
done
for g in 0 0.001 0.003 0.01 0.1 1; do
  run gap "Initial Gap = $g" $bricks --set "Mesh/Initial Gap=$g" --set "Contact/Search Distance=2"
done
# The steel brick held by friction only: its end keeps uz = 0, nothing holds it along x and y.
for F in 0.01 0.02 0.05 0.1 0.3 1; do
  iso $F; run held "bricks, steel end uz = 0 only, F = $F" $bricks "${ISO[@]}" \
    --set "Boundary/Dirichlet Node Sets={dirichlet_aluminium}" --set "Boundary/steelz/Node Set=dirichlet_steel" \
    --set "Boundary/steelz/Components=z"
done
# block_on_plate: the block held by contact and Coulomb 0.3 only, pressed by 20 MPa: it can
# carry a shear traction up to 0.3 x 20 = 6 MPa.
for t in 1 5 6 7 10; do
  run held "block on plate, shear $t MPa, pressure 20 MPa" input/block_on_plate.xml \
    --set "Loads/press/Traction={$t,0,-20}"
done
# Absurd magnitudes (issue 8's list): each is an input error now.
materials 1e300; run absurd "E = 1e300" $bricks "${MAT[@]}"
materials inf; run absurd "E = inf" $bricks "${MAT[@]}"
run absurd "traction 1e300" $bricks --set "Loads/top/Side Set=load_top" --set "Loads/top/Traction={0,0,-1e300}"
run absurd "traction NaN" $bricks --set "Loads/top/Side Set=load_top" --set "Loads/top/Traction={0,0,nan}"
iso 1e300; run absurd "F = 1e300" $bricks "${ISO[@]}"
materials 7e20; run absurd "E_steel / E_aluminium = 1e16" $bricks "${MAT[@]}"
run absurd "E = 1e100 both bodies" $bricks --set "Materials/aluminium/Young Modulus=1e100" \
  --set "Materials/aluminium/Poisson Ratio=0.35" --set "Materials/steel/Young Modulus=1e100" --set "Materials/steel/Poisson Ratio=0.3"
run absurd "traction 1e100" $bricks --set "Loads/top/Side Set=load_top" --set "Loads/top/Traction={0,0,-1e100}"

/usr/bin/python3 doc/tools/stability_table.py "$manifest"
