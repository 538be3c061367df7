#pragma once
// Small dense QPs for the qp/ tests, and independent ways to solve or check them:
//  - DenseOperator / DenseProjector: multiply by a dense matrix on a Tpetra vector (x is
//    imported to a locally replicated map, so they run on any number of ranks, any comm);
//  - BlockSet: the separable set in global indices, its dense projection, and a builder of
//    qp::SeparableSet on a (possibly distributed) map;
//  - checkKkt: the KKT conditions of a candidate solution with least-squares multipliers
//    (no use of SeparableSet::splitGradient);
//  - admm: a reference solution by ADMM (a different algorithm from MPGP and SMALSE-M);
//  - enumerateActiveSets: the exact solution of tiny bound-constrained problems.
#include <mpi.h>

#include <Teuchos_DefaultMpiComm.hpp>
#include <Tpetra_Import.hpp>
#include <Tpetra_Map.hpp>
#include <Tpetra_Vector.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "tribos/qp/DualTypes.hpp"
#include "tribos/qp/SeparableSet.hpp"

namespace tribos::test {

using Dense = std::vector<std::vector<double>>;
using CommPtr = Teuchos::RCP<const Teuchos::Comm<int>>;

inline CommPtr worldComm() { return Teuchos::rcp(new Teuchos::MpiComm<int>(MPI_COMM_WORLD)); }
inline CommPtr selfComm() { return Teuchos::rcp(new Teuchos::MpiComm<int>(MPI_COMM_SELF)); }

/// n entries spread uniformly over the ranks of comm.
inline Teuchos::RCP<const qp::Map> makeMap(int n, const CommPtr& comm = worldComm()) {
  return Teuchos::rcp(new qp::Map(n, 0, comm));
}
/// n entries, this rank owning `localSize` consecutive ones.
inline Teuchos::RCP<const qp::Map> makeMapWithLocalSize(int n, size_t localSize, const CommPtr& comm) {
  return Teuchos::rcp(new qp::Map(n, localSize, 0, comm));
}

/// All entries of distributed vectors on every rank of their communicator (global order),
/// by a Tpetra::Import to a locally replicated map. The import is built once per map (its
/// setup is collective; rebuilding it per product would dominate the distributed test).
class Gatherer {
 public:
  std::vector<double> operator()(const qp::Vector& v) const {
    const auto map = v.getMap();
    if (map.get() != source_.get()) {
      source_ = map;
      replicated_ =
          Teuchos::rcp(new qp::Map(map->getGlobalNumElements(), 0, map->getComm(), Tpetra::LocallyReplicated));
      import_ = Teuchos::rcp(new Tpetra::Import<int, long long>(map, replicated_));
    }
    qp::Vector all(replicated_);
    all.doImport(v, *import_, Tpetra::INSERT);
    auto view = all.getLocalViewHost(Tpetra::Access::ReadOnly);
    std::vector<double> out(view.extent(0));
    for (size_t i = 0; i < out.size(); ++i) out[i] = view(i, 0);
    return out;
  }

 private:
  mutable Teuchos::RCP<const qp::Map> source_, replicated_;
  mutable Teuchos::RCP<Tpetra::Import<int, long long>> import_;
};

inline std::vector<double> gather(const qp::Vector& v) { return Gatherer()(v); }

/// v := the owned entries of the global vector `all`.
inline void scatter(const std::vector<double>& all, qp::Vector& v) {
  const auto& map = *v.getMap();
  auto view = v.getLocalViewHost(Tpetra::Access::OverwriteAll);
  for (size_t i = 0; i < view.extent(0); ++i) view(i, 0) = all[map.getGlobalElement(static_cast<int>(i))];
}

inline std::vector<double> matVec(const Dense& A, const std::vector<double>& x) {
  std::vector<double> y(A.size(), 0.0);
  for (size_t i = 0; i < A.size(); ++i)
    for (size_t j = 0; j < x.size(); ++j) y[i] += A[i][j] * x[j];
  return y;
}
inline Dense matMul(const Dense& A, const Dense& B) {
  Dense C(A.size(), std::vector<double>(B[0].size(), 0.0));
  for (size_t i = 0; i < A.size(); ++i)
    for (size_t k = 0; k < B.size(); ++k)
      for (size_t j = 0; j < B[0].size(); ++j) C[i][j] += A[i][k] * B[k][j];
  return C;
}
inline double normInf(const std::vector<double>& x) {
  double m = 0.0;
  for (double v : x) m = std::max(m, std::abs(v));
  return m;
}
inline double norm2(const std::vector<double>& x) {
  double s = 0.0;
  for (double v : x) s += v * v;
  return std::sqrt(s);
}
inline double maxDifference(const std::vector<double>& a, const std::vector<double>& b) {
  double m = 0.0;
  for (size_t i = 0; i < a.size(); ++i) m = std::max(m, std::abs(a[i] - b[i]));
  return m;
}

/// y = A x with a dense A; counts its applications (the solver's counters are checked
/// against this count).
class DenseOperator : public qp::SymmetricOperator {
 public:
  explicit DenseOperator(Dense A) : A_(std::move(A)) {}
  void apply(const qp::Vector& x, qp::Vector& y) const override {
    ++applications;
    scatter(matVec(A_, gather_(x)), y);
  }
  mutable long long applications = 0;

