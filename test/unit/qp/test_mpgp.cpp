// qp::Mpgp (ALGORITHMS.md 5) on small dense QPs: against the exact active-set enumeration
// for bound constraints, and on bounds + discs + ellipses + segments + points + free
// entries against the KKT conditions (least-squares multipliers, independent of the set's
// own gradient splitting) and an ADMM reference. The counters must add up and agree with
// the products counted by the operator; the power method estimates ||A||.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "DenseQp.hpp"
#include "tribos/qp/Mpgp.hpp"
#include "tribos/qp/SeparableSet.hpp"

using namespace tribos;
using test::Dense;

namespace {
void expectConsistentCounters(const qp::MpgpCounters& c, const test::DenseOperator& op, long long before) {
  EXPECT_EQ(c.operatorApplications, op.applications - before);
  EXPECT_EQ(c.iterations, c.cgSteps + c.expansionSteps + c.proportioningSteps);
}
}  // namespace

TEST(powerMethod, estimatesTheNormFromBelowAndCountsProducts) {
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const Dense A = test::randomSpd(12, 40.0, seed);
    test::DenseOperator op(A);
    auto map = test::makeMap(12, test::selfComm());
    long long applications = 0;
    const double estimate = qp::powerMethod(op, *map, 500, 1e-14, &applications);
    EXPECT_EQ(applications, op.applications);
    EXPECT_LE(applications, 500);
    EXPECT_LE(estimate, 40.0 * (1 + 1e-12));  // ||A x|| / ||x|| never exceeds ||A||
    EXPECT_NEAR(estimate, 40.0, 40.0 * 1e-3);
    // Deterministic: the same estimate again.
    EXPECT_EQ(qp::powerMethod(op, *map, 500, 1e-14, nullptr), estimate);
  }
}

TEST(lanczosNorm, estimatesTheNormFromBelowInFewerProductsThanThePowerMethod) {
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const Dense A = test::randomSpd(40, 1000.0, seed);
    test::DenseOperator op(A);
    auto map = test::makeMap(40, test::selfComm());
    long long lanczos = 0, power = 0;
    const double estimate = qp::lanczosNorm(op, *map, 100, 1e-6, &lanczos);
    qp::powerMethod(op, *map, 500, 1e-6, &power);
    EXPECT_EQ(lanczos, op.applications - power);
    EXPECT_LE(estimate, 1000.0 * (1 + 1e-12)) << "seed " << seed;  // a Ritz value never exceeds lambda_max
    EXPECT_NEAR(estimate, 1000.0, 1000.0 * 1e-5) << "seed " << seed;
    EXPECT_LT(lanczos, power) << "seed " << seed;
    EXPECT_EQ(qp::lanczosNorm(op, *map, 100, 1e-6, nullptr), estimate);  // deterministic
  }
}

