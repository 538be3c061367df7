#include "tribos/core/Parallel.hpp"

#include <omp.h>

#include <exception>
#include <mutex>

namespace tribos::core {

namespace {
int g_threads = 0;  // 0: use OpenMP's default (OMP_NUM_THREADS)
}

int numThreads() { return g_threads > 0 ? g_threads : omp_get_max_threads(); }

void setNumThreads(int n) { g_threads = n > 0 ? n : 0; }

void forEachSubdomain(int count, const std::function<void(int)>& body) {
  std::exception_ptr firstError;
  std::mutex errorMutex;
  // Threads run over subdomains; no library below may open a second level of threads.
  omp_set_max_active_levels(1);
  const int threads = numThreads() < count ? numThreads() : (count > 0 ? count : 1);
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
  for (int i = 0; i < count; ++i) {
    try {
      body(i);
    } catch (...) {
      std::lock_guard<std::mutex> lock(errorMutex);
      if (!firstError) firstError = std::current_exception();
    }
  }
  if (firstError) std::rethrow_exception(firstError);
}

}  // namespace tribos::core

#include <Kokkos_Core.hpp>

namespace tribos::core {
void warmUpKokkosForThreads() {
  double sum = 0.0;
  Kokkos::parallel_reduce(
      "tribos::core::warmUp", Kokkos::RangePolicy<Kokkos::Serial>(0, 16),
      KOKKOS_LAMBDA(const int i, double& s) { s += i; }, sum);
}
}  // namespace tribos::core
