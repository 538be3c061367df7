#!/usr/bin/env bash
# Quick start, part 2: set up, build and run the whole test suite (labels unit and
# integration; perf is opt-in: ctest --test-dir build -L perf after -DTRIBOS_ENABLE_PERF=ON).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
ctest --test-dir build --output-on-failure -j 2 -LE perf
