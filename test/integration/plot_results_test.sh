#!/bin/sh
# CTest integration.plotResults.picturesFromASmallRun: tribos on the paper's smallest scene,
# then doc/tools/plot_results.py on its Exodus result and JSON summary; every picture must be
# a non-empty PNG. Then the three-body scene (two contact interfaces, issue 30): one map per
# interface, and a pressure profile along y = 0 on the block's top (z = 10) under the punch,
# whose numbers are checked. Then a load history (9 steps of block_on_plate.xml sheared back
# and forth): history.csv and history.png of --history, whose numbers are checked. Exit 77
# (CTest: skipped) when the Python has no matplotlib or ncdump is missing, with the plotting
# tool's message saying what to install.
# Usage: plot_results_test.sh TRIBOS PYTHON SOURCE_DIR
set -u
tribos=$1
python=$2
source=$3
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

# png DIR NAME...: each DIR/NAME.png exists, is non-empty and starts with the PNG signature.
. "$(dirname "$0")/png_check.sh"

# plot ARGS...: the plotting tool; a skip (77) ends the test as skipped, any other failure fails it.
plot() {
  "$python" "$source/doc/tools/plot_results.py" "$@"
  status=$?
  if [ "$status" -eq 77 ]; then
    echo "skipped: the pictures need $python with matplotlib and ncdump (see the message above)"
    exit 77
  fi
  [ "$status" -eq 0 ] || exit 1
}

# One interface: the maps keep their single name contact_stress.png.
"$tribos" --input "$source/input/two_bricks.xml" --set Solver/Verbose=false \
  --output "$dir/result.exo" --summary "$dir/summary.json" || exit 1
plot "$dir/result.exo" "$dir/summary.json" "$dir/pictures"
png "$dir/pictures" contact_stress convergence deformed

# Two interfaces, each with its map, and a profile across the punch's footprint.
"$tribos" --input "$source/input/three_bodies.xml" --set Solver/Verbose=false \
  --output "$dir/three.exo" --summary "$dir/three.json" || exit 1
plot "$dir/three.exo" "$dir/three.json" "$dir/three" --profile -5,0,10:5,0,10
png "$dir/three" contact_stress_punch_on_block contact_stress_block_on_foundation profile convergence deformed
if [ -e "$dir/three/contact_stress.png" ]; then
  echo "contact_stress.png written for a scene of two interfaces (expected one map per interface)"
  exit 1
fi

# The profile's numbers. The 200 samples run from x = -5 to 5 (s = x + 5), symmetric about
# x = 0. Measured (three_bodies.xml, 12 subdomains): every sample on block_top, p(0) = 74.1,
# max p = 176, zero beyond x = -4.05 and 3.34 (the rounded edges lift off), integral of p
# 598. The 200 N lateral load at the punch's top, 10 above the contact, tips it toward +x:
# statics put the pressure resultant 200 * 10 / 5000 = 0.4 to the +x side; the line's
# pressure centroid is 0.27. Pointwise, |p(x) - p(-x)| reaches 0.60 max p: the block's mesh
# (h = 1.5) is coarse for a 7-wide contact zone and matches neither the punch nor the load
# (along x = 0, where the load is symmetric, it is 0.49), so the symmetry is checked in L1:
# int |p(x) - p(-x)| / int (p(x) + p(-x)) is 0.26 here (0.23 along x = 0); 0.4 leaves room
# for mesh noise yet fails a one-sided or misplaced profile (1 for a profile that is zero on
# one side).
"$python" - "$dir/three/profile.csv" <<'PY' || exit 1
import csv
import sys

with open(sys.argv[1]) as f:
    header = f.readline().strip()
    rows = list(csv.DictReader(f, fieldnames=header.split(",")))
if header != "s,x,y,z,interface,pressure,tangential_stress":
    sys.exit("profile.csv header: " + header)
rows = [r for r in rows if r["pressure"] != ""]
if len(rows) < 50:
    sys.exit("profile.csv: %d rows on a slave surface, expected at least 50" % len(rows))
if any(r["interface"] != "punch_on_block" for r in rows):
    sys.exit("profile.csv: a point at z = 10 taken by another interface than punch_on_block")
x = [float(r["x"]) for r in rows]
p = [float(r["pressure"]) for r in rows]


def at(x0):
    """Pressure at x0, linear between the samples."""
    k = max(i for i in range(len(x) - 1) if x[i] <= x0)
    w = (x0 - x[k]) / (x[k + 1] - x[k])
    return (1 - w) * p[k] + w * p[k + 1]


def integral(values):
    return sum(0.5 * (values[i] + values[i + 1]) * (x[i + 1] - x[i]) for i in range(len(x) - 1))


