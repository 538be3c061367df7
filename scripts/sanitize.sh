#!/usr/bin/env bash
# The sanitizer leg: builds Tribos with AddressSanitizer + UndefinedBehaviorSanitizer into
# build-asan/ (TRIBOS_SANITIZE=ON, RelWithDebInfo, no perf targets) and runs the unit and
# small integration tests (CTest labels unit and small) under them. Any report fails the
# test that made it (halt_on_error; run-time options in test/cmake/TribosTesting.cmake, leak
# detection off there and why). Needs what scripts/setup.sh installs.
# Usage: scripts/sanitize.sh [extra cmake -D options]
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=${TRIBOS_BUILD_JOBS:-2}
start=$(date +%s)
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTRIBOS_SANITIZE=ON -DTRIBOS_ENABLE_PERF=OFF \
  "$@" >/dev/null
cmake --build build-asan -j "$jobs"
built=$(date +%s)
ctest --test-dir build-asan --output-on-failure -j 2 -L 'unit|small'
echo "sanitize.sh: build $((built - start)) s, tests $(($(date +%s) - built)) s"
