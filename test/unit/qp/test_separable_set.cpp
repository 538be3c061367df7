// qp::SeparableSet and qp::projectOntoEllipse (ALGORITHMS.md 5): the projection is
// idempotent, non-expansive and satisfies the variational inequality for axis ratios up to
// 1e6 and zero semi-axes; a disc projects by radial scaling; feasible steps land exactly
// on the boundary; the projected gradient is the limit (x - P(x - t g)) / t as t -> 0
// (the projection of -g onto the tangent cone), with degenerate ellipses included.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "DenseQp.hpp"
#include "tribos/qp/SeparableSet.hpp"

using namespace tribos;
using test::Dense;

namespace {
using Pair = std::array<double, 2>;
double dist(Pair a, Pair b) { return std::hypot(a[0] - b[0], a[1] - b[1]); }
double dot(Pair a, Pair b) { return a[0] * b[0] + a[1] * b[1]; }
Pair minus(Pair a, Pair b) { return {a[0] - b[0], a[1] - b[1]}; }

/// Feasibility relative to `scale` (independent of the code under test).
bool inEllipse(Pair y, Pair a, double tol, double scale) {
  if (a[0] == 0.0 || a[1] == 0.0) {
    for (int i = 0; i < 2; ++i)
      if (std::abs(y[i]) > a[i] + tol * scale) return false;
    return true;
  }
  return std::hypot(y[0] / a[0], y[1] / a[1]) <= 1.0 + tol;
}

/// Feasible sample points of the ellipse: on the boundary and inside.
std::vector<Pair> feasibleSamples(Pair a, int count) {
  std::vector<Pair> out;
  for (int k = 0; k < count; ++k) {
    const double t = 2 * M_PI * (k + 0.37) / count, r = (k % 4 == 3) ? 0.5 : 1.0;
    out.push_back({r * a[0] * std::cos(t), r * a[1] * std::sin(t)});
  }
  out.push_back({a[0], 0.0});
  out.push_back({0.0, -a[1]});
  out.push_back({0.0, 0.0});
  return out;
}
}  // namespace

TEST(projectOntoEllipse, isIdempotentNonExpansiveAndSatisfiesTheVariationalInequality) {
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0), unit(0.0, 1.0);
  int outside = 0, degenerate = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    // Semi-axes 10^[-3, 3] each: ratios up to 1e6; zero axes (segments, points).
    Pair a{std::pow(10.0, 3.0 * u(gen)), std::pow(10.0, 3.0 * u(gen))};
    if (trial % 10 == 0) a[trial % 20 == 0 ? 0 : 1] = 0.0;
    if (trial % 37 == 0) a = {0.0, 0.0};
    if (trial % 13 == 0) a[1] = a[0];  // disc
    degenerate += (a[0] == 0.0 || a[1] == 0.0);
    const double amax = std::max(a[0], a[1]);
    // Points inside, on the boundary (within round-off), outside, and on the axes.
    const double t = 2 * M_PI * unit(gen);
    const double r = trial % 4 == 0 ? unit(gen) : trial % 4 == 1 ? 1.0 : 1.0 + std::pow(10.0, 4.0 * u(gen));
    Pair w{r * a[0] * std::cos(t), r * a[1] * std::sin(t)};
    if (trial % 4 == 3) w = {2.0 * amax * u(gen) + (a[0] == 0.0 ? u(gen) : 0.0), 2.0 * amax * u(gen)};
    if (trial % 11 == 0) w[trial % 22 == 0 ? 0 : 1] = 0.0;
    if (a[0] == 0.0 && a[1] == 0.0) w = {u(gen), u(gen)};
    const Pair v{w[0] + 0.3 * (amax + 1e-3) * u(gen), w[1] + 0.3 * (amax + 1e-3) * u(gen)};
    const double scale = std::max({a[0], a[1], std::abs(w[0]), std::abs(w[1]), std::abs(v[0]), std::abs(v[1])});
    SCOPED_TRACE("a = (" + std::to_string(a[0]) + ", " + std::to_string(a[1]) + "), w = (" + std::to_string(w[0]) +
                 ", " + std::to_string(w[1]) + ")");
    const Pair p = qp::projectOntoEllipse(w, a), pv = qp::projectOntoEllipse(v, a);
    outside += dist(p, w) > 0.0;
    EXPECT_TRUE(inEllipse(p, a, 1e-12, scale));
    EXPECT_LE(dist(p, qp::projectOntoEllipse(p, a)), 1e-12 * scale);              // idempotent
    EXPECT_LE(dist(p, pv), dist(w, v) * (1 + 1e-12) + 1e-15 * scale);            // non-expansive
    if (inEllipse(w, a, 0.0, scale)) EXPECT_LE(dist(p, w), 1e-15 * scale);      // inside: unchanged
    // (w - P w)^T (y - P w) <= 0 for every feasible y: P w is the nearest point. It has the
    // units of length^2, hence the tolerance relative to scale^2.
    for (const Pair& y : feasibleSamples(a, 64))
      EXPECT_LE(dot(minus(w, p), minus(y, p)), 1e-12 * scale * scale) << "y = " << y[0] << ", " << y[1];
    if (a[0] == a[1] && a[0] > 0 && std::hypot(w[0], w[1]) > a[0]) {  // disc: radial scaling
      const double s = a[0] / std::hypot(w[0], w[1]);
      EXPECT_NEAR(p[0], s * w[0], 1e-14 * scale);
      EXPECT_NEAR(p[1], s * w[1], 1e-14 * scale);
    }
    if (w[0] == 0.0) EXPECT_EQ(p[0], 0.0);  // exact on the axes
    if (w[1] == 0.0) EXPECT_EQ(p[1], 0.0);
  }
  EXPECT_GT(outside, 1000);
  EXPECT_GT(degenerate, 300);
}