TEST(Mpgp, matchesActiveSetEnumerationOnBoundConstrainedQps) {
  int activeBounds = 0;
  for (unsigned seed = 1; seed <= 30; ++seed) {
    const int n = 6 + seed % 5;
    const Dense A = test::randomSpd(n, seed % 2 ? 50.0 : 500.0, seed);
    std::mt19937 gen(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<double> b(n), lower;
    for (double& v : b) v = u(gen);
    std::vector<int> bounded;
    for (int i = 0; i < n; ++i)
      if (u(gen) < 0.4) bounded.push_back(i);
    for (size_t k = 0; k < bounded.size(); ++k) lower.push_back(0.2 * u(gen));
    const auto exact = test::enumerateActiveSets(A, b, bounded, lower);
    ASSERT_EQ(exact.size(), static_cast<size_t>(n));
    for (size_t k = 0; k < bounded.size(); ++k) activeBounds += exact[bounded[k]] <= lower[k] + 1e-12;

    auto map = test::makeMap(n, test::selfComm());
    test::BlockSet blocks;
    blocks.boundIndex = bounded;
    blocks.lower = lower;
    const auto omega = blocks.build(*map);
    test::DenseOperator op(A);
    const double normA = 1.01 * qp::powerMethod(op, *map, 200, 1e-12, nullptr);
    const long long before = op.applications;
    qp::Vector bv(map), x(map), g(map);
    test::scatter(b, bv);
    const double tol = 1e-12 * test::norm2(b);
    const auto counters =
        qp::Mpgp().solve(op, bv, omega, normA, x, g, [&](double gp, const qp::Vector&) { return gp <= tol; });
    EXPECT_TRUE(counters.converged);
    EXPECT_LE(counters.projectedGradientNorm, tol);
    expectConsistentCounters(counters, op, before);
    const auto xs = test::gather(x);
    EXPECT_LE(test::maxDifference(xs, exact), 1e-8) << "seed " << seed;
    // g is returned as A x - b.
    auto r = test::matVec(A, xs);
    for (int i = 0; i < n; ++i) r[i] -= b[i];
    EXPECT_LE(test::maxDifference(test::gather(g), r), 1e-12);
  }
  EXPECT_GT(activeBounds, 20);
}

TEST(Mpgp, appliesThePreconditionerOnlyWhereACgStepUsesIt) {
  // The search direction z = chi_F M^-1 phi is made when the next step needs it (a CG step or
  // an expansion, both of which start from a product with p); a proportioning step and the end
  // of the solve do not use it, so no application is made for them. The solution and every
  // other count are those of the eager direction (MPGP's bits do not change).
  int proportioning = 0;
  for (unsigned seed = 1; seed <= 30; ++seed) {
    const int n = 8 + seed % 7;
    const Dense A = test::randomSpd(n, 300.0, seed);
    std::mt19937 gen(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<double> b(n), lower;
    for (double& v : b) v = u(gen);
    std::vector<int> bounded;
    for (int i = 0; i < n; ++i)
      if (u(gen) < 0.6) bounded.push_back(i);
    for (size_t k = 0; k < bounded.size(); ++k) lower.push_back(0.2 * u(gen));
    const auto exact = test::enumerateActiveSets(A, b, bounded, lower);
    auto map = test::makeMap(n, test::selfComm());
    test::BlockSet blocks;
    blocks.boundIndex = bounded;
    blocks.lower = lower;
    const auto omega = blocks.build(*map);
    test::DenseOperator op(A);
    Dense jacobi(n, std::vector<double>(n, 0.0));
    for (int i = 0; i < n; ++i) jacobi[i][i] = 1.0 / A[i][i];
    test::DenseOperator preconditioner(jacobi);
    qp::MpgpSettings settings;
    settings.preconditioner = &preconditioner;
    qp::Vector bv(map), x(map), g(map);
    test::scatter(b, bv);
    const double tol = 1e-12 * test::norm2(b);
    const auto c = qp::Mpgp(settings).solve(op, bv, omega, 1.01 * qp::powerMethod(op, *map, 200, 1e-12, nullptr), x,
                                            g, [&](double gp, const qp::Vector&) { return gp <= tol; });
    EXPECT_TRUE(c.converged);
    EXPECT_LE(test::maxDifference(test::gather(x), exact), 1e-8) << "seed " << seed;
    // Bounds only (no tangent CG, A positive definite): every step of the CG branch is a CG or
    // an expansion step and takes exactly one direction; the proportioning steps take none.
    EXPECT_EQ(c.preconditionerApplications, c.cgSteps + c.expansionSteps) << "seed " << seed;
    EXPECT_EQ(preconditioner.applications, c.preconditionerApplications);
    proportioning += static_cast<int>(c.proportioningSteps);
  }
  EXPECT_GT(proportioning, 10);  // the saving was exercised
}

TEST(Mpgp, aGivenGradientIsKeptOnlyWhereTheProjectionLeavesTheIterate) {
  // SMALSE-M's next outer iteration passes g = A x - b for its x (gradientGiven): no product
  // when x is feasible, a fresh gradient when the projection moves x (the slip bound shrank).
  const int n = 12;
  const Dense A = test::randomSpd(n, 100.0, 7);
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> b(n);
  for (double& v : b) v = u(gen);
  test::BlockSet blocks;
  for (int i = 0; i < n; i += 2) {
    blocks.boundIndex.push_back(i);
    blocks.lower.push_back(0.1 * u(gen));
  }
  auto map = test::makeMap(n, test::selfComm());
  const auto omega = blocks.build(*map);
  test::DenseOperator op(A);
  qp::Vector bv(map), x(map), g(map);
  test::scatter(b, bv);
  const double normA = 1.01 * qp::powerMethod(op, *map, 200, 1e-12, nullptr);
  const double tol = 1e-12 * test::norm2(b);
  auto stop = [&](double gp, const qp::Vector&) { return gp <= tol; };
  ASSERT_TRUE(qp::Mpgp().solve(op, bv, omega, normA, x, g, stop).converged);
  // Solved, feasible, g current: converged at the start without a product.
  const auto kept = qp::Mpgp().solve(op, bv, omega, normA, x, g, stop, true);
  EXPECT_TRUE(kept.converged);
  EXPECT_EQ(kept.operatorApplications, 0);
  EXPECT_EQ(qp::Mpgp().solve(op, bv, omega, normA, x, g, stop).operatorApplications, 1);
  // Moved below a bound with g left as it was: the projection moves x back, so the gradient
  // is computed again and the solve still ends at the solution with g = A x - b.
  const auto solution = test::gather(x);
  auto moved = solution;
  moved[0] = blocks.lower[0] - 1.0;
  test::scatter(moved, x);
  const auto again = qp::Mpgp().solve(op, bv, omega, normA, x, g, stop, true);
  EXPECT_TRUE(again.converged);
  EXPECT_GE(again.operatorApplications, 1);
  EXPECT_LE(test::maxDifference(test::gather(x), solution), 1e-10);
  auto r = test::matVec(A, test::gather(x));
  for (int i = 0; i < n; ++i) r[i] -= b[i];
  EXPECT_LE(test::maxDifference(test::gather(g), r), 1e-12);
}

namespace {
struct MixedRun {
  test::KktResult kkt;
  double admmDifference;
  qp::MpgpCounters counters;
};

MixedRun solveMixed(unsigned seed, double condition, double maxRatio, const qp::MpgpSettings& settings) {
  std::mt19937 gen(seed);
  std::uniform_int_distribution<int> size(6, 30);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int n = size(gen);
  const Dense A = test::randomSpd(n, condition, seed + 1000);
  std::vector<double> b(n);
  for (double& v : b) v = 3.0 * u(gen);
  const auto blocks = test::randomBlocks(n, gen, {1, 2, 1, 1, 0.5, 0.3}, maxRatio);
  auto map = test::makeMap(n, test::selfComm());
  const auto omega = blocks.build(*map);
  test::DenseOperator op(A);
  qp::Vector bv(map), x(map), g(map);
  test::scatter(b, bv);
  const double tol = 1e-12 * test::norm2(b);
  MixedRun run;
  run.counters = qp::Mpgp(settings).solve(op, bv, omega, condition * 1.01, x, g,
                                          [&](double gp, const qp::Vector&) { return gp <= tol; });
  EXPECT_EQ(run.counters.operatorApplications, op.applications);
  EXPECT_EQ(run.counters.iterations,
            run.counters.cgSteps + run.counters.expansionSteps + run.counters.proportioningSteps);
  EXPECT_TRUE(run.counters.converged) << "seed " << seed;
  EXPECT_TRUE(omega.contains(x, 1e-12));
  const auto xs = test::gather(x);
  run.kkt = test::checkKkt(A, b, xs, blocks);
  run.kkt.stationarity /= test::norm2(b);
  run.kkt.sign /= test::norm2(b);
  run.admmDifference = test::maxDifference(xs, test::admm(A, b, blocks, {}, std::sqrt(condition))) /
                       std::max(1.0, test::normInf(xs));
  return run;
}
}  // namespace

TEST(Mpgp, solvesBoundAndEllipseConstrainedQpsToKktAccuracy) {
  long long total = 0;
  int iterations = 0;
  for (unsigned seed = 1; seed <= 24; ++seed) {
    const double condition = seed % 3 == 0 ? 1000.0 : seed % 3 == 1 ? 10.0 : 100.0;
    const auto run = solveMixed(seed, condition, 100.0, {});
    EXPECT_LE(run.kkt.stationarity, 1e-9) << "seed " << seed;
    EXPECT_LE(run.kkt.sign, 1e-9) << "seed " << seed;
    EXPECT_LE(run.kkt.infeasibility, 1e-12) << "seed " << seed;
    EXPECT_LE(run.admmDifference, 1e-8) << "seed " << seed;
    total += run.counters.operatorApplications;
    iterations += run.counters.iterations;
  }
  RecordProperty("operator_applications", static_cast<int>(total));
  RecordProperty("iterations", iterations);
}

TEST(Mpgp, optimalExpansionAndFlatEllipsesReachTheSameSolution) {
  qp::MpgpSettings settings;
  settings.optimalExpansion = true;
  for (unsigned seed = 31; seed <= 40; ++seed) {
    const auto run = solveMixed(seed, 100.0, 1e4, settings);
    EXPECT_LE(run.kkt.stationarity, 1e-9) << "seed " << seed;
    EXPECT_LE(run.kkt.sign, 1e-9) << "seed " << seed;
    EXPECT_LE(run.admmDifference, 1e-8) << "seed " << seed;
  }
}

TEST(Mpgp, stopsAtTheStartOrWhenIterationsRunOut) {
  const int n = 10;
  const Dense A = test::randomSpd(n, 100.0, 77);
  std::mt19937 gen(77);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> b(n);
  for (double& v : b) v = 3.0 * u(gen);
  const auto blocks = test::randomBlocks(n, gen);
  auto map = test::makeMap(n, test::selfComm());
  const auto omega = blocks.build(*map);
  test::DenseOperator op(A);
  qp::Vector bv(map), x(map), g(map);
  test::scatter(b, bv);
  qp::MpgpSettings few;
  few.maxIterations = 3;
  auto c = qp::Mpgp(few).solve(op, bv, omega, 101.0, x, g, [](double gp, const qp::Vector&) { return gp <= 0.0; });
  EXPECT_FALSE(c.converged);
  EXPECT_EQ(c.iterations, 3);
  EXPECT_GT(c.projectedGradientNorm, 0.0);
  // Solve, then solve again from the solution: the stop test holds at the start.
  c = qp::Mpgp().solve(op, bv, omega, 101.0, x, g, [](double gp, const qp::Vector&) { return gp <= 1e-12; });
  ASSERT_TRUE(c.converged);
  const long long before = op.applications;
  int calls = 0;
  c = qp::Mpgp().solve(op, bv, omega, 101.0, x, g, [&](double gp, const qp::Vector&) {
    ++calls;
    return gp <= 1e-12;
  });
  EXPECT_TRUE(c.converged);
  EXPECT_EQ(c.iterations, 0);
  EXPECT_EQ(calls, 1);
  EXPECT_EQ(c.operatorApplications, 1);  // the gradient at the start
  EXPECT_EQ(op.applications - before, 1);
}

TEST(Mpgp, progressIsCalledEveryKIterationsWithTheCountersSoFar) {
  const int n = 10;
  const Dense A = test::randomSpd(n, 1000.0, 78);
  std::mt19937 gen(78);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> b(n);
  for (double& v : b) v = 3.0 * u(gen);
  const auto blocks = test::randomBlocks(n, gen);
  auto map = test::makeMap(n, test::selfComm());
  const auto omega = blocks.build(*map);
  test::DenseOperator op(A);
  qp::Vector bv(map), x(map), g(map);
  test::scatter(b, bv);
  qp::MpgpSettings settings;
  settings.progressEvery = 3;
  std::vector<qp::MpgpCounters> seen;
  settings.progress = [&](const qp::MpgpCounters& c) { seen.push_back(c); };
  const long long before = op.applications;
  double lastGp = 0.0;
  const auto c = qp::Mpgp(settings).solve(op, bv, omega, 1001.0, x, g, [&](double gp, const qp::Vector&) {
    lastGp = gp;
    return gp <= 1e-12;
  });
  ASSERT_TRUE(c.converged);
  ASSERT_GE(c.iterations, 6) << "the test needs a few calls";
  // After iterations 3, 6, ... that did not end the solve; the counters are those so far.
  EXPECT_EQ(static_cast<int>(seen.size()), (c.iterations - 1) / 3);
  for (size_t k = 0; k < seen.size(); ++k) {
    EXPECT_EQ(seen[k].iterations, 3 * static_cast<int>(k + 1));
    EXPECT_EQ(seen[k].iterations, seen[k].cgSteps + seen[k].expansionSteps + seen[k].proportioningSteps);
    EXPECT_GT(seen[k].projectedGradientNorm, 1e-12);
    if (k > 0) EXPECT_GT(seen[k].operatorApplications, seen[k - 1].operatorApplications);
    EXPECT_LE(seen[k].operatorApplications, op.applications - before);
  }
  // Without a callback the iterates are the same (the callback only reads).
  qp::Vector x2(map), g2(map);
  const auto c2 = qp::Mpgp().solve(op, bv, omega, 1001.0, x2, g2, [](double gp, const qp::Vector&) {
    return gp <= 1e-12;
  });
  EXPECT_EQ(c2.iterations, c.iterations);
  EXPECT_EQ(test::maxDifference(test::gather(x2), test::gather(x)), 0.0);
}

// Tangent CG from the start (active ellipses move along their tangent in CG steps) and
// switched off reach the same solutions as the defaults, to KKT accuracy.
TEST(Mpgp, tangentCgReachesTheSameSolution) {
  for (const int after : {0, 10000000}) {
    qp::MpgpSettings settings;
    settings.tangentCgAfter = after;
    for (unsigned seed = 1; seed <= 24; ++seed) {
      const double condition = seed % 3 == 0 ? 1000.0 : seed % 3 == 1 ? 10.0 : 100.0;
      const auto run = solveMixed(seed, condition, 100.0, settings);
      EXPECT_LE(run.kkt.stationarity, 1e-9) << "seed " << seed << " after " << after;
      EXPECT_LE(run.kkt.sign, 1e-9) << "seed " << seed << " after " << after;
      EXPECT_LE(run.admmDifference, 1e-8) << "seed " << seed << " after " << after;
    }
  }
}
