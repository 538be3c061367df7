#!/bin/sh
# Regenerates the README's pictures in doc/figures/ (about a minute on 2 cores): the paper's scene
# refined to 6x3x3 subdomains per brick with H/h = 4, and the Hertz sphere with Coulomb
# friction (input/hertz_sphere.xml). Usage, from the repository root:
#   doc/tools/make_figures.sh [build/bin/tribos]
# PYTHON (default /usr/bin/python3, Debian's, which has python3-matplotlib) runs the plots.
set -eu
tribos=${1:-build/bin/tribos}
python=${PYTHON:-/usr/bin/python3}
[ -x "$python" ] || python=python3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

"$tribos" --input input/two_bricks.xml --set "Mesh/Subdomains Per Brick=6x3x3" --set "Mesh/H Over h=4" \
  --set Solver/Verbose=false --output "$work/bricks.exo" --summary "$work/bricks.json"
"$python" doc/tools/plot_results.py "$work/bricks.exo" "$work/bricks.json" doc/figures/two_bricks --dpi 90

"$tribos" --input input/hertz_sphere.xml --set "Contact/Friction Model=Coulomb" \
  --set Solver/Verbose=false --output "$work/sphere.exo" --summary "$work/sphere.json"
# x 5: the sphere's approach would show as an overlap at the automatic magnification
"$python" doc/tools/plot_results.py "$work/sphere.exo" "$work/sphere.json" doc/figures/hertz_sphere \
  --scale 5 --dpi 90
