#pragma once
// Small dense QPs for the qp/ tests: an operator that multiplies by a dense matrix on a
// Tpetra vector (gathering all entries on every rank, so it also runs distributed), random
// SPD matrices, and an exact active-set enumeration for tiny bound-constrained problems.
#include <mpi.h>

#include <Teuchos_DefaultMpiComm.hpp>
#include <Tpetra_Map.hpp>
#include <Tpetra_Vector.hpp>

#include <cmath>
#include <random>
#include <vector>

#include "tribos/qp/DualTypes.hpp"

namespace tribos::test {

using Dense = std::vector<std::vector<double>>;

inline Teuchos::RCP<const qp::Map> makeMap(int n) {
  return Teuchos::rcp(new qp::Map(n, 0, Teuchos::rcp(new Teuchos::MpiComm<int>(MPI_COMM_WORLD))));
}

/// All entries of a distributed vector on every rank (global order).
inline std::vector<double> gather(const qp::Vector& v) {
  const auto& map = *v.getMap();
  std::vector<double> local(map.getNodeNumElements()), all(map.getGlobalNumElements(), 0.0);
  auto view = v.getLocalViewHost(Tpetra::Access::ReadOnly);
  for (size_t i = 0; i < local.size(); ++i) all[map.getGlobalElement(static_cast<int>(i))] = view(i, 0);
  std::vector<double> sum(all.size());
  MPI_Allreduce(all.data(), sum.data(), static_cast<int>(all.size()), MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  return sum;
}

inline void scatter(const std::vector<double>& all, qp::Vector& v) {
  const auto& map = *v.getMap();
  auto view = v.getLocalViewHost(Tpetra::Access::OverwriteAll);
  for (size_t i = 0; i < view.extent(0); ++i) view(i, 0) = all[map.getGlobalElement(static_cast<int>(i))];
}

class DenseOperator : public qp::SymmetricOperator {
 public:
  explicit DenseOperator(Dense A) : A_(std::move(A)) {}
  void apply(const qp::Vector& x, qp::Vector& y) const override {
    ++applications;
    const auto xs = gather(x);
    std::vector<double> ys(A_.size(), 0.0);
    for (size_t i = 0; i < A_.size(); ++i)
      for (size_t j = 0; j < A_.size(); ++j) ys[i] += A_[i][j] * xs[j];
    scatter(ys, y);
  }
  mutable long long applications = 0;

 private:
  Dense A_;
};

/// Q = G^T (G G^T)^{-1} G as a dense projector.
class DenseProjector : public qp::EqualityProjector {
 public:
  explicit DenseProjector(Dense Q) : Q_(std::move(Q)) {}
  void applyQ(const qp::Vector& x, qp::Vector& y) const override { DenseOperator(Q_).apply(x, y); }

 private:
  Dense Q_;
};

/// A random SPD matrix with eigenvalues spread over [1, condition].
inline Dense randomSpd(int n, double condition, unsigned seed) {
  std::mt19937 gen(seed);
  std::normal_distribution<double> normal;
  Dense Qm(n, std::vector<double>(n));
  for (auto& row : Qm)
    for (double& v : row) v = normal(gen);
  // Gram-Schmidt for an orthogonal basis.
  for (int j = 0; j < n; ++j) {
    for (int k = 0; k < j; ++k) {
      double d = 0.0;
      for (int i = 0; i < n; ++i) d += Qm[i][j] * Qm[i][k];
      for (int i = 0; i < n; ++i) Qm[i][j] -= d * Qm[i][k];
    }
    double norm = 0.0;
    for (int i = 0; i < n; ++i) norm += Qm[i][j] * Qm[i][j];
    for (int i = 0; i < n; ++i) Qm[i][j] /= std::sqrt(norm);
  }
  Dense A(n, std::vector<double>(n, 0.0));
  for (int k = 0; k < n; ++k) {
    const double lambda = std::pow(condition, static_cast<double>(k) / std::max(n - 1, 1));
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) A[i][j] += lambda * Qm[i][k] * Qm[j][k];
  }
  return A;
}

/// Solves the dense system M x = r (Gaussian elimination with partial pivoting).
inline std::vector<double> solveDense(Dense M, std::vector<double> r) {
  const size_t n = r.size();
  for (size_t p = 0; p < n; ++p) {
    size_t best = p;
    for (size_t i = p + 1; i < n; ++i)
      if (std::abs(M[i][p]) > std::abs(M[best][p])) best = i;
    std::swap(M[p], M[best]);
    std::swap(r[p], r[best]);
    for (size_t i = p + 1; i < n; ++i) {
      const double f = M[i][p] / M[p][p];
      for (size_t k = p; k < n; ++k) M[i][k] -= f * M[p][k];
      r[i] -= f * r[p];
    }
  }
  std::vector<double> x(n);
  for (size_t p = n; p-- > 0;) {
    double s = r[p];
    for (size_t k = p + 1; k < n; ++k) s -= M[p][k] * x[k];
    x[p] = s / M[p][p];
  }
  return x;
}

/// min 1/2 x^T A x - b^T x s.t. x_i >= l_i (i in bounded), C x = 0 (rows of C), by
/// enumerating the active sets: the one whose KKT point is feasible with non-negative bound
/// multipliers (unique for SPD A). Exponential: tiny problems only.
inline std::vector<double> enumerateActiveSets(const Dense& A, const std::vector<double>& b,
                                               const std::vector<int>& bounded, const std::vector<double>& lower,
                                               const Dense& C = {}) {
  const int n = static_cast<int>(b.size()), nb = static_cast<int>(bounded.size()), nc = static_cast<int>(C.size());
  for (int mask = 0; mask < (1 << nb); ++mask) {
    // Unknowns: x (n), bound multipliers for active bounds, equality multipliers.
    std::vector<int> active;
    for (int k = 0; k < nb; ++k)
      if (mask & (1 << k)) active.push_back(k);
    const int na = static_cast<int>(active.size()), m = n + na + nc;
    Dense K(m, std::vector<double>(m, 0.0));
    std::vector<double> r(m, 0.0);
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) K[i][j] = A[i][j];
      r[i] = b[i];
    }
    // A x - b - sum nu_k e_{i_k} + C^T w = 0; x_{i_k} = l_k; C x = 0.
    for (int a = 0; a < na; ++a) {
      const int i = bounded[active[a]];
      K[i][n + a] = -1.0;
      K[n + a][i] = 1.0;
      r[n + a] = lower[active[a]];
    }
    for (int c = 0; c < nc; ++c)
      for (int i = 0; i < n; ++i) {
        K[i][n + na + c] = C[c][i];
        K[n + na + c][i] = C[c][i];
      }
    const auto z = solveDense(K, r);
    bool ok = true;
    for (int a = 0; a < na && ok; ++a) ok = z[n + a] >= -1e-12;
    for (int k = 0; k < nb && ok; ++k) ok = z[bounded[k]] >= lower[k] - 1e-12;
    if (ok) return std::vector<double>(z.begin(), z.begin() + n);
  }
  return {};
}

}  // namespace tribos::test
