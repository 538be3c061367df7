// qp/: projections (idempotent, non-expansive, variational inequality, exact boundary
// steps), MPGP against exact active-set enumeration and against KKT conditions, SMALSE-M
// with an equality constraint against enumeration. Runs on 1 or 2 ranks.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "DenseQp.hpp"
#include "tribos/qp/Mpgp.hpp"
#include "tribos/qp/SeparableSet.hpp"
#include "tribos/qp/SmalseM.hpp"

using namespace tribos;
using test::Dense;

namespace {
double dist(std::array<double, 2> a, std::array<double, 2> b) { return std::hypot(a[0] - b[0], a[1] - b[1]); }
bool inEllipse(std::array<double, 2> y, std::array<double, 2> a, double tol) {
  if (a[0] == 0.0 || a[1] == 0.0) {
    for (int i = 0; i < 2; ++i)
      if (a[i] == 0.0 ? std::abs(y[i]) > tol : std::abs(y[i]) > a[i] * (1 + tol)) return false;
    return true;
  }
  return std::hypot(y[0] / a[0], y[1] / a[1]) <= 1.0 + tol;
}
}  // namespace

TEST(projectOntoEllipse, isIdempotentNonExpansiveAndSatisfiesTheVariationalInequality) {
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> u(-3.0, 3.0), logAxis(-6.0, 6.0);
  for (int trial = 0; trial < 2000; ++trial) {
    std::array<double, 2> a{std::pow(10.0, logAxis(gen) / 2), std::pow(10.0, logAxis(gen) / 2)};
    if (trial % 10 == 0) a[trial % 20 == 0 ? 0 : 1] = 0.0;  // degenerate: segments
    if (trial % 97 == 0) a = {0.0, 0.0};                      // a point
    const double scale = std::max({a[0], a[1], 1e-3});
    const std::array<double, 2> w{u(gen) * scale, u(gen) * scale}, v{u(gen) * scale, u(gen) * scale};
    const auto p = qp::projectOntoEllipse(w, a), pv = qp::projectOntoEllipse(v, a);
    EXPECT_TRUE(inEllipse(p, a, 1e-12)) << a[0] << " " << a[1];
    const auto pp = qp::projectOntoEllipse(p, a);
    EXPECT_LE(dist(p, pp), 1e-12 * scale);                   // idempotent
    EXPECT_LE(dist(p, pv), dist(w, v) * (1 + 1e-12) + 1e-15);  // non-expansive
    // (w - P w)^T (y - P w) <= 0 for feasible y (sampled on and inside the set).
    for (int k = 0; k < 20; ++k) {
      const double t = 2 * M_PI * k / 20, r = (k % 3) / 2.0;
      const std::array<double, 2> y{r * a[0] * std::cos(t), r * a[1] * std::sin(t)};
      const double vi = (w[0] - p[0]) * (y[0] - p[0]) + (w[1] - p[1]) * (y[1] - p[1]);
      EXPECT_LE(vi, 1e-10 * scale * scale);
    }
    if (a[0] == a[1] && a[0] > 0 && std::hypot(w[0], w[1]) > a[0]) {  // disc: radial scaling
      const double s = a[0] / std::hypot(w[0], w[1]);
      EXPECT_NEAR(p[0], s * w[0], 1e-12 * scale);
      EXPECT_NEAR(p[1], s * w[1], 1e-12 * scale);
    }
  }
}