TEST(SeparableSet, projectionIsBlockwiseIdempotentAndFeasible) {
  std::mt19937 gen(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 50; ++trial) {
    const int n = 30;
    const auto blocks = test::randomBlocks(n, gen, {1, 2, 1, 1, 0.5, 0.3}, 1e6);
    auto map = test::makeMap(n, test::selfComm());
    const auto omega = blocks.build(*map);
    std::vector<double> w(n), v(n);
    for (int i = 0; i < n; ++i) {
      w[i] = 3.0 * u(gen);
      v[i] = w[i] + u(gen);
    }
    qp::Vector x(map), y(map);
    test::scatter(w, x);
    test::scatter(v, y);
    EXPECT_EQ(omega.numBounds(), static_cast<int>(blocks.boundIndex.size()));
    EXPECT_EQ(omega.numEllipses(), static_cast<int>(blocks.ellipses.size()));
    omega.project(x);
    omega.project(y);
    const auto px = test::gather(x), py = test::gather(y);
    auto expected = w;
    blocks.project(expected);
    EXPECT_LE(test::maxDifference(px, expected), 1e-15 * 3.0);
    EXPECT_TRUE(omega.contains(x, 1e-12));
    EXPECT_LE(blocks.infeasibility(px), 1e-12 * 3.0);
    std::vector<double> dp(n), dw(n);
    for (int i = 0; i < n; ++i) {
      dp[i] = px[i] - py[i];
      dw[i] = w[i] - v[i];
    }
    EXPECT_LE(test::norm2(dp), test::norm2(dw) * (1 + 1e-12));
    qp::Vector again(x);
    omega.project(again);
    EXPECT_LE(test::maxDifference(test::gather(again), px), 1e-15 * 3.0);
    // Outside points are not contained.
    if (test::maxDifference(px, w) > 1e-6) {
      test::scatter(w, x);
      EXPECT_FALSE(omega.contains(x, 1e-9));
    }
  }
}

TEST(SeparableSet, aFeasiblePointIsLeftBitForBit) {
  // SMALSE-M keeps its gradient between outer iterations when the projection leaves mu in place
  // (Mpgp's gradientGiven): a point inside an ellipse must come back unchanged, not as
  // centre + (x - centre), which moves it in its last bits when the centre is far larger than
  // the point (the rounding of x - centre is of the centre's size).
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0), inside(0.0, 0.99);
  const int pairs = 200, n = 2 * pairs + 50;
  auto map = test::makeMap(n, test::selfComm());
  qp::SeparableSet omega;
  std::vector<double> w(n);
  for (int k = 0; k < pairs; ++k) {
    // |x - centre| <= 100 sqrt(2) + 0.2 < 150: inside
    const std::array<double, 2> centre{100.0 * u(gen), 100.0 * u(gen)}, axes{150.0 + inside(gen), 150.0 + inside(gen)};
    omega.addEllipse({2 * k, 2 * k + 1}, centre, axes);
    w[2 * k] = 0.1 * u(gen);
    w[2 * k + 1] = 0.1 * u(gen);
  }
  for (int r = 2 * pairs; r < n; ++r) {
    const double lower = u(gen);
    omega.addBound(r, lower);
    w[r] = lower + inside(gen);
  }
  qp::Vector x(map);
  test::scatter(w, x);
  omega.project(x);
  EXPECT_EQ(test::gather(x), w);
}

