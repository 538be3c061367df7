// The generalised inverses of a floating subdomain (paper Lemma 1, eq. (11); ALGORITHMS.md 1),
// with each sparse Cholesky behind makeSparseCholesky.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "RandomSpd.hpp"
#include "tribos/core/Errors.hpp"
#include "tribos/core/Parallel.hpp"
#include "tribos/feti/SparseCholesky.hpp"
#include "tribos/feti/SubdomainSolver.hpp"
#include "tribos/mesh/Decomposition.hpp"
#include "tribos/mesh/TwoBricks.hpp"

using namespace tribos;
using test::randomVector;

namespace {
struct Floating {
  fem::SubdomainSystem system;
  std::vector<std::array<double, 3>> coords;
};

Floating floatingSubdomain(int hOverH, int s = 0) {
  const mesh::TwoBricksSpec spec{{2, 1, 1}, hOverH};
  const auto mesh = mesh::generateTwoBricks(spec);
  const auto d = mesh::buildDecomposition(mesh, mesh::structuredPartition(mesh, spec));
  Floating f;
  f.system = fem::assembleSubdomain(mesh, d.subdomains[s], {{2.792e4, 2.593e4}, {6.360e4, 8.301e4}}, {});
  for (LO n : d.subdomains[s].nodes) f.coords.push_back(mesh.coords[n]);
  return f;
}

double norm(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x * x;
  return std::sqrt(s);
}
}  // namespace

class SubdomainSolverTest : public ::testing::TestWithParam<std::string> {};

// (The SparseCholesky implementations have their own tests: test_sparse_cholesky.cpp.)

TEST_P(SubdomainSolverTest, generalizedInverseSatisfiesKKplusKEqualsK) {
  for (int hOverH : {2, 3}) {
    const auto f = floatingSubdomain(hOverH);
    feti::SubdomainSolver solver;
    solver.compute(f.system, f.coords, core::valueOf(feti::kFactorizationNames, GetParam()));
    const size_t n = f.system.K.n;
    // Non-collinear fixing nodes.
    const auto& [a, b, c] = solver.fixingNodes();
    const auto &pa = f.coords[a], &pb = f.coords[b], &pc = f.coords[c];
    const double u[3] = {pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2]}, v[3] = {pc[0] - pa[0], pc[1] - pa[1], pc[2] - pa[2]};
    EXPECT_GT(std::hypot(u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]), 1e-3);
    for (unsigned seed : {1u, 2u, 3u}) {
      const auto x = randomVector(n, seed);
      std::vector<double> Kx(n), KplusKx(n), KKplusKx(n);
      f.system.K.apply(x.data(), Kx.data());
      solver.applyGeneralizedInverse(Kx.data(), KplusKx.data());
      f.system.K.apply(KplusKx.data(), KKplusKx.data());
      for (size_t i = 0; i < n; ++i) KKplusKx[i] -= Kx[i];
      EXPECT_LE(norm(KKplusKx), 1e-10 * norm(Kx));
    }
  }
}

TEST_P(SubdomainSolverTest, pseudoInverseSatisfiesMoorePenroseConditions) {
  const auto f = floatingSubdomain(2);
  feti::SubdomainSolver solver;
  solver.compute(f.system, f.coords, core::valueOf(feti::kFactorizationNames, GetParam()));
  const size_t n = f.system.K.n;
  // Dense K and K^dagger (n = 81).
  std::vector<double> K(n * n, 0.0), Kd(n * n, 0.0), e(n, 0.0);
  for (size_t j = 0; j < n; ++j) {
    std::fill(e.begin(), e.end(), 0.0);
    e[j] = 1.0;
    f.system.K.apply(e.data(), &K[j * n]);
    solver.applyPseudoInverse(e.data(), &Kd[j * n]);
  }
  auto multiply = [n](const std::vector<double>& A, const std::vector<double>& B) {
    std::vector<double> C(n * n, 0.0);
    for (size_t j = 0; j < n; ++j)
      for (size_t k = 0; k < n; ++k)
        for (size_t i = 0; i < n; ++i) C[j * n + i] += A[k * n + i] * B[j * n + k];
    return C;
  };
  auto maxAbs = [](const std::vector<double>& A) {
    double m = 0.0;
    for (double v : A) m = std::max(m, std::abs(v));
    return m;
  };
  const auto KKd = multiply(K, Kd), KdK = multiply(Kd, K);
  const auto KKdK = multiply(KKd, K), KdKKd = multiply(KdK, Kd);
  const double kScale = maxAbs(K), dScale = maxAbs(Kd);
  for (size_t i = 0; i < n * n; ++i) {
    EXPECT_NEAR(KKdK[i], K[i], 1e-10 * kScale);        // K K+ K = K
    EXPECT_NEAR(KdKKd[i], Kd[i], 1e-10 * dScale);      // K+ K K+ = K+
  }
  for (size_t i = 0; i < n; ++i)
    for (size_t j = 0; j < n; ++j) {
      EXPECT_NEAR(KKd[j * n + i], KKd[i * n + j], 1e-10);  // (K K+)^T = K K+
      EXPECT_NEAR(KdK[j * n + i], KdK[i * n + j], 1e-10);  // (K+ K)^T = K+ K
    }
}

