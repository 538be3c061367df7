#pragma once
/// \file Parallel.hpp
/// The one place that runs work over the subdomains of a rank on threads.
///
/// Debian's Kokkos 3.4 is Serial-only and not thread-safe in general (TOOLCHAIN.md): the
/// body of forEachSubdomain must follow these rules, which the callers in mesh/, fem/ and
/// feti/ satisfy by construction:
///  1. every managed Kokkos::View / Teuchos::RCP is created, copied and destroyed by one
///     thread only; across threads pass raw pointers or unmanaged Views over std::vector
///     storage allocated before the parallel region;
///  2. inside the body only Kokkos::parallel_for(RangePolicy) and scalar parallel_reduce;
///  3. Tpetra / Belos / Amesos2 objects stay on the main thread.
/// An exception thrown by any body is rethrown on the calling thread after all finish.
#include <functional>

namespace tribos::core {

/// Number of threads forEachSubdomain uses (OMP_NUM_THREADS unless set by setNumThreads).
int numThreads();
/// Overrides the thread count (>= 1) for subsequent calls.
void setNumThreads(int n);
/// Runs body(i) for i in [0, count) on numThreads() threads, dynamic schedule.
void forEachSubdomain(int count, const std::function<void(int)>& body);

/// Entries per chunk of forEachChunk's vector loops: 64 KiB of doubles, so that a loop over
/// several vectors keeps its chunk in L2 and a dual vector of 10^5 entries has enough chunks
/// for two threads.
constexpr long kVectorChunk = 8192;
/// The number of chunks of [0, n): ceil(n / chunk), at least 1.
long numChunks(long n, long chunk = kVectorChunk);
/// Runs body(c, begin, end) for the FIXED chunks c = 0 .. numChunks(n) - 1, [begin, end) =
/// [c chunk, min(n, (c + 1) chunk)), on the threads of forEachSubdomain (inline when there
/// is one chunk). The chunks do not depend on the thread count, so a body that only writes
/// its own entries, or its own slot c of a reduction combined in chunk order afterwards,
/// gives the same bits on any number of threads. Same rules for the body as forEachSubdomain.
void forEachChunk(long n, const std::function<void(long, long, long)>& body, long chunk = kVectorChunk);

}  // namespace tribos::core

namespace tribos::core {
/// Call once on the main thread right after Kokkos::initialize: runs one scalar reduction
/// so that the Serial back end's global scratch buffer exists before threads use kernels.
void warmUpKokkosForThreads();
}  // namespace tribos::core