TEST(SeparableSet, feasibleStepsLandExactlyOnTheBoundary) {
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0), unit(0.0, 1.0);
  auto map = test::makeMap(3, test::selfComm());
  int onBoundary = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    // One bound and one ellipse (ratios up to 1e6, zero axes).
    Pair a{std::pow(10.0, 3.0 * u(gen)), std::pow(10.0, 3.0 * u(gen))};
    if (trial % 10 == 0) a[trial % 20 == 0 ? 0 : 1] = 0.0;
    if (trial % 50 == 0) a = {0.0, 0.0};
    const Pair c{u(gen), u(gen)};
    const double lower = u(gen);
    qp::SeparableSet omega;
    omega.addBound(0, lower);
    omega.addEllipse({1, 2}, c, a);
    // x: feasible, inside or on the boundary; p: random direction (sometimes only along
    // one axis, sometimes zero on the ellipse).
    const double t = 2 * M_PI * unit(gen), r = trial % 3 == 0 ? 1.0 : unit(gen);
    std::vector<double> xs{lower + (trial % 5 == 0 ? 0.0 : unit(gen)), c[0] + r * a[0] * std::cos(t),
                           c[1] + r * a[1] * std::sin(t)};
    const double amax = std::max({a[0], a[1], 1e-3});
    std::vector<double> ps{u(gen), amax * u(gen), amax * u(gen)};
    if (trial % 7 == 0) ps[1 + trial % 2] = 0.0;
    if (trial % 17 == 0) ps[1] = ps[2] = 0.0;
    qp::Vector x(map), p(map), y(map);
    test::scatter(xs, x);
    test::scatter(ps, p);
    omega.project(x);  // on the boundary exactly where r = 1
    xs = test::gather(x);
    const double alpha = omega.maxFeasibleStep(x, p);
    ASSERT_GE(alpha, 0.0);
    if (std::isinf(alpha)) {
      // No block limits: p points into the set along every constrained entry.
      EXPECT_LE(ps[0], 0.0);
      EXPECT_TRUE(ps[1] == 0.0 && ps[2] == 0.0);
      continue;
    }
    y.update(1.0, x, -alpha, p, 0.0);
    const auto ys = test::gather(y);
    EXPECT_TRUE(omega.contains(y, 1e-12)) << "trial " << trial;
    // Which block limits: the bound lands exactly on l, the ellipse on ||E(y - c)|| = 1.
    const double boundGap = std::abs(ys[0] - lower) / std::max(1.0, std::abs(lower));
    double ellipseGap = std::numeric_limits<double>::infinity();
    if (a[0] > 0 && a[1] > 0) {
      ellipseGap = std::abs(std::hypot((ys[1] - c[0]) / a[0], (ys[2] - c[1]) / a[1]) - 1.0);
    } else {
      // Degenerate: the step leaves the segment/point unless it is zero, or ends at an end.
      const bool moves = (a[0] == 0.0 && ps[1] != 0.0) || (a[1] == 0.0 && ps[2] != 0.0);
      if (moves) ellipseGap = alpha == 0.0 ? 0.0 : 1.0;
      for (int ax = 0; ax < 2; ++ax)
        if (a[ax] > 0.0 && ps[1 + ax] != 0.0)
          ellipseGap = std::min(ellipseGap, std::abs(std::abs(ys[1 + ax] - c[ax]) - a[ax]) / a[ax]);
    }
    EXPECT_LE(std::min(boundGap, ellipseGap), 1e-12) << "trial " << trial << " alpha " << alpha;
    onBoundary += ellipseGap <= 1e-12 && a[0] > 0 && a[1] > 0;
    // And it is the largest: a slightly longer step leaves Omega (checked strictly here:
    // contains() allows a tolerance that can exceed the overshoot on small sets). Steps of
    // round-off size are x on the boundary moving out: 0 up to round-off.
    if (alpha * test::normInf(ps) > 1e-12 * std::max({1.0, a[0], a[1]})) {
      const double longer = alpha * (1 + 1e-6);
      const double z[3] = {xs[0] - longer * ps[0], xs[1] - longer * ps[1] - c[0], xs[2] - longer * ps[2] - c[1]};
      bool leaves = z[0] < lower;
      if (a[0] > 0 && a[1] > 0) leaves = leaves || std::hypot(z[1] / a[0], z[2] / a[1]) > 1.0;
      else leaves = leaves || std::abs(z[1]) > a[0] || std::abs(z[2]) > a[1];
      EXPECT_TRUE(leaves) << "trial " << trial;
    }
  }
  EXPECT_GT(onBoundary, 500);
}

