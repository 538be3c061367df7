#include "tribos/core/ReproducibleSum.hpp"

#include <Teuchos_Comm.hpp>
#include <Teuchos_CommHelpers.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace tribos::core {

namespace {
// Quanta of 2^(k - 52) with k below this would be subnormal: raised to it (a larger k only
// coarsens the slice, the sums stay exact).
constexpr int kLowestK = -1021 + 52;
// sigma = 1.5 * 2^k and the partial sums up to 2^(k + 1) must stay finite.
constexpr int kHighestK = 1021;
}  // namespace

SumBins::SumBins(double bound, long long count) {
  int L = 0;  // ceil(log2(count))
  while (L < 62 && (1LL << L) < count) ++L;
  int e = 0;
  if (bound > 0.0 && std::isfinite(bound)) std::frexp(bound, &e);  // bound < 2^e
  int k = e + L + 1;
  if (!std::isfinite(bound) || k > kHighestK || L > 50) {
    // Plain addition: sigma = 0 puts x whole into slot 0.
    std::fill(sigma_, sigma_ + kSlices, 0.0);
    reproducible_ = false;
    return;
  }
  for (int j = 0; j < kSlices; ++j) {
    k = std::max(k, kLowestK);
    sigma_[j] = std::ldexp(1.5, k);
    k -= 52 - L;  // the remainder is at most 2^(k - 53): N of them fit 2^(k - 53 + L)
  }
}

double globalMax(const Teuchos::Comm<int>* comm, double local) {
  if (!comm || comm->getSize() == 1) return local;
  double global = 0.0;
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, 1, &local, &global);
  return global;
}

void allReduceSlots(const Teuchos::Comm<int>* comm, std::vector<double>& slots) {
  if (!comm || comm->getSize() == 1 || slots.empty()) return;
  std::vector<double> global(slots.size(), 0.0);
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, static_cast<int>(slots.size()), slots.data(), global.data());
  slots.swap(global);
}

namespace {
// max |x_i| over this rank, +inf when some x_i is not finite (so that every rank falls back
// together; MPI's MAX of a NaN is not defined).
template <class Term>
double localBound(std::size_t n, Term term) {
  double m = 0.0;
  bool finite = true;
  for (std::size_t i = 0; i < n; ++i) {
    const double x = term(i);
    finite = finite && std::isfinite(x);
    m = std::max(m, std::abs(x));
  }
  return finite ? m : std::numeric_limits<double>::infinity();
}
}  // namespace

double reproducibleSum(const Teuchos::Comm<int>* comm, const double* x, std::size_t n, long long count) {
  const SumBins bins(globalMax(comm, localBound(n, [x](std::size_t i) { return x[i]; })), count);
  std::vector<double> slots(SumBins::kSlices, 0.0);
  for (std::size_t i = 0; i < n; ++i) bins.deposit(x[i], slots.data());
  allReduceSlots(comm, slots);
  return SumBins::combine(slots.data());
}

double reproducibleDot(const Teuchos::Comm<int>* comm, const double* a, const double* b, std::size_t n,
                       long long count) {
  const SumBins bins(globalMax(comm, localBound(n, [a, b](std::size_t i) { return a[i] * b[i]; })), count);
  std::vector<double> slots(SumBins::kSlices, 0.0);
  for (std::size_t i = 0; i < n; ++i) bins.deposit(a[i] * b[i], slots.data());
  allReduceSlots(comm, slots);
  return SumBins::combine(slots.data());
}

void reproducibleDots(const Teuchos::Comm<int>* comm, const double* a, const double* b, const double* c,
                      const double* d, std::size_t n, long long count, double out[2]) {
  // Each sum keeps its own bound (its own quanta); both travel in one all-reduce of length 2.
  double local[2] = {localBound(n, [a, b](std::size_t i) { return a[i] * b[i]; }),
                     localBound(n, [c, d](std::size_t i) { return c[i] * d[i]; })};
  double bound[2] = {local[0], local[1]};
  if (comm && comm->getSize() > 1) Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, 2, local, bound);
  const SumBins first(bound[0], count), second(bound[1], count);
  std::vector<double> slots(2 * SumBins::kSlices, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    first.deposit(a[i] * b[i], slots.data());
    second.deposit(c[i] * d[i], slots.data() + SumBins::kSlices);
  }
  allReduceSlots(comm, slots);
  out[0] = SumBins::combine(slots.data());
  out[1] = SumBins::combine(slots.data() + SumBins::kSlices);
}

}  // namespace tribos::core
