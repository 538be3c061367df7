// qp::SmalseM (paper Section 5, ALGORITHMS.md 4) on small QPs in the T-FETI shape
// (A = P M P, c = P b, Q = G^T (G G^T)^{-1} G formed densely) with bounds, ellipses and an
// equality G x = 0 (G random 2 x n): against the exact enumeration (bounds only), the KKT
// conditions with least-squares multipliers and an ADMM reference (bounds + ellipses), and
// with a hook that moves the semi-axes (the Coulomb slip bound g := x_normal).
#include <gtest/gtest.h>

#include <Teuchos_ParameterList.hpp>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include "DenseQp.hpp"
#include "tribos/core/Errors.hpp"
#include "tribos/qp/Mpgp.hpp"
#include "tribos/qp/SmalseM.hpp"

using namespace tribos;
using test::Dense;

namespace {
/// Random 2 x n rows with G x0 = 0 for a given x0 (so that Omega meets Ker G).
Dense randomRowsVanishingAt(const std::vector<double>& x0, std::mt19937& gen) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const size_t n = x0.size();
  Dense G(2, std::vector<double>(n));
  const double xx = test::norm2(x0) * test::norm2(x0);
  for (auto& row : G) {
    for (double& v : row) v = u(gen);
    if (xx == 0.0) continue;
    double d = 0.0;
    for (size_t i = 0; i < n; ++i) d += row[i] * x0[i];
    for (size_t i = 0; i < n; ++i) row[i] -= d / xx * x0[i];
  }
  return G;
}

/// A random QP of 6-9 unknowns with lower bounds on about 30 % of them and 2 equality rows
/// vanishing at the projection of 0 onto the bounds, and its exact solution by enumeration.
struct BoundedQp {
  test::EqualityQp qp;
  test::BlockSet blocks;
  std::vector<double> exact;
};
BoundedQp boundedQpWithEquality(unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int n = 6 + seed % 4;
  const Dense M = test::randomSpd(n, 30.0, seed + 200);
  std::vector<double> b(n);
  for (double& v : b) v = u(gen);
  test::BlockSet blocks;
  for (int i = 0; i < n; ++i)
    if (u(gen) < 0.3) {
      blocks.boundIndex.push_back(i);
      blocks.lower.push_back(0.2 * u(gen));
    }
  std::vector<double> x0(n, 0.0);
  blocks.project(x0);
  auto qp = test::makeEqualityQp(M, randomRowsVanishingAt(x0, gen), b);
  auto exact = test::enumerateActiveSets(M, b, blocks.boundIndex, blocks.lower, qp.G);
  return {std::move(qp), std::move(blocks), std::move(exact)};
}

qp::SmalseSettings paperSettings() {
  qp::SmalseSettings s;  // the paper's: rho = ||A||, M0 = 1e-6 ||A||, beta_M = 0.1, eta = ||c||
  s.tolerance = 1e-10;
  s.normEstimateSteps = 100;
  s.rho = 1.0;
  s.M0 = 1e-6;
  s.betaM = 0.1;
  s.eta = 1.0;
  s.mpgp.maxIterations = 10000;
  return s;
}
qp::SmalseSettings tunedSettings() {
  qp::SmalseSettings s = paperSettings();  // the solver stack's defaults (SmalseSettings{})
  s.rho = 10.0;
  s.M0 = 1.0;
  s.betaM = 0.5;
  return s;
}

struct Run {
  qp::SmalseCounters counters;
  std::vector<double> x;
  int hookCalls = 0;
};

Run runSmalse(const test::EqualityQp& qp, const test::BlockSet& blocks, const qp::SmalseSettings& settings) {
  const int n = static_cast<int>(qp.b.size());
  auto map = test::makeMap(n, test::selfComm());
  auto omega = blocks.build(*map);
  test::DenseOperator op(qp.A);
  test::DenseProjector projector(qp.Q);
  qp::Vector cv(map), mu(map);
  test::scatter(qp.c, cv);
  Run run;
  run.counters = qp::SmalseM(settings).solve(op, projector, cv, omega, mu,
                                             [&](int k, const qp::Vector&, double, double, double) {
                                               EXPECT_EQ(k, run.hookCalls);
                                               ++run.hookCalls;
                                               return false;
                                             });
  EXPECT_EQ(run.counters.operatorApplications, op.applications);
  EXPECT_EQ(run.counters.innerIterations,
            run.counters.cgSteps + run.counters.expansionSteps + run.counters.proportioningSteps);
  EXPECT_EQ(run.hookCalls, run.counters.outerIterations);
  EXPECT_TRUE(run.counters.converged);
  EXPECT_LE(run.counters.projectedGradient, settings.tolerance);
  run.x = test::gather(mu);
  return run;
}
}  // namespace

TEST(SmalseM, matchesEnumerationWithAnEqualityConstraint) {
  for (unsigned seed = 1; seed <= 16; ++seed) {
    // On Ker G, 1/2 x^T P M P x - c^T x = 1/2 x^T M x - b^T x: enumerated with the equality.
    const auto [qp, blocks, exact] = boundedQpWithEquality(seed);
    ASSERT_EQ(exact.size(), qp.b.size());
    const auto run = runSmalse(qp, blocks, seed % 2 ? paperSettings() : tunedSettings());
    EXPECT_LE(test::maxDifference(run.x, exact), 1e-8) << "seed " << seed;
  }
}

