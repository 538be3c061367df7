#!/bin/sh
# CTest integration.plotResults.picturesFromASmallRun: tribos on the paper's smallest scene,
# then doc/tools/plot_results.py on its Exodus result and JSON summary; every picture must be
# a non-empty PNG. Exit 77 (CTest: skipped) when the Python has no matplotlib or ncdump is
# missing, with the plotting tool's message saying what to install.
# Usage: plot_results_test.sh TRIBOS PYTHON SOURCE_DIR
set -u
tribos=$1
python=$2
source=$3
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

"$tribos" --input "$source/input/two_bricks.xml" --set Solver/Verbose=false \
  --output "$dir/result.exo" --summary "$dir/summary.json" || exit 1
"$python" "$source/doc/tools/plot_results.py" "$dir/result.exo" "$dir/summary.json" "$dir/pictures"
status=$?
if [ "$status" -eq 77 ]; then
  echo "skipped: the pictures need $python with matplotlib and ncdump (see the message above)"
  exit 77
fi
[ "$status" -eq 0 ] || exit 1
for name in contact_stress convergence deformed; do
  png="$dir/pictures/$name.png"
  if [ ! -s "$png" ] || [ "$(head -c 4 "$png" | tail -c 3)" != "PNG" ]; then
    echo "missing, empty or not a PNG: $name.png"
    exit 1
  fi
  echo "$name.png: $(wc -c < "$png") bytes"
done
