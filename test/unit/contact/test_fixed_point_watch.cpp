// The divergence test of the Coulomb successive approximations (FixedPointWatch, used by
// solveContact's inexact fixed point): no scene of the stability sweeps (doc/stability.md)
// makes the slip-bound change grow 8 updates in a row, so a test double feeds the sequences.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "tribos/contact/FixedPointWatch.hpp"

namespace {
using tribos::contact::FixedPointWatch;
constexpr double kInf = std::numeric_limits<double>::infinity();

// The number of updates after which the watch reported divergence, 0 if never.
int firesAfter(FixedPointWatch watch, const std::vector<double>& changes) {
  for (size_t k = 0; k < changes.size(); ++k)
    if (watch.diverges(changes[k])) return static_cast<int>(k + 1);
  return 0;
}
}  // namespace

TEST(FixedPointWatch, aGrowingSlipBoundChangeIsDivergence) {
  // The first update from g = 0 is infinite, then the change grows by 1.5 per update.
  std::vector<double> changes{kInf, 1e-3};
  for (int k = 0; k < 20; ++k) changes.push_back(changes.back() * 1.5);
  FixedPointWatch watch(8);
  EXPECT_EQ(firesAfter(watch, changes), 12);  // 8 growths after a warm-up of 3 (+1 to compare)
  for (double c : changes)
    if (watch.diverges(c)) break;
  EXPECT_NE(watch.message().find("the Coulomb fixed point diverges"), std::string::npos) << watch.message();
  EXPECT_NE(watch.message().find("8 consecutive updates"), std::string::npos) << watch.message();
  // A shorter window fires earlier, a longer one later.
  EXPECT_EQ(firesAfter(FixedPointWatch(2), changes), 6);
  EXPECT_EQ(firesAfter(FixedPointWatch(12), changes), 16);
}

TEST(FixedPointWatch, convergingAndStagnatingSequencesAreNoDivergence) {
  // Converging (the paper problem's sequence shape: a rise at the 3rd update, then down).
  EXPECT_EQ(firesAfter(FixedPointWatch(8), {kInf, 8.1e-2, 1.2e-1, 1.1e-2, 2.1e-3, 2.2e-4, 1.7e-5, 1.0e-6}), 0);
  // Stagnating: oscillating around 3e-5 for 200 updates (the material contrast 1e4 run):
  // never 8 growths in a row, so it ends at the outer iteration cap, "not converged".
  std::vector<double> oscillating{kInf};
  for (int k = 0; k < 200; ++k) oscillating.push_back(3e-5 * (1.0 + 0.5 * std::sin(1.7 * k)));
  EXPECT_EQ(firesAfter(FixedPointWatch(8), oscillating), 0);
  // Seven growths in a row are not yet eight.
  std::vector<double> seven{kInf, 1, 1, 1, 1, 1};
  for (int k = 1; k <= 7; ++k) seven.push_back(1.0 + k);
  seven.push_back(0.5);
  EXPECT_EQ(firesAfter(FixedPointWatch(8), seven), 0);
  seven.pop_back();
  seven.push_back(9.0);  // the eighth growth
  EXPECT_EQ(firesAfter(FixedPointWatch(8), seven), static_cast<int>(seven.size()));
}

TEST(FixedPointWatch, aNanChangeIsDivergenceAtOnce) {
  FixedPointWatch watch(8);
  EXPECT_FALSE(watch.diverges(kInf));
  EXPECT_TRUE(watch.diverges(std::numeric_limits<double>::quiet_NaN()));
  EXPECT_EQ(watch.message(), "diverged: the slip bound became NaN");
}
