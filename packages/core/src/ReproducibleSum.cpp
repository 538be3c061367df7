#include "tribos/core/ReproducibleSum.hpp"

#include <Teuchos_Comm.hpp>
#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_DefaultMpiComm.hpp>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

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
  // In place where the communicator is MPI's: the slots of G G^T's blocks are the size of its
  // replicated pattern (twice its values), and a second array of them would double that.
  // The slots hold exact sums, so the order MPI adds them in does not matter.
  if (const auto* mpi = dynamic_cast<const Teuchos::MpiComm<int>*>(comm)) {
    MPI_Allreduce(MPI_IN_PLACE, slots.data(), static_cast<int>(slots.size()), MPI_DOUBLE, MPI_SUM,
                  (*mpi->getRawMpiComm())());
    return;
  }
  std::vector<double> global(slots.size(), 0.0);
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, static_cast<int>(slots.size()), slots.data(), global.data());
  slots.swap(global);
}

namespace {
typedef double Pair __attribute__((vector_size(16)));

Pair load(const double* p) {
  Pair v;
  __builtin_memcpy(&v, p, sizeof(Pair));
  return v;
}

// The addends x_i = term(i) two at a time (term2(i) = {x_i, x_i+1}); the scalar tail by term.
// max |x_i| over this rank, +inf when some x_i is not finite (so that every rank falls back
// together; MPI's MAX of a NaN is not defined).
template <class Term, class Term2>
double localBound(std::size_t n, Term term, Term2 term2) {
  Pair m = {0.0, 0.0}, check = {0.0, 0.0};  // check: sum of x - x, NaN once an x is not finite
  std::size_t i = 0;
  for (; i + 2 <= n; i += 2) {
    const Pair x = term2(i), a = x < 0.0 ? -x : x;
    m = a > m ? a : m;
    check += x - x;
  }
  double bound = std::max(m[0], m[1]), nonFinite = check[0] + check[1];
  for (; i < n; ++i) {
    const double x = term(i);
    bound = std::max(bound, std::abs(x));
    nonFinite += x - x;
  }
  return nonFinite == 0.0 ? bound : std::numeric_limits<double>::infinity();
}

// slots[0..2) += the slices of every x_i (SumBins::deposit, the same operations), with
// four independent accumulators per slice (exact sums: their order does not matter), so
// that the loop runs at the adds' throughput, not their latency.
template <class Term, class Term2>
void depositAll(const SumBins& bins, std::size_t n, Term term, Term2 term2, double* slots) {
  static_assert(SumBins::kSlices == 2, "depositAll is written for two slices");
  const Pair s0 = {bins.sigma(0), bins.sigma(0)}, s1 = {bins.sigma(1), bins.sigma(1)};
  Pair a0 = {0.0, 0.0}, b0 = a0, a1 = a0, b1 = a0;
  std::size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    const Pair x = term2(i), y = term2(i + 2);
    const Pair qx = (x + s0) - s0, qy = (y + s0) - s0, rx = x - qx, ry = y - qy;
    a0 += qx;
    b0 += qy;
    a1 += (rx + s1) - s1;
    b1 += (ry + s1) - s1;
  }
  a0 += b0;
  a1 += b1;
  slots[0] += a0[0] + a0[1];
  slots[1] += a1[0] + a1[1];
  for (; i < n; ++i) bins.deposit(term(i), slots);
}
}  // namespace

double reproducibleSum(const Teuchos::Comm<int>* comm, const double* x, std::size_t n, long long count) {
  auto term = [x](std::size_t i) { return x[i]; };
  auto term2 = [x](std::size_t i) { return load(x + i); };
  const SumBins bins(globalMax(comm, localBound(n, term, term2)), count);
  std::vector<double> slots(SumBins::kSlices, 0.0);
  depositAll(bins, n, term, term2, slots.data());
  allReduceSlots(comm, slots);
  return SumBins::combine(slots.data());
}

double reproducibleDot(const Teuchos::Comm<int>* comm, const double* a, const double* b, std::size_t n,
                       long long count) {
  auto term = [a, b](std::size_t i) { return a[i] * b[i]; };
  auto term2 = [a, b](std::size_t i) { return load(a + i) * load(b + i); };
  const SumBins bins(globalMax(comm, localBound(n, term, term2)), count);
  std::vector<double> slots(SumBins::kSlices, 0.0);
  depositAll(bins, n, term, term2, slots.data());
  allReduceSlots(comm, slots);
  return SumBins::combine(slots.data());
}

void reproducibleDots(const Teuchos::Comm<int>* comm, const double* a, const double* b, const double* c,
                      const double* d, std::size_t n, long long count, double out[2]) {
  const double* left[2] = {a, c};
  const double* right[2] = {b, d};
  reproducibleDots(comm, left, right, 2, n, count, out);
}

void reproducibleDots(const Teuchos::Comm<int>* comm, const double* const* a, const double* const* b, int k,
                      std::size_t n, long long count, double* out) {
  auto terms = [&](int i) {
    const double *ai = a[i], *bi = b[i];
    return std::make_pair([ai, bi](std::size_t j) { return ai[j] * bi[j]; },
                          [ai, bi](std::size_t j) { return load(ai + j) * load(bi + j); });
  };
  // Each sum keeps its own bound (its own quanta), as reproducibleDot; all bounds travel in
  // one all-reduce of length k, all slots in one of length kSlices k.
  std::vector<double> local(k), bound(k);
  for (int i = 0; i < k; ++i) {
    const auto [term, term2] = terms(i);
    local[i] = localBound(n, term, term2);
  }
  bound = local;
  if (comm && comm->getSize() > 1) Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, k, local.data(), bound.data());
  std::vector<double> slots(static_cast<std::size_t>(SumBins::kSlices) * k, 0.0);
  for (int i = 0; i < k; ++i) {
    const auto [term, term2] = terms(i);
    depositAll(SumBins(bound[i], count), n, term, term2, slots.data() + SumBins::kSlices * i);
  }
  allReduceSlots(comm, slots);
  for (int i = 0; i < k; ++i) out[i] = SumBins::combine(slots.data() + SumBins::kSlices * i);
}

}  // namespace tribos::core
