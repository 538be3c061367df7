#!/usr/bin/env bash
# Quick start, part 2: set up, build and run the whole test suite: labels unit and integration
# (and small) in parallel, then the perf label serially (its tests are RUN_SERIAL and guard
# iteration counts against perf/baselines/, two-sided; about 15 s on 2 cores). CI runs this
# script (.ci/run). The perf tests are built with TRIBOS_ENABLE_PERF (ON by default); a build
# configured without them fails here (--no-tests=error) rather than skip the guard silently.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
ctest --test-dir build --output-on-failure -j 2 -LE perf
ctest --test-dir build --output-on-failure --no-tests=error -L perf