namespace {
/// Outer iterations summed over 16 seeds of boundedQpWithEquality with `settings`; every
/// solution must be the enumeration's.
int outerIterationsOverSeeds(const qp::SmalseSettings& settings) {
  int outer = 0;
  for (unsigned seed = 1; seed <= 16; ++seed) {
    const auto [qp, blocks, exact] = boundedQpWithEquality(seed);
    const auto run = runSmalse(qp, blocks, settings);
    EXPECT_LE(test::maxDifference(run.x, exact), 1e-8) << "seed " << seed;
    outer += run.counters.outerIterations;
  }
  return outer;
}

/// A small rho, whose outer iterations contract ||G mu|| slowly, and the paper's multiplier step.
qp::SmalseSettings slowRhoSettings() {
  qp::SmalseSettings s = tunedSettings();
  s.rho = 0.2;
  s.rhoGrowth = 1.0;  // the small rho kept fixed unless a test asks for its growth
  s.maxOuterIterations = 2000;
  s.multiplierStep = qp::MultiplierStep::Fixed;
  return s;
}
}  // namespace

// rho update "Model" (SmalseM.cpp, rhoFactor): from the small rho, rho grows to the value the
// augmented-Lagrangian rate predicts for the target ratio. The solutions stay exact and the
// outer iterations, summed over the seeds, must be fewer than with the small rho kept fixed.
TEST(SmalseM, modelRhoUpdateKeepsTheSolutionAndNeedsFewerOuterIterations) {
  qp::SmalseSettings model = slowRhoSettings();
  model.rhoUpdate = qp::RhoUpdate::Model;
  model.rhoGrowth = 8.0;
  model.rhoTargetRatio = 0.25;
  const int fixedOuter = outerIterationsOverSeeds(slowRhoSettings()), modelOuter = outerIterationsOverSeeds(model);
  EXPECT_LT(modelOuter, fixedOuter);
  std::printf("outer iterations over 16 seeds: rho 0.2 fixed %d, Model update %d\n", fixedOuter, modelOuter);
}

// rho growth after patience (the default: growth 2 after 10 slow outer iterations in a row):
// from the small rho, whose ||G mu|| falls slowly, rho grows and the solves need fewer outer
// iterations over the seeds; with a patience longer than any solve, rho stays fixed and the
// counts are those of rho growth 1 exactly.
TEST(SmalseM, rhoGrowsOnlyAfterItsPatience) {
  qp::SmalseSettings patient = slowRhoSettings();
  patient.rhoGrowth = 2.0;
  patient.rhoGrowthPatience = 10;
  qp::SmalseSettings never = patient;
  never.rhoGrowthPatience = 1000000;
  const int fixedOuter = outerIterationsOverSeeds(slowRhoSettings());
  const int patientOuter = outerIterationsOverSeeds(patient), neverOuter = outerIterationsOverSeeds(never);
  EXPECT_EQ(neverOuter, fixedOuter);
  EXPECT_LT(patientOuter, fixedOuter);
  std::printf("outer iterations over 16 seeds: rho 0.2 fixed %d, growth 2 after 10 slow %d\n", fixedOuter,
              patientOuter);
}

// multiplier step "Relaxed" (MultiplierRelaxation.hpp): at the small rho the over-relaxed step
// beta += omega rho G mu keeps every solution exact and needs fewer outer iterations, summed
// over the seeds, than the paper's step ("Fixed").
TEST(SmalseM, relaxedMultiplierStepKeepsTheSolutionAndNeedsFewerOuterIterations) {
  qp::SmalseSettings relaxed = slowRhoSettings();
  relaxed.multiplierStep = qp::MultiplierStep::Relaxed;
  const int fixedOuter = outerIterationsOverSeeds(slowRhoSettings()), relaxedOuter = outerIterationsOverSeeds(relaxed);
  EXPECT_LT(relaxedOuter, 0.9 * fixedOuter);  // measured 418 against 494: omega <= 5/3 where r0 > 0.8
  std::printf("outer iterations over 16 seeds: rho 0.2, Fixed step %d, Relaxed step %d\n", fixedOuter, relaxedOuter);
}

// A known ||A|| (SmalseM::solve's knownNormA, from an earlier solve with the same A: the exact
// Coulomb fixed point) replaces the Lanczos estimate: the same bits of the solution, and exactly
// the estimate's products fewer.
TEST(SmalseM, aKnownNormGivesTheSameSolutionWithoutTheEstimatesProducts) {
  for (unsigned seed = 1; seed <= 8; ++seed) {
    const auto [qp, blocks, exact] = boundedQpWithEquality(seed);
    const int n = static_cast<int>(qp.b.size());
    auto map = test::makeMap(n, test::selfComm());
    test::DenseOperator op(qp.A);
    test::DenseProjector projector(qp.Q);
    qp::Vector cv(map);
    test::scatter(qp.c, cv);
    const qp::SmalseM smalse(tunedSettings());
    auto solve = [&](double knownNormA, long long& products, qp::SmalseCounters& counters) {
      auto omega = blocks.build(*map);
      qp::Vector mu(map);
      const long long before = op.applications;
      counters = smalse.solve(op, projector, cv, omega, mu, nullptr, knownNormA);
      products = op.applications - before;
      return test::gather(mu);
    };
    long long estimated = 0, known = 0;
    qp::SmalseCounters first, second;
    const auto x1 = solve(0.0, estimated, first);
    const auto x2 = solve(first.normA, known, second);
    EXPECT_TRUE(first.converged && second.converged);
    EXPECT_EQ(x1, x2) << "seed " << seed;  // bit for bit
    EXPECT_EQ(second.normA, first.normA);
    long long lanczos = 0;
    qp::lanczosNorm(op, *map, tunedSettings().normEstimateSteps, qp::normEstimateToleranceFor(tunedSettings()), &lanczos);
    EXPECT_GT(lanczos, 0);
    EXPECT_EQ(estimated - known, lanczos) << "seed " << seed;
    EXPECT_EQ(second.operatorApplications, known);
    EXPECT_LE(test::maxDifference(x2, exact), 1e-8) << "seed " << seed;
  }
}