TEST(SeparableSet, feasibleStepsLandExactlyOnTheBoundary) {
  auto map = test::makeMap(5);
  qp::SeparableSet omega;
  const bool owner = map->getNodeNumElements() == 5;  // the checks below run where all entries live
  if (!owner) return;
  omega.addBound(0, -1.0);
  omega.addEllipse({1, 2}, {0.5, -0.25}, {2.0, 1e-3});
  omega.addEllipse({3, 4}, {0.0, 0.0}, {1.0, 1.0});
  qp::Vector x(map), p(map);
  test::scatter({0.0, 0.5, -0.25, 0.1, 0.2}, x);
  test::scatter({0.3, -1.0, 0.0, 0.0, 0.0}, p);
  double alpha = omega.maxFeasibleStep(x, p);
  qp::Vector y(map);
  y.update(1.0, x, -alpha, p, 0.0);
  auto yv = test::gather(y);
  EXPECT_NEAR(std::hypot((yv[1] - 0.5) / 2.0, (yv[2] + 0.25) / 1e-3), 1.0, 1e-12);
  EXPECT_TRUE(omega.contains(y, 1e-12));
  test::scatter({1.0, 0.0, 0.0, 0.0, 0.0}, p);  // the bound limits
  alpha = omega.maxFeasibleStep(x, p);
  EXPECT_NEAR(alpha, 1.0, 1e-15);
  test::scatter({0.0, 0.0, 0.0, -3.0, 4.0}, p);  // the disc: |(0.1, 0.2) - alpha (-3, 4)| = 1
  alpha = omega.maxFeasibleStep(x, p);
  y.update(1.0, x, -alpha, p, 0.0);
  yv = test::gather(y);
  EXPECT_NEAR(std::hypot(yv[3], yv[4]), 1.0, 1e-12);
}

TEST(Mpgp, matchesActiveSetEnumerationOnBoundConstrainedQps) {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    const int n = 6;
    const Dense A = test::randomSpd(n, 50.0, seed);
    std::mt19937 gen(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<double> b(n), lower;
    for (double& v : b) v = u(gen);
    const std::vector<int> bounded{0, 2, 3, 5};
    for (size_t k = 0; k < bounded.size(); ++k) lower.push_back(0.2 * u(gen));
    const auto exact = test::enumerateActiveSets(A, b, bounded, lower);
    ASSERT_EQ(exact.size(), static_cast<size_t>(n));

    auto map = test::makeMap(n);
    qp::SeparableSet omega;
    for (size_t k = 0; k < bounded.size(); ++k) {
      const int local = map->getLocalElement(bounded[k]);
      if (local >= 0) omega.addBound(local, lower[k]);
    }
    test::DenseOperator op(A);
    long long powerApps = 0;
    const double normA = qp::powerMethod(op, *map, 200, 1e-12, &powerApps);
    EXPECT_NEAR(normA, 50.0, 0.5);
    op.applications = 0;
    qp::Vector bv(map), x(map), g(map);
    test::scatter(b, bv);
    const auto counters = qp::Mpgp().solve(op, bv, omega, normA * 1.01, x, g,
                                           [](double gp, const qp::Vector&) { return gp <= 1e-12; });
    EXPECT_TRUE(counters.converged);
    EXPECT_EQ(counters.operatorApplications, op.applications);
    EXPECT_EQ(counters.iterations, counters.cgSteps + counters.expansionSteps + counters.proportioningSteps);
    const auto xs = test::gather(x);
    for (int i = 0; i < n; ++i) EXPECT_NEAR(xs[i], exact[i], 1e-8);
  }
}

