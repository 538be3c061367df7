#include "EliminatedComponents.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "SymmetricEigen.hpp"

namespace tribos::feti {

namespace {
constexpr int kModes = 6;
/// An eigenvalue of (C R)^T (C R) below this times the largest (at least 1: R is orthonormal)
/// marks a rigid mode that vanishes at every eliminated dof.
constexpr double kVanishing = 1e-10;

/// The eigenvalues and eigenvectors (columns, row-major) of (C R)^T (C R), C the rows of `dofs`.
std::vector<double> restraintGram(const std::vector<double>& R, LO n, const std::vector<LO>& dofs,
                                  std::vector<double>& vectors) {
  std::vector<double> gram(kModes * kModes, 0.0);
  for (LO d : dofs)
    for (int i = 0; i < kModes; ++i)
      for (int j = 0; j < kModes; ++j)
        gram[kModes * i + j] += R[static_cast<size_t>(i) * n + d] * R[static_cast<size_t>(j) * n + d];
  return symmetricEigen(gram, kModes, vectors);
}

/// R := R T, T the orthonormal basis of the kernel of C R (C: the rows of the eliminated dofs),
/// padded with zero columns to 6; returns the number of live columns.
int modesVanishingAt(std::vector<double>& R, LO n, const std::vector<LO>& dofs) {
  std::vector<double> vectors;
  const std::vector<double> values = restraintGram(R, n, dofs, vectors);
  double largest = 1.0;
  for (double v : values) largest = std::max(largest, v);
  std::vector<double> reduced(R.size(), 0.0);
  int live = 0;
  for (int j = 0; j < kModes; ++j) {
    if (!(values[j] <= kVanishing * largest)) continue;
    double* column = &reduced[static_cast<size_t>(live) * n];
    for (int m = 0; m < kModes; ++m) {
      const double t = vectors[kModes * m + j];
      for (LO k = 0; k < n; ++k) column[k] += R[static_cast<size_t>(m) * n + k] * t;
    }
    for (LO d : dofs) column[d] = 0.0;  // zero there to round-off; exactly zero now
    ++live;
  }
  R = std::move(reduced);
  return live;
}
}  // namespace

double weakestRestraint(const std::vector<std::array<double, 3>>& coords, const std::vector<LO>& dofs) {
  if (dofs.empty()) return std::numeric_limits<double>::infinity();
  const std::vector<double> R = fem::rigidBodyModes(coords);
  std::vector<double> vectors;
  const std::vector<double> values = restraintGram(R, static_cast<LO>(3 * coords.size()), dofs, vectors);
  double largest = 1.0, weakest = std::numeric_limits<double>::infinity();
  for (double v : values) largest = std::max(largest, v);
  for (double v : values)
    if (v > kVanishing * largest) weakest = std::min(weakest, v);
  return weakest;
}

EliminatedRows eliminateComponents(fem::SubdomainSystem& system, const std::vector<LO>& dofs, int& liveModes) {
  fem::CsrMatrix& K = system.K;
  EliminatedRows out;
  out.dof = dofs;
  std::vector<char> eliminated(static_cast<size_t>(K.n), 0);
  for (LO d : dofs) eliminated[d] = 1;
  for (LO d : dofs) {
    for (LO k = K.rowPtr[d]; k < K.rowPtr[d + 1]; ++k) {
      out.colInd.push_back(K.colInd[k]);
      out.values.push_back(K.values[k]);
    }
    out.rowPtr.push_back(static_cast<LO>(out.colInd.size()));
  }
  // Rows and columns of the eliminated dofs become zero but the diagonal: the pattern stays.
  for (LO i = 0; i < K.n; ++i)
    for (LO k = K.rowPtr[i]; k < K.rowPtr[i + 1]; ++k)
      if ((eliminated[i] || eliminated[K.colInd[k]]) && K.colInd[k] != i) K.values[k] = 0.0;
  eliminateLoads(system.f, out);
  liveModes = modesVanishingAt(system.R, K.n, dofs);
  return out;
}

void eliminateLoads(std::vector<double>& f, EliminatedRows& rows) {
  rows.load.resize(rows.dof.size());
  for (size_t i = 0; i < rows.dof.size(); ++i) {
    rows.load[i] = f[rows.dof[i]];
    f[rows.dof[i]] = 0.0;
  }
}

std::vector<double> eliminatedReactions(const EliminatedRows& rows, const std::vector<double>& u) {
  std::vector<double> out(rows.dof.size());
  for (size_t i = 0; i < rows.dof.size(); ++i) {
    double sum = 0.0;
    for (LO k = rows.rowPtr[i]; k < rows.rowPtr[i + 1]; ++k) sum += rows.values[k] * u[rows.colInd[k]];
    out[i] = sum - rows.load[i];
  }
  return out;
}

}  // namespace tribos::feti
