// EqualityNorm (qp/src/EqualityNorm.hpp): ||Q x|| at MPGP's stop tests, followed along CG
// steps by the linear coordinates of EqualityProjector::coordinates, recomputed afresh after
// any other change of x and every `refreshEvery` tracked steps.
#include <gtest/gtest.h>

#include <random>

#include "DenseQp.hpp"
#include "EqualityNorm.hpp"

using namespace tribos;
using test::Dense;

namespace {
/// Q = G^T (G G^T)^{-1} G with coordinates u = G x, w = (G G^T)^{-1} G x; counts its calls.
class CoordinateProjector : public test::DenseProjector {
 public:
  explicit CoordinateProjector(const test::EqualityQp& qp) : test::DenseProjector(qp.Q), G_(qp.G) {
    const size_t m = G_.size();
    GGt_.assign(m, std::vector<double>(m, 0.0));
    for (size_t r = 0; r < m; ++r)
      for (size_t s = 0; s < m; ++s)
        for (size_t i = 0; i < G_[r].size(); ++i) GGt_[r][s] += G_[r][i] * G_[s][i];
  }
  bool coordinates(const qp::Vector& x, std::vector<double>& u, std::vector<double>& w) const override {
    ++calls;
    u = test::matVec(G_, test::gather(x));
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
};

/// ||Q x|| by projecting.
double exactNorm(const test::EqualityQp& qp, const qp::Vector& x) {
  return test::norm2(test::matVec(qp.Q, test::gather(x)));
}
/// An equality-constrained QP of size n with `rows` random rows of G.
test::EqualityQp randomQp(int n, int rows, unsigned seed, unsigned spdSeed) {
  std::mt19937 gen(seed);
  std::normal_distribution<double> normal;
  Dense G(rows, std::vector<double>(n));
  for (auto& row : G)
    for (double& v : row) v = normal(gen);
  return test::makeEqualityQp(test::randomSpd(n, 10.0, spdSeed), G, std::vector<double>(n, 1.0));
}

/// randomQp's problem and the vectors of a test on its map: x random, p and scratch.
struct NormScene {
  NormScene(int n, int rows, unsigned seed, unsigned spdSeed)
      : qp(randomQp(n, rows, seed, spdSeed)), map(test::makeMap(n, test::selfComm())), x(map), p(map), scratch(map) {
    x.randomize();
  }
  test::EqualityQp qp;
  Teuchos::RCP<const qp::Map> map;
  qp::Vector x, p, scratch;
};
}  // namespace

TEST(EqualityNorm, followsCgStepsRecomputesAfterOtherStepsAndRefreshes) {
  NormScene scene(14, 3, 4, 3);
  const auto& qp = scene.qp;
  qp::Vector &x = scene.x, &p = scene.p, &scratch = scene.scratch;
  CoordinateProjector Q(qp);
  const int refreshEvery = 3;
  qp::EqualityNorm norm(Q, refreshEvery);
  norm.restart();
  EXPECT_NEAR(norm.norm(x, scratch), exactNorm(qp, x), 1e-12 * exactNorm(qp, x));
  EXPECT_EQ(Q.calls, 1);
  // CG steps: the coordinates of p only (refreshEvery of them in a row), then afresh.
  for (int step = 1; step <= 2 * (refreshEvery + 1); ++step) {
    p.randomize();
    const double alpha = 0.1 * step;
    x.update(-alpha, p, 1.0);
    const long long before = Q.calls;
    norm.cgStep(alpha, p);
    const double value = norm.norm(x, scratch);
    EXPECT_NEAR(value, exactNorm(qp, x), 1e-12 * exactNorm(qp, x)) << "step " << step;
    EXPECT_EQ(Q.calls - before, 1) << "step " << step;  // p's, or x's after refreshEvery
  }
  EXPECT_EQ(norm.trackedNorms(), 2 * refreshEvery);
  // Another change of x (no cgStep): afresh.
  x.randomize();
  const long long tracked = norm.trackedNorms();
  EXPECT_NEAR(norm.norm(x, scratch), exactNorm(qp, x), 1e-12 * exactNorm(qp, x));
  EXPECT_EQ(norm.trackedNorms(), tracked);
  // Two steps between stop tests cannot be followed: afresh.
  for (int k = 0; k < 2; ++k) {
    p.randomize();
    x.update(-0.5, p, 1.0);
    norm.cgStep(0.5, p);
  }
  EXPECT_NEAR(norm.norm(x, scratch), exactNorm(qp, x), 1e-12 * exactNorm(qp, x));
  EXPECT_EQ(norm.trackedNorms(), tracked);
  EXPECT_EQ(Q.norms, 0);
}

TEST(EqualityNorm, withoutCoordinatesEveryNormProjects) {
  NormScene scene(8, 2, 5, 4);
  const auto& qp = scene.qp;
  qp::Vector &x = scene.x, &p = scene.p, &scratch = scene.scratch;
  test::DenseProjector Q(qp.Q);
  qp::EqualityNorm norm(Q);
  norm.restart();
  for (int step = 0; step < 3; ++step) {
    p.randomize();
    x.update(-0.3, p, 1.0);
    norm.cgStep(0.3, p);
    EXPECT_NEAR(norm.norm(x, scratch), exactNorm(qp, x), 1e-12 * exactNorm(qp, x));
  }
  EXPECT_EQ(norm.trackedNorms(), 0);
}

TEST(EqualityNorm, takesTheCoordinatesThatTheLastProductHandedOver) {
  // The product with A hands over the coordinates of its input (lastProduct): a CG step takes
  // those of p from it, and a norm after gradientFromProduct those of x, without calling Q's
  // coordinates. Without the report the norm computes them (x moved otherwise); a product that
  // gave none (null) leaves Q to compute them too.
  NormScene scene(12, 3, 7, 5);
  const auto& qp = scene.qp;
  qp::Vector &x = scene.x, &p = scene.p, &scratch = scene.scratch;
  CoordinateProjector Q(qp);
  qp::EqualityCoordinates product;  // of the last "product's" input, as A_rho would keep them
  bool given = true;
  qp::EqualityNorm norm(Q, 10, [&]() { return given ? &product : nullptr; });
  auto productWith = [&](const qp::Vector& v) {
    CoordinateProjector fresh(qp);
    fresh.coordinates(v, product.u, product.w);
  };
  norm.restart();
  productWith(x);
  norm.gradientFromProduct();
  EXPECT_NEAR(norm.norm(x, scratch), exactNorm(qp, x), 1e-12 * exactNorm(qp, x));
  EXPECT_EQ(Q.calls, 0);
  p.randomize();
  productWith(p);
  x.update(-0.4, p, 1.0);
  norm.cgStep(0.4, p);
  EXPECT_NEAR(norm.norm(x, scratch), exactNorm(qp, x), 1e-12 * exactNorm(qp, x));
  EXPECT_EQ(Q.calls, 0);
  EXPECT_EQ(norm.trackedNorms(), 1);
  // x moved without a report: computed (the report of an earlier norm is not reused).
  p.randomize();
  x.update(-0.2, p, 1.0);
  EXPECT_NEAR(norm.norm(x, scratch), exactNorm(qp, x), 1e-12 * exactNorm(qp, x));
  EXPECT_EQ(Q.calls, 1);
  // A product that kept no coordinates: Q computes them.
  given = false;
  x.randomize();
  norm.gradientFromProduct();
  EXPECT_NEAR(norm.norm(x, scratch), exactNorm(qp, x), 1e-12 * exactNorm(qp, x));
  EXPECT_EQ(Q.calls, 2);
}