TEST_P(SubdomainSolverTest, concurrentFactorizationsEqualSequentialOnes) {
  std::vector<Floating> subs;
  for (int s = 0; s < 4; ++s) subs.push_back(floatingSubdomain(3, s));
  auto run = [&](int threads) {
    core::setNumThreads(threads);
    std::vector<std::vector<double>> out(16);
    std::vector<feti::SubdomainSolver> solvers(16);
    core::forEachSubdomain(16, [&](int i) {
      const auto& f = subs[i % 4];
      solvers[i].compute(f.system, f.coords, core::valueOf(feti::kFactorizationNames, GetParam()));
      const auto x = randomVector(f.system.K.n, i);
      out[i].resize(x.size());
      solvers[i].applyPseudoInverse(x.data(), out[i].data());
    });
    core::setNumThreads(0);
    return out;
  };
  const auto one = run(1), two = run(2);
  for (size_t i = 0; i < one.size(); ++i) {
    double diff = 0.0;
    for (size_t k = 0; k < one[i].size(); ++k) diff = std::max(diff, std::abs(one[i][k] - two[i][k]));
    // The same operations on any thread count: bitwise (CHOLMOD picks its mode by the size
    // of the matrix, never by the thread; issue 9).
    EXPECT_EQ(diff, 0.0) << GetParam() << " subdomain " << i;
  }
}

TEST_P(SubdomainSolverTest, pseudoInverseIsOrthogonalToTheKernel) {
  // K^dagger x lies in Range K = (Ker K)^perp (eq. (11)): R^T K^dagger x = 0; and the
  // kernel R is orthonormal, as (I - R R^T) being a projector needs.
  const auto f = floatingSubdomain(3, 1);
  feti::SubdomainSolver solver;
  solver.compute(f.system, f.coords, core::valueOf(feti::kFactorizationNames, GetParam()));
  const size_t n = f.system.K.n;
  const auto& R = solver.kernel();
  for (int a = 0; a < 6; ++a)
    for (int b = 0; b < 6; ++b) {
      double dot = 0.0;
      for (size_t k = 0; k < n; ++k) dot += R[a * n + k] * R[b * n + k];
      EXPECT_NEAR(dot, a == b ? 1.0 : 0.0, 1e-12);
    }
  const int nrhs = 3;
  const auto x = randomVector(n * nrhs, 5);
  std::vector<double> y(x.size());
  solver.applyPseudoInverse(x.data(), y.data(), nrhs);
  for (int j = 0; j < nrhs; ++j)
    for (int a = 0; a < 6; ++a) {
      double dot = 0.0;
      for (size_t k = 0; k < n; ++k) dot += R[a * n + k] * y[j * n + k];
      EXPECT_LE(std::abs(dot), 1e-12 * norm(std::vector<double>(y.begin() + j * n, y.begin() + (j + 1) * n)));
    }
}

TEST(SubdomainSolver, fixingNodesAreFarApartAndNotCollinear) {
  // Collinear-prone input: nodes on a line plus one off it; the third must be off the line.
  std::vector<std::array<double, 3>> coords;
  for (int i = 0; i < 10; ++i) coords.push_back({double(i), 0.0, 0.0});
  coords.push_back({4.0, 0.5, 0.0});
  const auto nodes = feti::chooseFixingNodes(coords);
  EXPECT_TRUE((nodes[0] == 0 && nodes[1] == 9) || (nodes[0] == 9 && nodes[1] == 0));
  EXPECT_EQ(nodes[2], 10);
  EXPECT_THROW(feti::chooseFixingNodes({{0, 0, 0}, {1, 0, 0}}), std::invalid_argument);
}

INSTANTIATE_TEST_SUITE_P(Factorizations, SubdomainSolverTest, ::testing::ValuesIn(feti::sparseCholeskyNames()),
                         [](const auto& info) { return info.param; });