namespace {
/// (x - P(x - t g)) / t: tends to g^P = -P_T(-g) as t -> 0 (T the tangent cone at x).
std::vector<double> limitProjectedGradient(const test::BlockSet& blocks, const std::vector<double>& x,
                                           const std::vector<double>& g, double t) {
  std::vector<double> y(x.size());
  for (size_t i = 0; i < x.size(); ++i) y[i] = x[i] - t * g[i];
  blocks.project(y);
  for (size_t i = 0; i < x.size(); ++i) y[i] = (x[i] - y[i]) / t;
  return y;
}
}  // namespace

TEST(SeparableSet, projectedGradientIsTheProjectionOntoTheTangentCone) {
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int active = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 20;
    // Axis ratios up to 10 here: the limit has an error of order t |g|^2 times the curvature.
    const auto blocks = test::randomBlocks(n, gen, {1, 2, 1, 1, 0.7, 0.4}, 10.0);
    auto map = test::makeMap(n, test::selfComm());
    const auto omega = blocks.build(*map);
    // x: projections of random points (many on the boundary); g random.
    std::vector<double> xs(n), gs(n);
    for (int i = 0; i < n; ++i) {
      xs[i] = 2.0 * u(gen);
      gs[i] = u(gen);
    }
    blocks.project(xs);
    qp::Vector x(map), g(map), phi(map), beta(map), reduced(map);
    test::scatter(xs, x);
    test::scatter(gs, g);
    omega.splitGradient(x, g, phi, beta);
    const auto f = test::gather(phi), b = test::gather(beta);
    const auto limit = limitProjectedGradient(blocks, xs, gs, 1e-8);
    for (int i = 0; i < n; ++i) {
      EXPECT_NEAR(f[i] + b[i], limit[i], 1e-4) << "trial " << trial << " entry " << i;
      // phi and beta live on complementary entries (active blocks vs the rest).
      EXPECT_TRUE(f[i] == 0.0 || b[i] == 0.0);
      if (f[i] != 0.0) EXPECT_EQ(f[i], gs[i]);
      active += b[i] != 0.0;
    }
    // The reduced free gradient by its definition.
    const double alpha = 0.7;
    omega.reducedFreeGradient(x, phi, alpha, reduced);
    std::vector<double> expected(n);
    for (int i = 0; i < n; ++i) expected[i] = xs[i] - alpha * f[i];
    blocks.project(expected);
    const auto r = test::gather(reduced);
    for (int i = 0; i < n; ++i) EXPECT_NEAR(r[i], (xs[i] - expected[i]) / alpha, 1e-14);
  }
  EXPECT_GT(active, 500);
}

// A small disc next to a large centre (x = c + y stored): a block a few ulps of c inside its
// boundary cannot be stepped onto it, so it must count as on the boundary. Else it stays
// free with a feasible step of ~1e-18 in every iteration (the MPGP stall at 20x10x10 per
// brick, H/h 2: radius 5.9e-5, ||E y|| = 1 - 2.1e-12).
TEST(SeparableSet, aBlockWithinRoundOffOfItsCentreIsOnTheBoundary) {
  auto map = test::makeMap(2, test::selfComm());
  const double radius = 5.944e-5;
  const Pair center{1.0, -0.5};
  qp::SeparableSet omega;
  omega.addEllipse({0, 1}, center, {radius, radius});
  // y = (1 - 2.1e-12) radius e_1: inside by 1.2e-16, about half an ulp of c_1 = 1.
  const double inside = 1.0 - 2.1e-12;
  std::vector<double> xs{center[0] + inside * radius, center[1]};
  ASSERT_LT(std::hypot((xs[0] - center[0]) / radius, (xs[1] - center[1]) / radius), 1.0 - 1e-12);
  qp::Vector x(map), g(map), phi(map), beta(map), p(map);
  test::scatter(xs, x);
  test::scatter(std::vector<double>{-1.0, 0.3}, g);  // -g points out of the disc
  omega.splitGradient(x, g, phi, beta);
  const auto f = test::gather(phi), b = test::gather(beta);
  EXPECT_EQ(f[0], 0.0);
  EXPECT_EQ(f[1], 0.0);
  // On the boundary: beta is g with its outward-pressing normal part removed (n = e_1).
  EXPECT_EQ(b[0], 0.0);
  EXPECT_DOUBLE_EQ(b[1], 0.3);
  // The step to the boundary along e_1 cannot be resolved: x + t e_1 rounds back to x for t
  // below half an ulp of c_1, which is why the block must not be left free.
  EXPECT_EQ(xs[0] + 1e-16, xs[0]);
  // The same block clearly inside stays free.
  test::scatter(std::vector<double>{center[0] + 0.5 * radius, center[1]}, x);
  omega.splitGradient(x, g, phi, beta);
  EXPECT_EQ(test::gather(phi)[0], -1.0);
}