TEST(SmalseM, theNormEstimateIsLooseOnlyWhereRhoBoundsTheStep) {
  // From rho = 2 on, ||A_rho|| = rho ||A||_est for any estimate above ||A|| / 2, so the Lanczos
  // stop may be loose; below, alpha_bar rests on ||A|| itself and the stop is at most 1e-4.
  qp::SmalseSettings s;
  s.normEstimateTolerance = 1e-3;
  s.rho = 10.0;
  EXPECT_EQ(qp::normEstimateToleranceFor(s), 1e-3);
  s.rho = 2.0;
  EXPECT_EQ(qp::normEstimateToleranceFor(s), 1e-3);
  s.rho = 1.0;  // the paper's
  EXPECT_EQ(qp::normEstimateToleranceFor(s), 1e-4);
  s.normEstimateTolerance = 1e-6;
  EXPECT_EQ(qp::normEstimateToleranceFor(s), 1e-6);
  EXPECT_EQ(qp::SmalseSettings{}.normEstimateTolerance, 1e-3);
}

TEST(SmalseM, satisfiesKktAndMatchesAdmmWithBoundsEllipsesAndEquality) {
  long long applications = 0;
  int outer = 0;
  for (unsigned seed = 1; seed <= 16; ++seed) {
    std::mt19937 gen(seed + 50);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::uniform_int_distribution<int> size(10, 24);
    const int n = size(gen);
    const double condition = seed % 2 ? 30.0 : 300.0;
    const Dense M = test::randomSpd(n, condition, seed + 300);
    std::vector<double> b(n);
    for (double& v : b) v = 3.0 * u(gen);
    const auto blocks = test::randomBlocks(n, gen, {1.5, 2, 1, 1, 0.3, 0.15}, 30.0);
    std::vector<double> x0(n);
    for (double& v : x0) v = u(gen);
    blocks.project(x0);
    const auto qp = test::makeEqualityQp(M, randomRowsVanishingAt(x0, gen), b);
    auto settings = seed % 4 < 2 ? paperSettings() : tunedSettings();
    // The Paper test ||Q mu|| <= eps M0 ||mu|| needs eps M0 above round-off: with M0 = 1.
    if (seed % 3 == 0) {
      settings = tunedSettings();
      settings.equalityTest = qp::EqualityTest::Paper;
    }
    const auto run = runSmalse(qp, blocks, settings);
    const double scale = test::norm2(qp.c);
    const auto kkt = test::checkKkt(qp.A, qp.c, run.x, blocks, qp.G);
    EXPECT_LE(kkt.stationarity, 1e-8 * scale) << "seed " << seed;
    EXPECT_LE(kkt.sign, 1e-8 * scale) << "seed " << seed;
    EXPECT_LE(kkt.infeasibility, 1e-12) << "seed " << seed;
    EXPECT_LE(kkt.equality, 1e-8) << "seed " << seed;
    const auto reference = test::admm(M, b, blocks, qp.G, std::sqrt(condition));
    EXPECT_LE(test::maxDifference(run.x, reference), 1e-8 * std::max(1.0, test::normInf(reference))) << "seed " << seed;
    applications += run.counters.operatorApplications;
    outer += run.counters.outerIterations;
  }
  RecordProperty("operator_applications", static_cast<int>(applications));
  RecordProperty("outer_iterations", outer);
}