 private:
  Dense A_;
  Gatherer gather_;
};

/// Q = G^T (G G^T)^{-1} G as a dense matrix.
class DenseProjector : public qp::EqualityProjector {
 public:
  explicit DenseProjector(Dense Q) : Q_(std::move(Q)) {}
  void applyQ(const qp::Vector& x, qp::Vector& y) const override { scatter(matVec(Q_, gather_(x)), y); }

 private:
  Dense Q_;
  Gatherer gather_;
};

/// A random SPD matrix with eigenvalues spread geometrically over [1, condition].
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

/// The T-FETI shape of an equality-constrained QP: from an SPD M, rows G and b, the
/// projector Q = G^T (G G^T)^{-1} G, P = I - Q, A = P M P and c = P b. On Ker G,
/// 1/2 x^T A x - c^T x = 1/2 x^T M x - b^T x.
struct EqualityQp {
  Dense M, G, Q, A;
  std::vector<double> b, c;
};
inline EqualityQp makeEqualityQp(const Dense& M, const Dense& G, const std::vector<double>& b) {
  const size_t n = b.size(), m = G.size();
  EqualityQp qp{M, G, {}, {}, b, {}};
  Dense GGt(m, std::vector<double>(m, 0.0));
  for (size_t r = 0; r < m; ++r)
    for (size_t s = 0; s < m; ++s)
      for (size_t i = 0; i < n; ++i) GGt[r][s] += G[r][i] * G[s][i];
  // Columns of (G G^T)^{-1} G.
  Dense W(m, std::vector<double>(n));
  for (size_t i = 0; i < n; ++i) {
    std::vector<double> col(m);
    for (size_t r = 0; r < m; ++r) col[r] = G[r][i];
    const auto w = solveDense(GGt, col);
    for (size_t r = 0; r < m; ++r) W[r][i] = w[r];
  }
  qp.Q.assign(n, std::vector<double>(n, 0.0));
  for (size_t i = 0; i < n; ++i)
    for (size_t j = 0; j < n; ++j)
      for (size_t r = 0; r < m; ++r) qp.Q[i][j] += G[r][i] * W[r][j];
  Dense P(n, std::vector<double>(n));
  for (size_t i = 0; i < n; ++i)
    for (size_t j = 0; j < n; ++j) P[i][j] = (i == j) - qp.Q[i][j];
  qp.A = matMul(matMul(P, M), P);
  qp.c = matVec(P, b);
  return qp;
}

/// ||diag(1/a) y|| <= 1 about centre c; a zero semi-axis makes it a segment or a point.
struct Ellipse {
  int i, j;
  std::array<double, 2> c, a;
};

/// The separable set in global indices (what qp::SeparableSet holds in local ones).
struct BlockSet {
  std::vector<int> boundIndex;
  std::vector<double> lower;
  std::vector<Ellipse> ellipses;
  std::vector<int> blockStarts;  ///< first global index of every block (free entries too)

