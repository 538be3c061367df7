#!/usr/bin/env bash
# The fuzz leg: builds the libFuzzer targets with clang into build-fuzz/ (TRIBOS_FUZZ=ON:
# coverage + AddressSanitizer; only the targets and what they link, no tests) and runs each
# for TRIBOS_FUZZ_SECONDS (default 30) from the seed corpus (CTest label fuzz). A finding
# fails its test and leaves the input as build-fuzz/test/fuzz/crash-* (or timeout-*, leak-*):
# reproduce with build-fuzz/bin/fuzz_gmsh_reader FILE. Installs clang and its libFuzzer
# runtime from Debian when missing (as scripts/setup.sh does for the rest).
# Usage: scripts/fuzz.sh [extra cmake -D options]
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/install_missing.sh
install_missing fuzz clang libclang-rt-14-dev
jobs=${TRIBOS_BUILD_JOBS:-2}
CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTRIBOS_FUZZ=ON \
  -DTRIBOS_ENABLE_TESTS=OFF -DTRIBOS_ENABLE_PERF=OFF -DTRIBOS_FUZZ_SECONDS="${TRIBOS_FUZZ_SECONDS:-30}" "$@" >/dev/null
cmake --build build-fuzz -j "$jobs" --target tribos_fuzz_targets
ctest --test-dir build-fuzz --output-on-failure -L fuzz