TEST(SmalseM, hookMovingTheSemiAxesConvergesToAFixedPoint) {
  // Contact nodes (normal, t1, t2): x_nu >= l, and the tangential pair in the ellipse with
  // semi-axes F_j (x_nu - l) about c (the Coulomb slip bound g := lambda_nu, paper (20)),
  // plus free entries. The hook updates the semi-axes after every outer iteration and vetoes
  // convergence while they move; it starts from g = 0 (points: degenerate ellipses).
  const std::array<double, 2> F{0.3, 0.15};
  int vetoes = 0, slipping = 0, pressed = 0;
  for (unsigned seed = 1; seed <= 8; ++seed) {
    std::mt19937 gen(seed + 900);
    std::uniform_real_distribution<double> u(-1.0, 1.0), unit(0.0, 1.0);
    const int nodes = 3, nFree = 4, n = 3 * nodes + nFree;
    const Dense M = test::randomSpd(n, 50.0, seed + 400);
    test::BlockSet blocks;
    std::vector<double> b(n), x0(n, 0.0);
    for (int k = 0; k < nodes; ++k) {
      const int i = 3 * k;
      blocks.boundIndex.push_back(i);
      blocks.lower.push_back(-0.2 * unit(gen));
      blocks.ellipses.push_back({i + 1, i + 2, {0.1 * u(gen), 0.1 * u(gen)}, {0.0, 0.0}});
      b[i] = 20.0 + 5.0 * unit(gen);  // pressed: x_nu > l
      b[i + 1] = 8.0 * u(gen);        // pulled tangentially: slip
      b[i + 2] = 8.0 * u(gen);
      x0[i] = blocks.lower.back();
      x0[i + 1] = blocks.ellipses.back().c[0];
      x0[i + 2] = blocks.ellipses.back().c[1];
    }
    for (int i = 3 * nodes; i < n; ++i) b[i] = u(gen);
    const auto qp = test::makeEqualityQp(M, randomRowsVanishingAt(x0, gen), b);

    auto map = test::makeMap(n, test::selfComm());
    auto omega = blocks.build(*map);
    test::DenseOperator op(qp.A);
    test::DenseProjector projector(qp.Q);
    qp::Vector cv(map), mu(map);
    test::scatter(qp.c, cv);
    int calls = 0;
    auto hook = [&](int, const qp::Vector& current, double, double, double) {
      ++calls;
      const auto x = test::gather(current);
      double change = 0.0, size = 0.0;
      for (int k = 0; k < nodes; ++k) {
        const double g = std::max(x[3 * k] - blocks.lower[k], 0.0);
        const std::array<double, 2> a{F[0] * g, F[1] * g};
        change = std::max(change, std::abs(a[0] - blocks.ellipses[k].a[0]) / F[0]);
        size = std::max(size, g);
        blocks.ellipses[k].a = a;
        omega.setSemiAxes(k, a);
      }
      const bool moved = change > 1e-10 * size;
      vetoes += moved;
      return moved;
    };
    const auto settings = seed % 2 ? paperSettings() : tunedSettings();
    const auto counters = qp::SmalseM(settings).solve(op, projector, cv, omega, mu, hook);
    ASSERT_TRUE(counters.converged) << "seed " << seed;
    EXPECT_EQ(calls, counters.outerIterations);
    EXPECT_EQ(counters.operatorApplications, op.applications);
    EXPECT_EQ(counters.innerIterations, counters.cgSteps + counters.expansionSteps + counters.proportioningSteps);
    const auto x = test::gather(mu);
    // A fixed point: the semi-axes are F (x_nu - l) of the solution, and x solves the
    // problem with those semi-axes (KKT and ADMM).
    for (int k = 0; k < nodes; ++k) {
      const double g = x[3 * k] - blocks.lower[k];
      pressed += g > 0.0;
      EXPECT_NEAR(blocks.ellipses[k].a[0], F[0] * g, 1e-9 * std::abs(g));
      const auto& e = blocks.ellipses[k];
      slipping += std::hypot((x[e.i] - e.c[0]) / e.a[0], (x[e.j] - e.c[1]) / e.a[1]) > 1.0 - 1e-10;
    }
    const double scale = test::norm2(qp.c);
    // x solved the problem with the semi-axes before the last update, which moved them by
    // up to 1e-10 max g (the fixed-point test), i.e. relatively more on lightly pressed
    // nodes: activity and feasibility are judged at that level.
    const auto kkt = test::checkKkt(qp.A, qp.c, x, blocks, qp.G, 1e-6);
    EXPECT_LE(kkt.stationarity, 1e-8 * scale) << "seed " << seed;
    EXPECT_LE(kkt.sign, 1e-8 * scale) << "seed " << seed;
    EXPECT_LE(kkt.infeasibility, 1e-9) << "seed " << seed;
    EXPECT_LE(kkt.equality, 1e-8) << "seed " << seed;
    const auto reference = test::admm(M, b, blocks, qp.G, std::sqrt(50.0));
    EXPECT_LE(test::maxDifference(x, reference), 1e-8 * std::max(1.0, test::normInf(reference))) << "seed " << seed;
  }
  EXPECT_GT(vetoes, 8);    // the hook did hold convergence back
  EXPECT_GT(slipping, 4);  // and the friction constraints matter
  EXPECT_GT(pressed, 16);
}