  /// The qp::SeparableSet of the blocks owned by this rank; a block split between ranks
  /// is a test error.
  qp::SeparableSet build(const qp::Map& map) const {
    qp::SeparableSet omega;
    for (size_t k = 0; k < boundIndex.size(); ++k) {
      const int l = map.getLocalElement(boundIndex[k]);
      if (l >= 0) omega.addBound(l, lower[k]);
    }
    for (const auto& e : ellipses) {
      const int li = map.getLocalElement(e.i), lj = map.getLocalElement(e.j);
      if ((li >= 0) != (lj >= 0)) throw std::logic_error("BlockSet::build: an ellipse is split between ranks");
      if (li >= 0) omega.addEllipse({li, lj}, e.c, e.a);
    }
    return omega;
  }
  /// Dense projection (bounds: max; ellipses: qp::projectOntoEllipse, tested on its own).
  void project(std::vector<double>& x) const {
    for (size_t k = 0; k < boundIndex.size(); ++k) x[boundIndex[k]] = std::max(x[boundIndex[k]], lower[k]);
    for (const auto& e : ellipses) {
      const auto y = qp::projectOntoEllipse({x[e.i] - e.c[0], x[e.j] - e.c[1]}, e.a);
      x[e.i] = e.c[0] + y[0];
      x[e.j] = e.c[1] + y[1];
    }
  }
  /// The largest violation of a constraint (in the units of x).
  double infeasibility(const std::vector<double>& x) const {
    double worst = 0.0;
    for (size_t k = 0; k < boundIndex.size(); ++k) worst = std::max(worst, lower[k] - x[boundIndex[k]]);
    for (const auto& e : ellipses) {
      const double y[2] = {x[e.i] - e.c[0], x[e.j] - e.c[1]};
      if (e.a[0] > 0.0 && e.a[1] > 0.0) {
        const double r = std::hypot(y[0] / e.a[0], y[1] / e.a[1]);
        worst = std::max(worst, (r - 1.0) * std::min(e.a[0], e.a[1]));
      } else {
        for (int ax = 0; ax < 2; ++ax) worst = std::max(worst, std::abs(y[ax]) - e.a[ax]);
      }
    }
    return worst;
  }
};

/// Random block layout over n entries: free entries, bounds, discs, ellipses with axis
/// ratios up to `maxRatio`, segments and points (in that order of the `kinds` weights).
inline BlockSet randomBlocks(int n, std::mt19937& gen, std::array<double, 6> kinds = {1, 2, 1, 1, 0.5, 0.3},
                             double maxRatio = 100.0) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), unit(0.0, 1.0);
  std::discrete_distribution<int> kind(kinds.begin(), kinds.end());
  BlockSet set;
  int i = 0;
  while (i < n) {
    set.blockStarts.push_back(i);
    int k = kind(gen);
    if (k >= 2 && i + 1 >= n) k = unit(gen) < 0.5 ? 0 : 1;  // no room for a pair
    if (k == 0) {
      ++i;
    } else if (k == 1) {
      set.boundIndex.push_back(i);
      set.lower.push_back(0.3 * u(gen));
      ++i;
    } else {
      const double radius = std::pow(10.0, u(gen) * 0.7 - 0.3);
      std::array<double, 2> a{radius, radius};
      if (k == 3) a[1] = radius * std::pow(maxRatio, u(gen));
      if (k == 4) a[unit(gen) < 0.5 ? 0 : 1] = 0.0;
      if (k == 5) a = {0.0, 0.0};
      set.ellipses.push_back({i, i + 1, {0.3 * u(gen), 0.3 * u(gen)}, a});
      i += 2;
    }
  }
  return set;
}