TEST(Mpgp, solvesEllipseConstrainedQpsToKktAccuracy) {
  // Bounds, discs, very flat ellipses and free entries; compared with a long projected
  // gradient run (a different algorithm over the same, separately tested, projection).
  for (unsigned seed = 1; seed <= 10; ++seed) {
    const int n = 9;
    const Dense A = test::randomSpd(n, 20.0, seed + 100);
    std::mt19937 gen(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<double> b(n);
    for (double& v : b) v = 3.0 * u(gen);
    auto map = test::makeMap(n);
    qp::SeparableSet omega;
    auto local = [&](int gidx) { return map->getLocalElement(gidx); };
    if (local(0) >= 0 && local(0) == local(0)) omega.addBound(local(0), 0.1);
    if (local(1) >= 0 && local(2) >= 0) omega.addEllipse({local(1), local(2)}, {0.1, -0.2}, {0.5, 0.5});
    if (local(3) >= 0 && local(4) >= 0) omega.addEllipse({local(3), local(4)}, {0.0, 0.3}, {1.0, 1e-3 * (seed % 3 + 1)});
    if (local(5) >= 0 && local(6) >= 0) omega.addEllipse({local(5), local(6)}, {0.0, 0.0}, {0.2, 0.0});
    test::DenseOperator op(A);
    qp::Vector bv(map), x(map), g(map), xr(map), gr(map);
    test::scatter(b, bv);
    const auto c = qp::Mpgp().solve(op, bv, omega, 20.0 * 1.01, x, g, [](double gp, const qp::Vector&) { return gp <= 1e-11; });
    EXPECT_TRUE(c.converged);
    EXPECT_TRUE(omega.contains(x, 1e-12));
    // Reference: projected gradient x <- P(x - (1/||A||) g), many steps.
    for (int it = 0; it < 20000; ++it) {
      op.apply(xr, gr);
      gr.update(-1.0, bv, 1.0);
      xr.update(-1.0 / 20.0, gr, 1.0);
      omega.project(xr);
    }
    const auto a = test::gather(x), r = test::gather(xr);
    for (int i = 0; i < n; ++i) EXPECT_NEAR(a[i], r[i], 1e-8) << "seed " << seed << " entry " << i;
  }
}

TEST(SmalseM, matchesEnumerationWithAnEqualityConstraint) {
  for (unsigned seed = 1; seed <= 10; ++seed) {
    const int n = 6;
    const Dense M = test::randomSpd(n, 30.0, seed + 200);
    std::mt19937 gen(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    Dense G(1, std::vector<double>(n));
    for (double& v : G[0]) v = u(gen);
    double gg = 0.0;
    for (double v : G[0]) gg += v * v;
    // Q = G^T G / |G|^2, P = I - Q; A = P M P, c = P b (the T-FETI shape).
    Dense Q(n, std::vector<double>(n)), P(n, std::vector<double>(n)), A(n, std::vector<double>(n, 0.0));
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        Q[i][j] = G[0][i] * G[0][j] / gg;
        P[i][j] = (i == j) - Q[i][j];
      }
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        for (int k = 0; k < n; ++k)
          for (int l = 0; l < n; ++l) A[i][j] += P[i][k] * M[k][l] * P[l][j];
    std::vector<double> b(n), c(n, 0.0);
    for (double& v : b) v = u(gen);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) c[i] += P[i][j] * b[j];
    const std::vector<int> bounded{0, 1, 4};
    const std::vector<double> lower{-0.1, 0.05, -0.2};
    // On Ker G, 1/2 x^T P M P x - c^T x = 1/2 x^T M x - b^T x: enumerate with the equality.
    const auto exact = test::enumerateActiveSets(M, b, bounded, lower, G);
    ASSERT_EQ(exact.size(), static_cast<size_t>(n));

    auto map = test::makeMap(n);
    qp::SeparableSet omega;
    for (size_t k = 0; k < bounded.size(); ++k)
      if (map->getLocalElement(bounded[k]) >= 0) omega.addBound(map->getLocalElement(bounded[k]), lower[k]);
    test::DenseOperator op(A);
    test::DenseProjector projector(Q);
    qp::Vector cv(map), mu(map);
    test::scatter(c, cv);
    qp::SmalseSettings settings;
    settings.tolerance = 1e-10;
    settings.rho = 10.0;
    settings.M0 = 1.0;
    settings.betaM = 0.5;
    settings.powerIterations = 200;
    int hookCalls = 0;
    const auto counters = qp::SmalseM(settings).solve(op, projector, cv, omega, mu,
                                                      [&](int, const qp::Vector&, double, double, double) {
                                                        ++hookCalls;
                                                        return false;
                                                      });
    EXPECT_TRUE(counters.converged);
    EXPECT_EQ(hookCalls, counters.outerIterations);
    EXPECT_EQ(counters.operatorApplications, op.applications);
    const auto x = test::gather(mu);
    for (int i = 0; i < n; ++i) EXPECT_NEAR(x[i], exact[i], 1e-8) << "seed " << seed;
  }
}
