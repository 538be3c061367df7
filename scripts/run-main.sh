#!/usr/bin/env bash
# Quick start, part 1: set up, build and run the main job, the paper's two-brick scene.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
build/bin/tribos --input input/two_bricks.xml --summary two_bricks.json --output two_bricks.exo "$@"
