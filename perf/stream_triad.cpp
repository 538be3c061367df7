// STREAM-like triad a[i] = b[i] + s * c[i] with 1 and 2 OpenMP threads: the memory
// bandwidth that bounds an implicit F application (doc/measurements/performance.md). Counts 24 bytes per
// element (two loads, one store; write-allocate traffic not counted, as STREAM does).
// Each thread first-touches its own part of the arrays, then the best of `repeats` sweeps
// is reported (STREAM's convention: the best run is the one least disturbed by neighbours).
//
// Usage: build/bin/tribos_stream_triad [megabytes per array (default 400)] [repeats (default 20)]
// Prints "threads,megabytes_per_array,best_GB_s,median_GB_s" per thread count.
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <vector>

namespace {

struct Arrays {
  std::unique_ptr<double[]> a, b, c;
  long n = 0;
};

// Allocates without touching, then fills with the same static schedule as the sweep, so that
// pages land where (and in the cache state) the sweeping thread wants them.
Arrays allocate(long n, int threads) {
  Arrays x;
  x.n = n;
  x.a.reset(new double[n]);
  x.b.reset(new double[n]);
  x.c.reset(new double[n]);
#pragma omp parallel for schedule(static) num_threads(threads)
  for (long i = 0; i < n; ++i) {
    x.a[i] = 0.0;
    x.b[i] = 1.0;
    x.c[i] = 2.0;
  }
  return x;
}

double sweepSeconds(Arrays& x, double scalar, int threads) {
  double* a = x.a.get();
  const double* b = x.b.get();
  const double* c = x.c.get();
  const long n = x.n;
  const auto start = std::chrono::steady_clock::now();
#pragma omp parallel for schedule(static) num_threads(threads)
  for (long i = 0; i < n; ++i) a[i] = b[i] + scalar * c[i];
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

int main(int argc, char** argv) {
  const double megabytes = argc > 1 ? std::atof(argv[1]) : 400.0;
  const int repeats = argc > 2 ? std::max(1, std::atoi(argv[2])) : 20;
  const long n = static_cast<long>(megabytes * 1e6 / sizeof(double));
  std::printf("threads,megabytes_per_array,best_GB_s,median_GB_s\n");
  for (int threads : {1, 2}) {
    Arrays x = allocate(n, threads);
    std::vector<double> rates;
    sweepSeconds(x, 3.0, threads);  // warm-up: page tables, frequency
    for (int r = 0; r < repeats; ++r) rates.push_back(24.0 * static_cast<double>(n) / sweepSeconds(x, 3.0, threads) / 1e9);
    std::sort(rates.begin(), rates.end());
    volatile double sink = x.a[n / 2];  // keep the stores observable
    (void)sink;
    std::printf("%d,%.0f,%.1f,%.1f\n", threads, megabytes, rates.back(), rates[rates.size() / 2]);
  }
  return 0;
}