TEST(SmalseM, monitorsSeeEveryOuterIterationAndTheInnerProgressInBetween) {
  // The monitor once per outer iteration, after the hook (it sees what the hook did); the
  // inner monitor every mpgp.progressEvery MPGP iterations, within the outer iteration in
  // progress, with the products with A counted over the whole solve.
  std::mt19937 gen(31);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int n = 12;
  const Dense M = test::randomSpd(n, 300.0, 31);
  std::vector<double> b(n);
  for (double& v : b) v = u(gen);
  test::BlockSet blocks;
  for (int i = 0; i < n; i += 2) {
    blocks.boundIndex.push_back(i);
    blocks.lower.push_back(0.1 * u(gen));
  }
  std::vector<double> x0(n, 0.0);
  blocks.project(x0);
  const auto qp = test::makeEqualityQp(M, randomRowsVanishingAt(x0, gen), b);
  auto settings = paperSettings();
  settings.mpgp.progressEvery = 2;
  std::vector<qp::SmalseProgress> outer, inner;
  int hookCalls = 0;
  settings.monitor = [&](const qp::SmalseProgress& p) {
    EXPECT_EQ(hookCalls, p.outerIteration);  // the hook of this iteration has run
    outer.push_back(p);
  };
  settings.innerMonitor = [&](const qp::SmalseProgress& p) { inner.push_back(p); };
  auto map = test::makeMap(n, test::selfComm());
  auto omega = blocks.build(*map);
  test::DenseOperator op(qp.A);
  test::DenseProjector projector(qp.Q);
  qp::Vector cv(map), mu(map);
  test::scatter(qp.c, cv);
  const auto counters = qp::SmalseM(settings).solve(op, projector, cv, omega, mu,
                                                    [&](int, const qp::Vector&, double, double, double) {
                                                      ++hookCalls;
                                                      return false;
                                                    });
  ASSERT_TRUE(counters.converged);
  ASSERT_EQ(static_cast<int>(outer.size()), counters.outerIterations);
  for (size_t k = 0; k < outer.size(); ++k) EXPECT_EQ(outer[k].outerIteration, static_cast<int>(k + 1));
  EXPECT_EQ(outer.back().operatorApplications, counters.operatorApplications);
  ASSERT_FALSE(inner.empty()) << "no inner solve took more than 2 MPGP iterations";
  for (const auto& p : inner) {
    ASSERT_GE(p.outerIteration, 1);
    ASSERT_LE(p.outerIteration, counters.outerIterations);
    const auto& done = outer[p.outerIteration - 1];
    EXPECT_EQ(p.innerIterations % 2, 0);
    EXPECT_LT(p.innerIterations, done.innerIterations);
    EXPECT_LT(p.operatorApplications, done.operatorApplications);
    EXPECT_GT(p.projectedGradient, 0.0);
    EXPECT_GT(p.innerTarget, 0.0);
    if (p.outerIteration > 1) EXPECT_GT(p.operatorApplications, outer[p.outerIteration - 2].operatorApplications);
  }
}

TEST(SmalseM, aStopRequestEndsTheSolveAtOnceNotConverged) {
  // The budget hook (stopRequested): once it answers true, the inner solve in progress ends
  // and so does the outer loop, not converged; a request that never fires changes nothing.
  std::mt19937 gen(31);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int n = 12;
  const Dense M = test::randomSpd(n, 300.0, 31);
  std::vector<double> b(n);
  for (double& v : b) v = u(gen);
  test::BlockSet blocks;
  for (int i = 0; i < n; i += 2) {
    blocks.boundIndex.push_back(i);
    blocks.lower.push_back(0.1 * u(gen));
  }
  std::vector<double> x0(n, 0.0);
  blocks.project(x0);
  const auto qp = test::makeEqualityQp(M, randomRowsVanishingAt(x0, gen), b);
  auto solve = [&](int fireAfter, int& asked) {
    auto settings = paperSettings();
    settings.stopRequested = [&asked, fireAfter] { return ++asked > fireAfter; };
    auto map = test::makeMap(n, test::selfComm());
    auto omega = blocks.build(*map);
    test::DenseOperator op(qp.A);
    test::DenseProjector projector(qp.Q);
    qp::Vector cv(map), mu(map);
    test::scatter(qp.c, cv);
    return qp::SmalseM(settings).solve(op, projector, cv, omega, mu);
  };
  int asked = 0;
  const auto free = solve(1 << 30, asked);
  ASSERT_TRUE(free.converged);
  ASSERT_GT(free.innerIterations, 6);
  asked = 0;
  const auto stopped = solve(5, asked);
  EXPECT_FALSE(stopped.converged);
  EXPECT_EQ(stopped.outerIterations, 1);
  EXPECT_LE(stopped.innerIterations, 5);
}

TEST(SmalseM, zeroRightHandSide) {
  const int n = 6;
  const Dense M = test::randomSpd(n, 10.0, 5);
  std::mt19937 gen(5);
  test::BlockSet blocks;
  blocks.boundIndex = {0, 3};
  blocks.lower = {-0.5, 0.25};  // 0 is not in Omega
  std::vector<double> x0(n, 0.0);
  blocks.project(x0);
  const auto qp = test::makeEqualityQp(M, randomRowsVanishingAt(x0, gen), std::vector<double>(n, 0.0));
  const auto run = runSmalse(qp, blocks, tunedSettings());
  const auto exact = test::enumerateActiveSets(M, qp.b, blocks.boundIndex, blocks.lower, qp.G);
  EXPECT_LE(test::maxDifference(run.x, exact), 1e-8);
  // With 0 in Omega the answer is 0 at once.
  blocks.lower = {-0.5, -0.25};
  const auto zero = runSmalse(qp, blocks, tunedSettings());
  EXPECT_EQ(test::normInf(zero.x), 0.0);
  EXPECT_EQ(zero.counters.outerIterations, 0);
}

