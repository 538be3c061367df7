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

}  // namespace tribos::core

namespace tribos::core {
/// Call once on the main thread right after Kokkos::initialize: runs one scalar reduction
/// so that the Serial back end's global scratch buffer exists before threads use kernels.
void warmUpKokkosForThreads();
}  // namespace tribos::core