// Tangent CG's linearised face (splitGradient with slideOnEllipses): on an active ellipse the
// tangential part of g is free and only an inward normal part is chopped, so phi + beta is
// the same g^P; the curvature product's quadratic form is boundaryCurvature; an active
// ellipse no longer limits the feasible step.
TEST(SeparableSet, slidingOnEllipsesKeepsTheProjectedGradient) {
  auto map = test::makeMap(2, test::selfComm());
  const Pair a{2.0, 1.0}, center{0.5, -0.25};
  qp::SeparableSet omega;
  omega.addEllipse({0, 1}, center, a);
  const double t = 0.6;
  const Pair y{a[0] * std::cos(t), a[1] * std::sin(t)};  // on the boundary
  Pair n{y[0] / (a[0] * a[0]), y[1] / (a[1] * a[1])};
  const double nn = std::hypot(n[0], n[1]);
  n = {n[0] / nn, n[1] / nn};
  qp::Vector x(map), g(map), phi(map), beta(map), phiS(map), betaS(map), d(map), hd(map);
  test::scatter(std::vector<double>{center[0] + y[0], center[1] + y[1]}, x);
  for (const double sign : {-1.0, 1.0}) {  // pressed outwards, then released inwards
    const Pair gs{sign * 1.5 * n[0] + 0.4 * n[1], sign * 1.5 * n[1] - 0.4 * n[0]};
    test::scatter(std::vector<double>{gs[0], gs[1]}, g);
    omega.splitGradient(x, g, phi, beta);
    omega.splitGradient(x, g, phiS, betaS, true);
    const auto f = test::gather(phi), b = test::gather(beta), fs = test::gather(phiS), bs = test::gather(betaS);
    for (int i = 0; i < 2; ++i) EXPECT_NEAR(fs[i] + bs[i], f[i] + b[i], 1e-15);
    EXPECT_NEAR(dot({fs[0], fs[1]}, n), 0.0, 1e-15);  // phi is tangent
    EXPECT_NEAR(std::hypot(fs[0], fs[1]), 0.4, 1e-15);
    EXPECT_NEAR(std::hypot(bs[0], bs[1]), sign > 0 ? 1.5 : 0.0, 1e-15);
  }
  // Pressed outwards by 1.5: H_c = 1.5 kappa (I - n n^T), its form on d is boundaryCurvature.
  test::scatter(std::vector<double>{-1.5 * n[0], -1.5 * n[1]}, g);
  test::scatter(std::vector<double>{0.3, -0.7}, d);
  hd.putScalar(0.0);
  omega.addCurvatureProduct(x, g, d, hd);
  const auto h = test::gather(hd);
  EXPECT_NEAR(0.3 * h[0] - 0.7 * h[1], omega.boundaryCurvature(x, g, d) * dot({0.3, -0.7}, {-n[1], n[0]}) *
                                           dot({0.3, -0.7}, {-n[1], n[0]}) / (0.3 * 0.3 + 0.7 * 0.7),
              1e-12);
  EXPECT_NEAR(dot({h[0], h[1]}, n), 0.0, 1e-14);
  // Outwards along the tangent: no step without sliding, unlimited with it.
  test::scatter(std::vector<double>{n[1], -n[0]}, d);
  EXPECT_EQ(omega.maxFeasibleStep(x, d), 0.0);
  EXPECT_EQ(omega.maxFeasibleStep(x, d, true), std::numeric_limits<double>::infinity());
}