TEST(SmalseM, parametersAreDocumentedAndValidated) {
  const auto valid = qp::SmalseM::getValidParameters();
  for (const char* name : {"SMALSE-M", "MPGP"}) {
    ASSERT_TRUE(valid->isSublist(name));
    const auto& sub = valid->sublist(name);
    for (auto it = sub.begin(); it != sub.end(); ++it)
      EXPECT_FALSE(sub.entry(it).docString().empty()) << name << "/" << sub.name(it);
  }
  // An empty list gives the defaults of SmalseSettings, which are the solver stack's.
  Teuchos::ParameterList empty;
  const auto defaults = qp::SmalseM::settingsFromParameters(empty);
  const qp::SmalseSettings reference;
  EXPECT_EQ(defaults.tolerance, reference.tolerance);
  EXPECT_EQ(defaults.maxOuterIterations, reference.maxOuterIterations);
  EXPECT_EQ(defaults.rho, reference.rho);
  EXPECT_EQ(defaults.M0, reference.M0);
  EXPECT_EQ(defaults.betaM, reference.betaM);
  EXPECT_EQ(defaults.equalityTest, reference.equalityTest);
  EXPECT_EQ(defaults.rhoTargetRatio, reference.rhoTargetRatio);
  EXPECT_EQ(defaults.innerFloor, reference.innerFloor);
  EXPECT_EQ(defaults.mpgp.stepScale, reference.mpgp.stepScale);
  EXPECT_EQ(defaults.mpgp.maxIterations, reference.mpgp.maxIterations);
  EXPECT_EQ(reference.rho, 10.0);
  EXPECT_EQ(reference.M0, 1.0);
  EXPECT_EQ(reference.betaM, 0.9);
  // Values are read, and out-of-range or unknown names are errors.
  Teuchos::ParameterList pl;
  pl.sublist("SMALSE-M").set("rho", 10.0);
  pl.sublist("SMALSE-M").set("equality test", "Paper");
  pl.sublist("MPGP").set("Gamma", 2.0);
  const auto s = qp::SmalseM::settingsFromParameters(pl);
  EXPECT_EQ(s.rho, 10.0);
  EXPECT_EQ(s.equalityTest, qp::EqualityTest::Paper);
  EXPECT_EQ(s.mpgp.gamma, 2.0);
  EXPECT_EQ(defaults.rhoUpdate, qp::RhoUpdate::Ratio);
  EXPECT_EQ(defaults.multiplierStep, qp::MultiplierStep::Relaxed);
  // The options: a valid name is read as its value, another is an input error.
  Teuchos::ParameterList model, fixed;
  model.sublist("SMALSE-M").set("rho update", "Model");
  fixed.sublist("SMALSE-M").set("multiplier step", "Fixed");
  EXPECT_EQ(qp::SmalseM::settingsFromParameters(model).rhoUpdate, qp::RhoUpdate::Model);
  EXPECT_EQ(qp::SmalseM::settingsFromParameters(fixed).multiplierStep, qp::MultiplierStep::Fixed);
  for (const auto& [name, invalid] : {std::pair<const char*, const char*>{"rho update", "Fast"},
                                      std::pair<const char*, const char*>{"multiplier step", "Doubled"}}) {
    Teuchos::ParameterList list;
    list.sublist("SMALSE-M").set(name, invalid);
    EXPECT_THROW(qp::SmalseM::settingsFromParameters(list), core::InputError) << name;
  }
  Teuchos::ParameterList bad;
  bad.sublist("SMALSE-M").set("beta", 1.0);
  EXPECT_THROW(qp::SmalseM::settingsFromParameters(bad), std::exception);
  Teuchos::ParameterList unknown;
  unknown.sublist("MPGP").set("step size", 1.0);
  EXPECT_THROW(qp::SmalseM::settingsFromParameters(unknown), std::exception);
  Teuchos::ParameterList step;
  step.sublist("MPGP").set("step scale", 2.0);
  EXPECT_THROW(qp::SmalseM::settingsFromParameters(step), core::InputError);
  // The open ends, NaN and Inf are refused too; an int is accepted for a real.
  const std::pair<const char*, double> refused[] = {{"rho", 0.0}, {"beta", 0.0}, {"beta", 15.0},
      {"eta", std::numeric_limits<double>::quiet_NaN()}, {"initial M", std::numeric_limits<double>::infinity()}};
  for (const auto& [name, value] : refused) {
    Teuchos::ParameterList pl2;
    pl2.sublist("SMALSE-M").set(name, value);
    EXPECT_THROW(qp::SmalseM::settingsFromParameters(pl2), core::InputError) << name << " = " << value;
  }
  Teuchos::ParameterList zeroTolerance;
  zeroTolerance.set("Tolerance", 0.0);
  EXPECT_THROW(qp::SmalseM::settingsFromParameters(zeroTolerance), core::InputError);
  Teuchos::ParameterList intForReal;
  intForReal.sublist("SMALSE-M").set("rho", 3);
  EXPECT_EQ(qp::SmalseM::settingsFromParameters(intForReal).rho, 3.0);
}

namespace {
/// A that turns every product into NaN from its `poisonFrom`-th application on: a fault in F
/// (a non-finite load, material or subdomain solve) as the dual iterations would see it.
class PoisonedOperator : public qp::SymmetricOperator {
 public:
  PoisonedOperator(test::Dense A, long long poisonFrom) : inner_(std::move(A)), poisonFrom_(poisonFrom) {}
  void apply(const qp::Vector& x, qp::Vector& y) const override {
    inner_.apply(x, y);
    if (inner_.applications >= poisonFrom_) y.putScalar(std::numeric_limits<double>::quiet_NaN());
  }
  long long applications() const { return inner_.applications; }

 private:
  test::DenseOperator inner_;
  long long poisonFrom_;
};
}  // namespace