mirrored = [at(-v) for v in x]
total = integral(p)
asymmetry = integral([abs(a - b) for a, b in zip(p, mirrored)]) / integral([a + b for a, b in zip(p, mirrored)])
centroid = integral([v * a for v, a in zip(x, p)]) / total
print("profile: %d rows, p(0) = %.4g, max p = %.4g, integral %.4g, L1 asymmetry %.3f, centroid x = %.3f"
      % (len(rows), at(0.0), max(p), total, asymmetry, centroid))
checks = ((at(0.0) > 0, "no pressure at x = 0, under the punch's flat face"),
          (p[0] == 0 and p[-1] == 0, "pressure at x = +-5, where the punch's rounded edges lift off"),
          (total > 0, "integral of the pressure not positive"),
          (asymmetry < 0.4, "pressure far from symmetric about x = 0"),
          (0 < centroid < 1.0, "pressure centroid not on the +x side the lateral load tips the punch to"))
failed = [message for ok, message in checks if not ok]
if failed:
    sys.exit("profile.csv: " + "; ".join(failed))
PY

# A load history: block_on_plate.xml's block pressed (press: 0.5, 0, -20 MPa on block_top's
# 600 mm^2, i.e. 300, 0, -12000 N) and sheared along x by 5 MPa x factor (3000 N x factor):
# up to 1, back to 0, on to -1 and back to 0, with Coulomb F = 0.3 (a hysteresis loop).
"$tribos" --input "$source/input/block_on_plate.xml" --set Solver/Verbose=false \
  --set 'Loads/shear/Side Set=block_top' --set 'Loads/shear/Traction={5, 0, 0}' \
  --set 'Load Steps/Number Of Steps=9' --set 'Load Steps/press/Factors={1,1,1,1,1,1,1,1,1}' \
  --set 'Load Steps/shear/Factors={0.25,0.5,0.75,1,0.5,0,-0.5,-1,0}' \
  --output "$dir/history.exo" --summary "$dir/history.json" || exit 1
plot "$dir/history.exo" "$dir/history.json" "$dir/history" --history block_top:x
png "$dir/history" history contact_stress deformed

# Measured (8 subdomains, any thread count): contact_force_x = -1050.001, -1800.000,
# -2549.998, -3300.003, -1800.000, -300.000, 1200.000, 2700.000, -300.000 (the force of the
# plate on the block balances the block's load 300 + 3000 x factor, to 9.6e-7 relative at
# most: the solver's tolerance is 1e-5, so 1e-5 is checked); mean displ_x of block_top
# 5.909e-4, 1.011e-3, 1.431e-3, 2.155e-3, 1.316e-3, 4.764e-4, -3.628e-4, -1.224e-3, 4.546e-4;
# dissipated energy 0, 0, 0.00405, 0.9687 (88 nodes slip), 0.9687 x 4, 1.0307 (41 slip),
# 1.0307.
"$python" - "$dir/history/history.csv" <<'PY' || exit 1
import csv
import sys

with open(sys.argv[1]) as f:
    rows = list(csv.DictReader(f))
if len(rows) != 9:
    sys.exit("history.csv: %d rows, expected 9 (one per load step)" % len(rows))
for name in ("time", "step", "converged", "displ_x", "reaction_x", "contact_force_x", "contact_dissipated_energy",
             "dissipated_energy"):
    if name not in rows[0]:
        sys.exit("history.csv: no column " + name)
force = [float(r["contact_force_x"]) for r in rows]
u = [float(r["displ_x"]) for r in rows]
energy = [float(r["dissipated_energy"]) for r in rows]
print("history: contact_force_x %s" % ", ".join("%.6g" % v for v in force))
print("history: displ_x %s" % ", ".join("%.4g" % v for v in u))
print("history: dissipated_energy %s" % ", ".join("%.4g" % v for v in energy))
expected = -(300.0 + 3000.0)  # step 4: the whole shear; the contact force on the block opposes its load
checks = ((all(r["converged"] == "1" for r in rows), "a step not converged"),
          ([r["step"] for r in rows] == [str(k) for k in range(1, 10)], "steps not numbered 1 to 9"),
          (abs(force[3] - expected) <= 1e-5 * abs(expected),
           "contact_force_x at step 4 %.9g, expected %.9g" % (force[3], expected)),
          # The friction's memory: shear 0 after loading (step 6) and shear 0 after the reversal
          # (step 9) leave the block at different places (measured 2.2e-5 apart): an open loop.
          (abs(u[5] - u[8]) > 1e-9, "displ_x equal at steps 6 and 9 (a closed loop: no friction memory)"),
          (all(b >= a for a, b in zip(energy, energy[1:])), "dissipated energy decreases"),
          (energy[-1] > 0, "no energy dissipated though the block slipped"),
          (all(r["reaction_x"] == "" for r in rows), "reactions summed over block_top, which is not prescribed"))
failed = [message for ok, message in checks if not ok]
if failed:
    sys.exit("history.csv: " + "; ".join(failed))
PY
