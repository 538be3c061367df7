#!/usr/bin/env bash
# Installs what Tribos needs on Debian 12 (only what is missing: quiet and fast when all is
# there), then configures and builds into build/ (Release, ccache when present, -j2).
# Usage: scripts/setup.sh [extra cmake -D options]
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(build-essential cmake ninja-build ccache
  libtrilinos-tpetra-dev libtrilinos-amesos2-dev libtrilinos-belos-dev libtrilinos-teuchos-dev
  libtrilinos-kokkos-dev libtrilinos-kokkos-kernels-dev
  libtrilinos-shylu-dev libtrilinos-epetra-dev libtrilinos-epetraext-dev libtrilinos-triutils-dev
  libtrilinos-thyra-dev libtrilinos-rtop-dev libtrilinos-xpetra-dev libtrilinos-aztecoo-dev
  libptscotch-dev libmetis-dev libopenmpi-dev openmpi-bin libexodusii-dev libsuitesparse-dev
  libopenblas0-serial netcdf-bin nlohmann-json3-dev libgtest-dev)
# The element catalogue's reference tables in a unit test (mesh.ElementCatalogue.*); Intrepid2's
# headers include Sacado's.
packages+=(libtrilinos-shards-dev libtrilinos-intrepid2-dev libtrilinos-sacado-dev)
# meshio and its Exodus backend (only recommended by python3-meshio): the interoperability
# tests integration.meshio.* (skipped without them).
packages+=(python3-meshio python3-netcdf4)
# The pictures (doc/tools/plot_results.py) and their test integration.plotResults.*.
packages+=(python3-matplotlib)

source scripts/install_missing.sh
install_missing setup "${packages[@]}"

jobs=${TRIBOS_BUILD_JOBS:-2}
# TRIBOS_UNITY_BUILD=ON (set by .ci/run): CMake's unity build, a target's sources compiled a few
# at a time as one file. A clean build took 202 s instead of about 270 s on 2 cores, with the
# same bits (perf/tools/bit_identity.sh identical); off by default, where a rebuild after one
# change would recompile its whole batch.
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_UNITY_BUILD="${TRIBOS_UNITY_BUILD:-OFF}" "$@" >/dev/null
cmake --build build -j "$jobs"