TEST(SmalseM, nonFiniteOperatorStopsAtOnceAndNeverConverges) {
  // Without the check a NaN fails every comparison: MPGP ran to its iteration cap and SMALSE-M
  // to its outer cap. Poisoned at the start (the power method) and in the middle of the solve.
  const int n = 12;
  const auto M = test::randomSpd(n, 30.0, 11);
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> b(n);
  for (double& v : b) v = u(gen);
  test::BlockSet blocks;
  blocks.boundIndex = {0, 4, 7};
  blocks.lower = {0.0, -0.1, 0.05};
  std::vector<double> x0(n, 0.0);
  blocks.project(x0);
  const auto qp = test::makeEqualityQp(M, randomRowsVanishingAt(x0, gen), b);
  for (long long poisonFrom : {1LL, 60LL}) {
    SCOPED_TRACE(poisonFrom);
    auto map = test::makeMap(n, test::selfComm());
    auto omega = blocks.build(*map);
    PoisonedOperator op(qp.A, poisonFrom);
    test::DenseProjector projector(qp.Q);
    qp::Vector cv(map), mu(map);
    test::scatter(qp.c, cv);
    auto settings = tunedSettings();
    settings.mpgp.maxIterations = 100000;
    const auto counters = qp::SmalseM(settings).solve(op, projector, cv, omega, mu);
    EXPECT_TRUE(counters.nonFinite);
    EXPECT_FALSE(counters.converged);
    EXPECT_LE(op.applications(), poisonFrom + 2) << "iterations went on after the NaN";
  }
}

namespace {
/// A = P M P that adds s Q x from its own P x (qp::ProjectedOperator), counting the fused calls.
class FusedDenseOperator : public qp::ProjectedOperator {
 public:
  FusedDenseOperator(Dense A, Dense Q) : A_(std::move(A)), Q_(std::move(Q)) {}
  void apply(const qp::Vector& x, qp::Vector& y) const override {
    ++applications;
    test::scatter(test::matVec(A_, gather_(x)), y);
  }
  bool applyPlusComplement(const qp::Vector& x, qp::Vector& y, double s, qp::EqualityCoordinates*) const override {
    ++fused;
    const auto xs = gather_(x);
    auto ys = test::matVec(A_, xs);
    const auto qx = test::matVec(Q_, xs);  // x - P x
    for (size_t i = 0; i < ys.size(); ++i) ys[i] += s * qx[i];
    ++applications;
    test::scatter(ys, y);
    return false;
  }
  mutable long long applications = 0, fused = 0;

 private:
  Dense A_, Q_;
  test::Gatherer gather_;
};

/// Q with ||Q x||^2 = (G x)^T (G G^T)^{-1} G x (as the T-FETI projector computes it, without
/// a projected vector), for the two rows of G; counts its calls.
class NormDenseProjector : public test::DenseProjector {
 public:
  NormDenseProjector(const Dense& Q, const Dense& G) : test::DenseProjector(Q), G_(G) {}
  double normQ(const qp::Vector& x, qp::Vector&) const override {
    ++norms;
    const auto a = test::matVec(G_, gather_(x));
    double g[2][2] = {{0.0, 0.0}, {0.0, 0.0}};
    for (int r = 0; r < 2; ++r)
      for (int c = 0; c < 2; ++c)
        for (size_t i = 0; i < G_[r].size(); ++i) g[r][c] += G_[r][i] * G_[c][i];
    const double det = g[0][0] * g[1][1] - g[0][1] * g[1][0];
    const double y0 = (g[1][1] * a[0] - g[0][1] * a[1]) / det, y1 = (g[0][0] * a[1] - g[1][0] * a[0]) / det;
    return std::sqrt(std::max(a[0] * y0 + a[1] * y1, 0.0));
  }
  mutable long long norms = 0;

 private:
  Dense G_;
  test::Gatherer gather_;
};
}  // namespace

