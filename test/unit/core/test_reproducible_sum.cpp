// core::ReproducibleSum: the bits of a sum do not depend on the order of its addends nor on
// how they are split into parts (ranks, thread chunks), and the result is within the bound
// documented in ReproducibleSum.hpp of a far more accurate reference.
#include <gtest/gtest.h>

#include <Teuchos_DefaultComm.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "tribos/core/ReproducibleSum.hpp"

namespace {
using tribos::core::SumBins;

// Signed values spread over 2^-40 .. 2^40 (81 binades), a few exact zeros.
std::vector<double> wideValues(size_t n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> mantissa(1.0, 2.0), exponent(-40.0, 40.0);
  std::vector<double> x(n);
  for (size_t i = 0; i < n; ++i) {
    x[i] = (rng() % 2 ? -1.0 : 1.0) * std::ldexp(mantissa(rng), static_cast<int>(exponent(rng)));
    if (i % 97 == 0) x[i] = 0.0;
  }
  return x;
}

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof(double)) == 0; }

// The sum of x deposited in `parts` contiguous parts, each into its own slots, the parts'
// slots then added in reverse part order (what ranks and thread chunks do).
double splitSum(const std::vector<double>& x, int parts) {
  double bound = 0.0;
  for (double v : x) bound = std::max(bound, std::abs(v));
  const SumBins bins(bound, static_cast<long long>(x.size()));
  std::vector<std::vector<double>> slots(parts, std::vector<double>(SumBins::kSlices, 0.0));
  for (size_t i = 0; i < x.size(); ++i) bins.deposit(x[i], slots[i * parts / x.size()].data());
  std::vector<double> total(SumBins::kSlices, 0.0);
  for (int p = parts - 1; p >= 0; --p)
    for (int j = 0; j < SumBins::kSlices; ++j) total[j] += slots[p][j];
  return SumBins::combine(total.data());
}

// Kahan-compensated sum in long double (64-bit mantissa): error ~2^-64 sum |x|, far below
// the bound tested.
long double reference(const std::vector<double>& x) {
  long double s = 0.0L, c = 0.0L;
  for (double v : x) {
    const long double y = v - c, t = s + y;
    c = (t - s) - y;
    s = t;
  }
  return s;
}
}  // namespace

TEST(ReproducibleSum, sameBitsInAnyOrderAndSplitAndWithinTheBound) {
  for (size_t n : {1u, 7u, 1000u, 100000u}) {
    SCOPED_TRACE("n = " + std::to_string(n));
    auto x = wideValues(n, 11u + static_cast<unsigned>(n));
    const double sum = tribos::core::reproducibleSum(nullptr, x.data(), x.size(), static_cast<long long>(n));
    // Other orders.
    std::mt19937 rng(5);
    for (int trial = 0; trial < 3; ++trial) {
      auto y = x;
      if (trial == 0) std::reverse(y.begin(), y.end());
      if (trial == 1) std::sort(y.begin(), y.end(), [](double a, double b) { return std::abs(a) > std::abs(b); });
      if (trial == 2) std::shuffle(y.begin(), y.end(), rng);
      EXPECT_TRUE(sameBits(tribos::core::reproducibleSum(nullptr, y.data(), y.size(), static_cast<long long>(n)), sum));
      for (int parts : {2, 3, 5, 64}) EXPECT_TRUE(sameBits(splitSum(y, parts), sum)) << parts << " parts";
    }
    // The documented bound: 2^(2L - 102) N M + 2^-52 |S|, L = ceil(log2 N).
    double M = 0.0;
    for (double v : x) M = std::max(M, std::abs(v));
    int L = 0;
    while ((1LL << L) < static_cast<long long>(n)) ++L;
    const long double exact = reference(x);
    const double bound = std::ldexp(static_cast<double>(n) * M, 2 * L - 102) + std::ldexp(std::abs(static_cast<double>(exact)), -52);
    EXPECT_LE(std::abs(static_cast<long double>(sum) - exact), bound);
    // Plain recursive summation in this order is further off (the test would not tell
    // the two apart otherwise) for the large n.
    if (n >= 1000) {
      double plain = 0.0;
      for (double v : x) plain += v;
      EXPECT_GT(std::abs(static_cast<long double>(plain) - exact), std::abs(static_cast<long double>(sum) - exact));
    }
  }
}

