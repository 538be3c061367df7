#!/usr/bin/env bash
# The sanitizer leg: builds Tribos with AddressSanitizer + UndefinedBehaviorSanitizer into
# build-asan/ (TRIBOS_SANITIZE=ON, no perf targets) and runs the unit and small integration
# tests (CTest labels unit and small) under them. Any report fails the test that made it
# (halt_on_error; run-time options in test/cmake/TribosTesting.cmake, leak detection off there
# and why). Needs what scripts/setup.sh installs.
# Three things keep the leg's build short (it is most of CI's time on 2 cores): a unity build
# (CMake compiles a target's sources a few at a time as one file: the leg's programs built in
# 223 s instead of 480 s on 2 cores, 2026-12-07, every test passing as before), only the programs
# those tests run are built (scripts/test_programs.py lists them), and the code is compiled at -O1 with line
# tables only (-g1): the sanitizers' reports keep file and line, the compiler spends 37 % less
# time on the heaviest test file than at RelWithDebInfo's -O2 -g (measured 26.6 s against 42.2 s);
# the tests' own files at -O0 (test/cmake/TribosTesting.cmake: 7.1 s against 14.4 s for
# test_smalse_m.cpp, the tests' run time unchanged, 97 s against 92 s with two more tests).
# Usage: scripts/sanitize.sh [extra cmake -D options]
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=${TRIBOS_BUILD_JOBS:-2}
labels='unit|small'
start=$(date +%s)
cmake -S . -B build-asan -G Ninja -DCMAKE_UNITY_BUILD=ON -DCMAKE_BUILD_TYPE=Sanitize -DCMAKE_CXX_FLAGS_SANITIZE="-O1 -g1 -DNDEBUG" \
  -DCMAKE_C_FLAGS_SANITIZE="-O1 -g1 -DNDEBUG" -DTRIBOS_SANITIZE=ON -DTRIBOS_ENABLE_PERF=OFF "$@" >/dev/null
# The programs the tests of $labels run (read from the configured tree: scripts/test_programs.py).
mapfile -t programs < <(python3 scripts/test_programs.py build-asan "$labels")
[ "${#programs[@]}" -gt 0 ] || exit 1
cmake --build build-asan -j "$jobs" --target "${programs[@]}"
built=$(date +%s)
ctest --test-dir build-asan --output-on-failure -j 2 -L "$labels"
echo "sanitize.sh: ${#programs[@]} programs built in $((built - start)) s, tests $(($(date +%s) - built)) s"
