#!/usr/bin/env bash
# Packs build/bin/tribos (the launcher) and tribos-solver beside it with every shared library they need and Open MPI's runtime (Debian 12
# layout) into one tarball, for a machine where nothing can be installed (same x86-64, glibc
# at least Debian 12's 2.36). Extract it into / as root there:
#   tar -xJf tribos-runtime.tar.xz -C /
#   export LD_LIBRARY_PATH=/opt/tribos/lib PATH=/opt/tribos/bin:$PATH
#   mpirun --allow-run-as-root -x LD_LIBRARY_PATH -np 16 tribos --input input/two_bricks.xml ...
# The program and its libraries go to /opt/tribos/{bin,lib}; Open MPI's and PMIx's plugin and
# help folders go to Debian's absolute paths, which Open MPI has compiled in. libc, libm,
# libpthread, libdl, librt and the loader stay the target's own.
# Usage: perf/tools/bundle_runtime.sh [output tarball (default tribos-runtime.tar.xz)] [tribos binary]
set -euo pipefail
out=$(realpath -m "${1:-tribos-runtime.tar.xz}")
binary=$(realpath "${2:-$(dirname "$0")/../../build/bin/tribos}")
multiarch=/usr/lib/x86_64-linux-gnu
stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
mkdir -p "$stage/opt/tribos/bin" "$stage/opt/tribos/lib"
solver=$(dirname "$binary")/tribos-solver  # the launcher runs it from its own folder
cp "$binary" "$stage/opt/tribos/bin/tribos"
cp "$solver" "$stage/opt/tribos/bin/tribos-solver"
cp /usr/bin/orterun "$stage/opt/tribos/bin/mpirun"
cp /usr/bin/orted "$stage/opt/tribos/bin/orted"

# Libraries: those of the program, of mpirun/orted and of every Open MPI / PMIx plugin.
objects=("$binary" "$solver" /usr/bin/orterun /usr/bin/orted "$multiarch"/openmpi/lib/openmpi3/*.so "$multiarch"/pmix2/lib/pmix/*.so)
for o in "${objects[@]}"; do ldd "$o" | awk '/=> \//{print $1, $3}'; done | sort -u |
  while read -r soname path; do
    case "$soname" in
      libc.so.*|libm.so.*|libpthread.so.*|libdl.so.*|librt.so.*|ld-linux*|libresolv.so.*|libutil.so.*) continue ;;
    esac
    cp -L "$path" "$stage/opt/tribos/lib/$soname"
  done

# Open MPI and PMIx at Debian's paths (plugins, help texts, configuration).
tar -C / -cf - "${multiarch#/}/openmpi/lib" "${multiarch#/}/pmix2/lib/pmix" "${multiarch#/}/pmix2/lib/libpmix.so.2" \
  "${multiarch#/}/pmix2/lib/libpmix.so.2.6.2" "${multiarch#/}/pmix2/share" usr/share/openmpi etc/openmpi |
  tar -C "$stage" -xf -
XZ_OPT="-6 -T2" tar -C "$stage" -cJf "$out" .
echo "$out: $(du -h "$out" | cut -f1), $(ls "$stage/opt/tribos/lib" | wc -l) libraries"
