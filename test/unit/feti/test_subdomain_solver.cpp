// Sparse Cholesky and the generalised inverses of a floating subdomain (paper Lemma 1, (11)).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "tribos/core/Errors.hpp"
#include "tribos/core/Parallel.hpp"
#include "tribos/feti/SparseCholesky.hpp"
#include "tribos/feti/SubdomainSolver.hpp"
#include "tribos/mesh/Decomposition.hpp"
#include "tribos/mesh/TwoBricks.hpp"

using namespace tribos;

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

std::vector<double> randomVector(size_t n, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> dist(-1.0, 1.0);
  std::vector<double> v(n);
  for (double& x : v) x = dist(gen);
  return v;
}

double norm(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x * x;
  return std::sqrt(s);
}
}  // namespace

TEST(SparseCholesky, solvesSpdSystemsWithSeveralRightHandSides) {
  // 3D Laplacian on a 6^3 grid plus a shift.
  const int m = 6, n = m * m * m;
  fem::CsrMatrix A;
  A.n = n;
  A.rowPtr.push_back(0);
  for (int k = 0; k < m; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) {
        const int row = i + m * (j + m * k);
        std::vector<std::pair<int, double>> entries{{row, 6.5}};
        if (i > 0) entries.push_back({row - 1, -1.0});
        if (i < m - 1) entries.push_back({row + 1, -1.0});
        if (j > 0) entries.push_back({row - m, -1.0});
        if (j < m - 1) entries.push_back({row + m, -1.0});
        if (k > 0) entries.push_back({row - m * m, -1.0});
        if (k < m - 1) entries.push_back({row + m * m, -1.0});
        std::sort(entries.begin(), entries.end());
        for (auto [c, v] : entries) {
          A.colInd.push_back(c);
          A.values.push_back(v);
        }
        A.rowPtr.push_back(static_cast<LO>(A.colInd.size()));
      }
  auto chol = feti::makeSparseCholesky("CHOLMOD");
  chol->factorize(A);
  const int nrhs = 3;
  const auto b = randomVector(static_cast<size_t>(n) * nrhs, 1);
  std::vector<double> x(b.size()), r(n);
  chol->solve(b.data(), x.data(), nrhs);
  for (int j = 0; j < nrhs; ++j) {
    A.apply(&x[j * n], r.data());
    for (int i = 0; i < n; ++i) r[i] -= b[j * n + i];
    EXPECT_LT(norm(r), 1e-12 * norm(std::vector<double>(b.begin() + j * n, b.begin() + (j + 1) * n)));
  }
  // Not positive definite: an error, not a silent result.
  for (double& v : A.values) v = -v;
  EXPECT_THROW(chol->factorize(A), std::runtime_error);
  EXPECT_THROW(feti::makeSparseCholesky("NoSuchSolver"), core::InputError);
}

TEST(SubdomainSolver, generalizedInverseSatisfiesKKplusKEqualsK) {
  for (int hOverH : {2, 3}) {
    const auto f = floatingSubdomain(hOverH);
    feti::SubdomainSolver solver;
    solver.compute(f.system, f.coords, "CHOLMOD");
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

TEST(SubdomainSolver, pseudoInverseSatisfiesMoorePenroseConditions) {
  const auto f = floatingSubdomain(2);
  feti::SubdomainSolver solver;
  solver.compute(f.system, f.coords, "CHOLMOD");
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

TEST(SubdomainSolver, concurrentFactorizationsEqualSequentialOnes) {
  std::vector<Floating> subs;
  for (int s = 0; s < 4; ++s) subs.push_back(floatingSubdomain(3, s));
  auto run = [&](int threads) {
    core::setNumThreads(threads);
    std::vector<std::vector<double>> out(16);
    std::vector<feti::SubdomainSolver> solvers(16);
    core::forEachSubdomain(16, [&](int i) {
      const auto& f = subs[i % 4];
      solvers[i].compute(f.system, f.coords, "CHOLMOD");
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
    EXPECT_LE(diff, 1e-12 * norm(one[i]));
  }
}