// The contact solver's products reuse P x for the rho Q term and take ||Q mu|| from G mu
// (ProjectedOperator, EqualityProjector::normQ): SMALSE-M must use them, with and without a
// preconditioner, and reach the solution of the separate products.
TEST(SmalseM, fusedPenaltyTermAndNormQGiveTheSameSolution) {
  for (unsigned seed = 1; seed <= 8; ++seed) {
    std::mt19937 gen(seed + 900);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const int n = 12 + seed % 5;
    const Dense M = test::randomSpd(n, 100.0, seed + 700);
    std::vector<double> b(n);
    for (double& v : b) v = 2.0 * u(gen);
    const auto blocks = test::randomBlocks(n, gen, {1.5, 2, 1, 1, 0.3, 0.15}, 30.0);
    std::vector<double> x0(n);
    for (double& v : x0) v = u(gen);
    blocks.project(x0);
    const auto qp = test::makeEqualityQp(M, randomRowsVanishingAt(x0, gen), b);
    // P D P with D = diag(M)^-1 as the preconditioner in face, plain and fused.
    Dense PDP(n, std::vector<double>(n, 0.0));
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        for (int k = 0; k < n; ++k) {
          const double pik = (i == k) - qp.Q[i][k], pkj = (k == j) - qp.Q[k][j];
          PDP[i][j] += pik * pkj / M[k][k];
        }
    for (const bool preconditioned : {false, true}) {
      auto settings = tunedSettings();
      test::DenseOperator plainPreconditioner(PDP);
      if (preconditioned) settings.preconditioner = &plainPreconditioner;
      const auto reference = runSmalse(qp, blocks, settings);

      auto map = test::makeMap(n, test::selfComm());
      auto omega = blocks.build(*map);
      FusedDenseOperator op(qp.A, qp.Q);
      FusedDenseOperator fusedPreconditioner(PDP, qp.Q);
      if (preconditioned) settings.preconditioner = &fusedPreconditioner;
      NormDenseProjector projector(qp.Q, qp.G);
      qp::Vector cv(map), mu(map);
      test::scatter(qp.c, cv);
      const auto counters = qp::SmalseM(settings).solve(op, projector, cv, omega, mu);
      EXPECT_TRUE(counters.converged) << "seed " << seed;
      EXPECT_EQ(counters.operatorApplications, op.applications);
      EXPECT_GT(op.fused, 0) << "seed " << seed;
      EXPECT_GT(projector.norms, 0) << "seed " << seed;
      if (preconditioned) EXPECT_EQ(fusedPreconditioner.fused, counters.preconditionerApplications);
      // The time split of the summary (times.products_s, preconditioning_s): each part timed,
      // within the operators' time, within the whole.
      EXPECT_GT(counters.productSeconds, 0.0);
      if (preconditioned)
        EXPECT_GT(counters.preconditionerSeconds, 0.0);
      else
        EXPECT_EQ(counters.preconditionerSeconds, 0.0);
      EXPECT_LE(counters.productSeconds + counters.preconditionerSeconds, counters.operatorSeconds);
      EXPECT_LE(counters.operatorSeconds, counters.seconds);
      const auto x = test::gather(mu);
      EXPECT_LE(test::maxDifference(x, reference.x), 1e-8 * std::max(1.0, test::normInf(reference.x)))
          << "seed " << seed << (preconditioned ? " preconditioned" : "");
    }
  }
}

namespace {
/// Q with linear coordinates (EqualityProjector::coordinates: u = G x, w = (G G^T)^{-1} G x);
/// counts the calls of coordinates and of normQ.
class CoordinateDenseProjector : public test::DenseProjector {
 public:
  explicit CoordinateDenseProjector(const test::EqualityQp& qp) : test::DenseProjector(qp.Q), G_(qp.G) {
    GGt_.assign(G_.size(), std::vector<double>(G_.size(), 0.0));
    for (size_t r = 0; r < G_.size(); ++r)
      for (size_t s = 0; s < G_.size(); ++s)
        for (size_t i = 0; i < G_[r].size(); ++i) GGt_[r][s] += G_[r][i] * G_[s][i];
  }
  bool coordinates(const qp::Vector& x, std::vector<double>& u, std::vector<double>& w) const override {
    ++calls;
    u = test::matVec(G_, gather_(x));
    w = test::solveDense(GGt_, u);
    return true;
  }
  double normQ(const qp::Vector& x, qp::Vector& scratch) const override {
    ++norms;
    return test::DenseProjector::normQ(x, scratch);
  }
  mutable long long calls = 0, norms = 0;

 private:
  Dense G_, GGt_;
  test::Gatherer gather_;
};
}  // namespace

// With coordinates, the inner stop tests follow ||Q mu|| along the CG steps (one call of
// coordinates per CG step, for p, instead of a projection of mu): the same solution.
TEST(SmalseM, equalityNormFollowedAlongCgStepsGivesTheSameSolution) {
  int followed = 0;
  for (unsigned seed = 1; seed <= 8; ++seed) {
    std::mt19937 gen(seed + 300);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const int n = 12 + seed % 5;
    const Dense M = test::randomSpd(n, 100.0, seed + 500);
    std::vector<double> b(n);
    for (double& v : b) v = 2.0 * u(gen);
    const auto blocks = test::randomBlocks(n, gen, {1.5, 2, 1, 1, 0.3, 0.15}, 30.0);
    std::vector<double> x0(n);
    for (double& v : x0) v = u(gen);
    blocks.project(x0);
    const auto qp = test::makeEqualityQp(M, randomRowsVanishingAt(x0, gen), b);
    const auto settings = tunedSettings();
    const auto reference = runSmalse(qp, blocks, settings);
    auto map = test::makeMap(n, test::selfComm());
    auto omega = blocks.build(*map);
    test::DenseOperator op(qp.A);
    CoordinateDenseProjector projector(qp);
    qp::Vector cv(map), mu(map);
    test::scatter(qp.c, cv);
    const auto counters = qp::SmalseM(settings).solve(op, projector, cv, omega, mu);
    EXPECT_TRUE(counters.converged) << "seed " << seed;
    EXPECT_EQ(projector.norms, 0) << "seed " << seed;
    // One stop test per inner iteration plus one per inner solve; each costs one call of
    // coordinates (of p after a CG step, of mu otherwise), except the forced refreshes.
    EXPECT_LE(projector.calls, counters.innerIterations + counters.outerIterations) << "seed " << seed;
    if (counters.cgSteps > 0) ++followed;
    const auto x = test::gather(mu);
    EXPECT_LE(test::maxDifference(x, reference.x), 1e-8 * std::max(1.0, test::normInf(reference.x))) << "seed " << seed;
  }
  EXPECT_GT(followed, 0);
}