TEST(ReproducibleSum, everyRankSplitGivesTheBitsOfOneProcess) {
  // The same global list on every rank; each rank sums its own contiguous part over the
  // communicator, with parts of unequal sizes.
  const auto comm = Teuchos::DefaultComm<int>::getComm();
  const int rank = comm->getRank(), size = comm->getSize();
  const auto x = wideValues(20000, 3u), y = wideValues(20000, 4u);
  const long long n = static_cast<long long>(x.size());
  const size_t first = x.size() * rank * rank / (size * size), end = x.size() * (rank + 1) * (rank + 1) / (size * size);
  const double whole = tribos::core::reproducibleSum(nullptr, x.data(), x.size(), n);
  const double parted = tribos::core::reproducibleSum(comm.get(), x.data() + first, end - first, n);
  EXPECT_TRUE(sameBits(whole, parted)) << whole << " vs " << parted;
  const double dotWhole = tribos::core::reproducibleDot(nullptr, x.data(), y.data(), x.size(), n);
  const double dotParted = tribos::core::reproducibleDot(comm.get(), x.data() + first, y.data() + first, end - first, n);
  EXPECT_TRUE(sameBits(dotWhole, dotParted));
  // The dot product is the reproducible sum of the rounded products (vectorised or not).
  std::vector<double> products(x.size());
  for (size_t i = 0; i < x.size(); ++i) products[i] = x[i] * y[i];
  EXPECT_TRUE(sameBits(dotWhole, tribos::core::reproducibleSum(nullptr, products.data(), products.size(), n)));
  EXPECT_TRUE(sameBits(dotWhole, splitSum(products, 7)));
  double both[2];
  tribos::core::reproducibleDots(comm.get(), x.data() + first, y.data() + first, x.data() + first, x.data() + first,
                                 end - first, n, both);
  EXPECT_TRUE(sameBits(both[0], dotWhole));
  EXPECT_TRUE(sameBits(both[1], tribos::core::reproducibleDot(nullptr, x.data(), x.data(), x.size(), n)));
  // k sums in one pair of all-reduces: each has the bits of its own reproducibleDot, also when
  // their sizes differ by orders of magnitude (each keeps its own quanta; shared quanta would
  // round the small one on the large one's grid).
  std::vector<double> small(x.size());
  for (size_t i = 0; i < x.size(); ++i) small[i] = 1e-9 * y[i];
  const double* left[3] = {x.data() + first, small.data() + first, y.data() + first};
  const double* right[3] = {y.data() + first, x.data() + first, y.data() + first};
  double three[3];
  tribos::core::reproducibleDots(comm.get(), left, right, 3, end - first, n, three);
  EXPECT_TRUE(sameBits(three[0], dotWhole));
  EXPECT_TRUE(sameBits(three[1], tribos::core::reproducibleDot(nullptr, small.data(), x.data(), x.size(), n)));
  EXPECT_TRUE(sameBits(three[2], tribos::core::reproducibleDot(nullptr, y.data(), y.data(), y.size(), n)));
}

TEST(ReproducibleSum, zerosAndNonFiniteValues) {
  std::vector<double> x(10, 0.0);
  EXPECT_EQ(tribos::core::reproducibleSum(nullptr, x.data(), x.size(), 10), 0.0);
  x[3] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(std::isnan(tribos::core::reproducibleSum(nullptr, x.data(), x.size(), 10)));
  x[3] = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(std::isfinite(tribos::core::reproducibleSum(nullptr, x.data(), x.size(), 10)));
  EXPECT_FALSE(SumBins(std::numeric_limits<double>::infinity(), 10).reproducible());
  EXPECT_TRUE(SumBins(1e300, 1000).reproducible());
  // Tiny values: exact sums of two, quanta raised to the smallest normal.
  std::vector<double> tiny{std::ldexp(1.0, -1000), std::ldexp(1.0, -1000)};
  EXPECT_EQ(tribos::core::reproducibleSum(nullptr, tiny.data(), tiny.size(), 2), std::ldexp(1.0, -999));
}
