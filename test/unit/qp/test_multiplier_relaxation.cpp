// qp::MultiplierRelaxation (src/MultiplierRelaxation.hpp): the omega of SMALSE-M's over-relaxed
// multiplier step, on the model it is built on: G mu made of modes that each contract by
// 1 - omega theta per outer iteration (theta in (0, 1): slow modes small, stiff ones near 1).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "MultiplierRelaxation.hpp"

using tribos::qp::MultiplierRelaxation;

namespace {
/// Runs `iterations` outer iterations of the mode model from G mu = start, with the omega that
/// `relax` chooses (or 1 without it); returns ||G mu|| at the end and the last omega.
struct ModelRun {
  double finalNorm, omega, unrelaxed;
};
ModelRun runModes(const std::vector<double>& theta, std::vector<double> gmu, int iterations, bool relax) {
  MultiplierRelaxation relaxation;
  auto norm = [](const std::vector<double>& v) {
    double s = 0.0;
    for (double x : v) s += x * x;
    return std::sqrt(s);
  };
  std::vector<double> previous;
  double omega = 1.0;
  for (int k = 0; k < iterations; ++k) {
    if (relax && !previous.empty()) {
      double dot = 0.0;
      for (size_t i = 0; i < gmu.size(); ++i) dot += gmu[i] * previous[i];
      omega = relaxation.next(norm(gmu), norm(previous), dot / (norm(gmu) * norm(previous)));
    }
    previous = gmu;
    for (size_t i = 0; i < gmu.size(); ++i) gmu[i] *= 1.0 - omega * theta[i];
  }
  return {norm(gmu), omega, relaxation.unrelaxedRatio()};
}
}  // namespace

// A slow mode (theta 0.4: r0 = 0.6) beside stiff ones: omega settles at 2 / (2 - r0), the
// unrelaxed ratio read back is r0, and 30 iterations end far below omega = 1's 0.6^30.
TEST(MultiplierRelaxation, findsTheBalancingOmegaOfASlowMode) {
  const std::vector<double> theta = {0.4, 0.9, 0.95}, start = {1.0, 1.0, 1.0};
  const auto fixed = runModes(theta, start, 30, false);
  const auto relaxed = runModes(theta, start, 30, true);
  // (to the stiff modes' remainder: (|1 - omega 0.95| / (1 - omega 0.4))^30 ~ 0.004)
  EXPECT_NEAR(relaxed.omega, 2.0 / (2.0 - 0.6), 1e-2);
  EXPECT_NEAR(relaxed.unrelaxed, 0.6, 1e-2);
  // The balanced rate is r0 / (2 - r0) = 3/7 per iteration once the stiff modes have died out.
  EXPECT_LT(relaxed.finalNorm, 1e-3 * fixed.finalNorm);
  EXPECT_LT(relaxed.finalNorm, std::pow(0.5, 30));
}

// Fast contraction (r0 <= 0.3) is left alone: omega stays 1 and the run is omega = 1's.
TEST(MultiplierRelaxation, leavesFastContractionAlone) {
  const std::vector<double> theta = {0.8, 0.95}, start = {1.0, 0.5};
  const auto fixed = runModes(theta, start, 12, false);
  const auto relaxed = runModes(theta, start, 12, true);
  EXPECT_EQ(relaxed.omega, 1.0);
  EXPECT_EQ(relaxed.finalNorm, fixed.finalNorm);
}

// What the model does not explain returns omega to 1: a growing ||G mu|| (the active set or the
// slip bound moved), a G mu that turned against the previous one (stiff modes overshooting), and
// a slow mode estimated above kSlowestRate is capped there.
TEST(MultiplierRelaxation, resetsWhenTheContractionIsNotSteadyAndCapsOmega) {
  MultiplierRelaxation r;
  EXPECT_NEAR(r.next(0.6, 1.0, 0.9), 2.0 / 1.4, 1e-12);
  EXPECT_EQ(r.next(1.1, 1.0, 0.9), 1.0);   // grew
  EXPECT_NEAR(r.next(0.6, 1.0, 0.9), 2.0 / 1.4, 1e-12);
  EXPECT_EQ(r.next(0.5, 1.0, -0.2), 1.0);  // turned
  EXPECT_NEAR(r.unrelaxedRatio(), 1.0 - 0.5 / (2.0 / 1.4), 1e-12);
  const double capped = 2.0 / (2.0 - MultiplierRelaxation::kSlowestRate);
  EXPECT_NEAR(r.next(0.99, 1.0, 0.99), capped, 1e-12);
  EXPECT_NEAR(r.unrelaxedRatio(), 0.99, 1e-12);
  // Under omega = 5/3 a measured 0.99 means r0 = 1 - 0.01 / (5/3): capped again, not above.
  EXPECT_NEAR(r.next(0.99, 1.0, 0.99), capped, 1e-12);
  EXPECT_LT(capped, 2.0);
}
