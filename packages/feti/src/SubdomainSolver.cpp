#include "tribos/feti/SubdomainSolver.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

namespace tribos::feti {

namespace {
double distance2(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  const double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
  return dx * dx + dy * dy + dz * dz;
}
}  // namespace

std::array<LO, 3> chooseFixingNodes(const std::vector<std::array<double, 3>>& coords) {
  const LO n = static_cast<LO>(coords.size());
  if (n < 3) throw std::invalid_argument("tribos::feti::chooseFixingNodes: a subdomain needs at least 3 nodes");
  std::array<double, 3> centroid{0, 0, 0};
  for (const auto& x : coords)
    for (int d = 0; d < 3; ++d) centroid[d] += x[d] / n;
  auto farthestFrom = [&](auto&& measure) {
    LO best = 0;
    double bestValue = -1.0;
    for (LO i = 0; i < n; ++i)
      if (const double v = measure(coords[i]); v > bestValue) {
        bestValue = v;
        best = i;
      }
    return best;
  };
  const LO a = farthestFrom([&](const auto& x) { return distance2(x, centroid); });
  const LO b = farthestFrom([&](const auto& x) { return distance2(x, coords[a]); });
  // Farthest from the line through a and b: |(x - a) x (b - a)|^2.
  const auto& pa = coords[a];
  const std::array<double, 3> ab{coords[b][0] - pa[0], coords[b][1] - pa[1], coords[b][2] - pa[2]};
  const LO c = farthestFrom([&](const auto& x) {
    const double d[3] = {x[0] - pa[0], x[1] - pa[1], x[2] - pa[2]};
    const double cx = d[1] * ab[2] - d[2] * ab[1], cy = d[2] * ab[0] - d[0] * ab[2], cz = d[0] * ab[1] - d[1] * ab[0];
    return cx * cx + cy * cy + cz * cz;
  });
  return {a, b, c};
}

void SubdomainSolver::compute(const fem::SubdomainSystem& system, const std::vector<std::array<double, 3>>& coords,
                              Factorization factorization, const SparseCholeskyOptions& options) {
  const fem::CsrMatrix& K = system.K;
  n_ = K.n;
  R_ = system.R;
  fixingNodes_ = chooseFixingNodes(coords);

  // K_reg = K + rho_f R_f R_f^T with R_f = the rows of R at the 9 dofs of the fixing nodes
  // (ALGORITHMS.md 1): for 3 non-collinear nodes R_f has rank 6, so K_reg is SPD and
  // K_reg^{-1} is a generalised inverse of K (K K_reg^{-1} K = K; paper Lemma 1). The 9x9
  // block may couple dofs that K does not: the pattern is the union.
  std::vector<LO> fixedDofs;
  for (LO node : fixingNodes_)
    for (int c = 0; c < 3; ++c) fixedDofs.push_back(3 * node + c);
  std::sort(fixedDofs.begin(), fixedDofs.end());
  double rho = 0.0;
  for (LO i = 0; i < n_; ++i) rho = std::max(rho, K.at(i, i));
  std::map<std::pair<LO, LO>, double> extra;  // (i, j) -> rho (R_f R_f^T)_ij
  for (LO i : fixedDofs)
    for (LO j : fixedDofs) {
      double s = 0.0;
      for (int m = 0; m < 6; ++m) s += R_[static_cast<size_t>(m) * n_ + i] * R_[static_cast<size_t>(m) * n_ + j];
      extra[{i, j}] = rho * s;
    }
  fem::CsrMatrix reg;
  reg.n = n_;
  reg.rowPtr.assign(n_ + 1, 0);
  reg.colInd.reserve(K.colInd.size() + 81);
  reg.values.reserve(K.colInd.size() + 81);
  for (LO i = 0; i < n_; ++i) {
    auto it = extra.lower_bound({i, 0});
    for (LO k = K.rowPtr[i]; k <= K.rowPtr[i + 1]; ++k) {
      const LO col = k < K.rowPtr[i + 1] ? K.colInd[k] : n_;
      // Merge the extra entries of row i that come before this column.
      for (; it != extra.end() && it->first.first == i && it->first.second < col; ++it) {
        reg.colInd.push_back(it->first.second);
        reg.values.push_back(it->second);
      }
      if (col == n_) break;
      double v = K.values[k];
      if (it != extra.end() && it->first.first == i && it->first.second == col) v += (it++)->second;
      reg.colInd.push_back(col);
      reg.values.push_back(v);
    }
    reg.rowPtr[i + 1] = static_cast<LO>(reg.colInd.size());
  }
  factor_ = makeSparseCholesky(factorization, options);
  factor_->factorize(reg);
  const std::vector<LO>& perm = factor_->permutation();
  kernelRows_.resize(6 * static_cast<size_t>(n_));
  for (LO k = 0; k < n_; ++k)
    for (int m = 0; m < 6; ++m) kernelRows_[6 * static_cast<size_t>(k) + m] = R_[static_cast<size_t>(m) * n_ + perm[k]];
  scratch_.assign(n_, 0.0);
}

void SubdomainSolver::applyGeneralizedInverse(const double* x, double* y, int nrhs) const {
  factor_->solve(x, y, nrhs);
}

void SubdomainSolver::removeKernelPermuted(double* v) const {
  // (I - R R^T) v with R orthonormal (paper eq. (11)); the six dot products in one pass
  // over the rows of R, each summed in the factor's order.
  double c[6] = {0, 0, 0, 0, 0, 0};
  const double* r = kernelRows_.data();
  for (LO k = 0; k < n_; ++k, r += 6)
    for (int m = 0; m < 6; ++m) c[m] += r[m] * v[k];
  r = kernelRows_.data();
  for (LO k = 0; k < n_; ++k, r += 6)
    v[k] -= ((r[0] * c[0] + r[1] * c[1]) + (r[2] * c[2] + r[3] * c[3])) + (r[4] * c[4] + r[5] * c[5]);
}

void SubdomainSolver::applyPseudoInversePermuted(double* v) const {
  // K^dagger = (I - R R^T) K^+ (I - R R^T) (paper eq. (11) / Lemma 1, R orthonormal).
  removeKernelPermuted(v);
  factor_->solveInPlace(v);
  removeKernelPermuted(v);
}

void SubdomainSolver::applyPseudoInverse(const double* x, double* y, int nrhs) const {
  const std::vector<LO>& perm = permutation();
  for (int j = 0; j < nrhs; ++j) {
    const double* xj = x + static_cast<size_t>(j) * n_;
    double* yj = y + static_cast<size_t>(j) * n_;
    for (LO k = 0; k < n_; ++k) scratch_[k] = xj[perm[k]];
    applyPseudoInversePermuted(scratch_.data());
    for (LO k = 0; k < n_; ++k) yj[perm[k]] = scratch_[k];
  }
}


}  // namespace tribos::feti