/// KKT residuals of x for min 1/2 x^T A x - c^T x over the blocks and G x = 0, with the
/// multipliers fitted by least squares: r = A x - c + sum z_k v_k with v_k the outer
/// normals of the active constraints (z_k >= 0 required), the rows of G and the fixed
/// directions of degenerate ellipses (z_k free). Independent of qp::SeparableSet.
struct KktResult {
  double stationarity = 0.0;  ///< ||r||_inf with the least-squares multipliers
  double sign = 0.0;          ///< the most negative sign-constrained multiplier, as a positive number
  double infeasibility = 0.0;
  double equality = 0.0;      ///< ||G x||_inf
};
inline KktResult checkKkt(const Dense& A, const std::vector<double>& c, const std::vector<double>& x,
                          const BlockSet& set, const Dense& G = {}, double activeTolerance = 1e-10) {
  const size_t n = x.size();
  std::vector<double> g = matVec(A, x);
  for (size_t i = 0; i < n; ++i) g[i] -= c[i];
  std::vector<std::vector<double>> columns;
  std::vector<bool> signed_;
  auto unitColumn = [&](int i, double s, bool sign) {
    std::vector<double> v(n, 0.0);
    v[i] = s;
    columns.push_back(v);
    signed_.push_back(sign);
  };
  for (size_t k = 0; k < set.boundIndex.size(); ++k)
    if (x[set.boundIndex[k]] - set.lower[k] <= activeTolerance * std::max(1.0, std::abs(set.lower[k])))
      unitColumn(set.boundIndex[k], -1.0, true);
  for (const auto& e : set.ellipses) {
    const double y[2] = {x[e.i] - e.c[0], x[e.j] - e.c[1]};
    const int idx[2] = {e.i, e.j};
    if (e.a[0] > 0.0 && e.a[1] > 0.0) {
      if (std::hypot(y[0] / e.a[0], y[1] / e.a[1]) >= 1.0 - activeTolerance) {
        std::vector<double> v(n, 0.0);
        const double nx = y[0] / (e.a[0] * e.a[0]), ny = y[1] / (e.a[1] * e.a[1]), nn = std::hypot(nx, ny);
        v[e.i] = nx / nn;
        v[e.j] = ny / nn;
        columns.push_back(v);
        signed_.push_back(true);
      }
      continue;
    }
    for (int ax = 0; ax < 2; ++ax) {
      if (!(e.a[ax] > 0.0)) unitColumn(idx[ax], 1.0, false);  // fixed: any force balances
      else if (std::abs(y[ax]) >= e.a[ax] * (1.0 - activeTolerance)) unitColumn(idx[ax], y[ax] > 0 ? 1.0 : -1.0, true);
    }
  }
  for (const auto& row : G) {
    columns.push_back(row);
    signed_.push_back(false);
  }
  // Least squares min ||g + C z|| by the normal equations (C^T C) z = -C^T g.
  const size_t m = columns.size();
  std::vector<double> z;
  if (m > 0) {
    Dense N(m, std::vector<double>(m, 0.0));
    std::vector<double> rhs(m, 0.0);
    for (size_t p = 0; p < m; ++p) {
      for (size_t q = 0; q < m; ++q)
        for (size_t i = 0; i < n; ++i) N[p][q] += columns[p][i] * columns[q][i];
      for (size_t i = 0; i < n; ++i) rhs[p] -= columns[p][i] * g[i];
    }
    z = solveDense(N, rhs);
  }
  KktResult out;
  std::vector<double> r = g;
  for (size_t p = 0; p < m; ++p) {
    for (size_t i = 0; i < n; ++i) r[i] += z[p] * columns[p][i];
    if (signed_[p]) out.sign = std::max(out.sign, -z[p]);
  }
  out.stationarity = normInf(r);

  out.infeasibility = set.infeasibility(x);
  for (const auto& row : G) {
    double s = 0.0;
    for (size_t i = 0; i < n; ++i) s += row[i] * x[i];
    out.equality = std::max(out.equality, std::abs(s));
  }
  return out;
}

/// Reference solution of min 1/2 x^T M x - b^T x over the blocks and G x = 0 by ADMM
/// (x-step: the equality-constrained quadratic with the penalty sigma/2 ||x - z + u||^2,
/// z-step: the projection), run until x = z and z stalls to round-off.
inline std::vector<double> admm(const Dense& M, const std::vector<double>& b, const BlockSet& set, const Dense& G,
                                double sigma, int maxIterations = 200000) {
  const size_t n = b.size(), m = G.size(), N = n + m;
  Dense K(N, std::vector<double>(N, 0.0));
  for (size_t i = 0; i < n; ++i) {
    for (size_t j = 0; j < n; ++j) K[i][j] = M[i][j];
    K[i][i] += sigma;
  }
  for (size_t r = 0; r < m; ++r)
    for (size_t i = 0; i < n; ++i) K[n + r][i] = K[i][n + r] = G[r][i];
  Dense Kinv(N, std::vector<double>(N));
  for (size_t j = 0; j < N; ++j) {
    std::vector<double> e(N, 0.0);
    e[j] = 1.0;
    const auto col = solveDense(K, e);
    for (size_t i = 0; i < N; ++i) Kinv[i][j] = col[i];
  }
  std::vector<double> z(n, 0.0), u(n, 0.0), rhs(N, 0.0);
  const double scale = std::max(1.0, normInf(b));
  for (int it = 0; it < maxIterations; ++it) {
    for (size_t i = 0; i < n; ++i) rhs[i] = b[i] + sigma * (z[i] - u[i]);
    const auto xw = matVec(Kinv, rhs);
    std::vector<double> zNew(n);
    for (size_t i = 0; i < n; ++i) zNew[i] = xw[i] + u[i];
    set.project(zNew);
    double primal = 0.0, change = 0.0;
    for (size_t i = 0; i < n; ++i) {
      u[i] += xw[i] - zNew[i];
      primal = std::max(primal, std::abs(xw[i] - zNew[i]));
      change = std::max(change, std::abs(zNew[i] - z[i]));
    }
    z = zNew;
    if (it > 10 && primal <= 1e-15 * scale && change <= 1e-15 * scale) break;
  }
  return z;
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
