#pragma once
/// \file SubdomainSolver.hpp
/// Generalised inverses of a floating subdomain stiffness K_s (paper Section 4.1, Lemma 1;
/// ALGORITHMS.md 1): fixing-node regularisation K_reg = K + rho_f R_f R_f^T (R_f = R
/// restricted to the 9 dofs of 3 non-collinear, far-apart nodes), factorised once; then
///   K^+ x = K_reg^{-1} x                       (K K^+ K = K)
///   K^dagger x = (I - R R^T) K^+ (I - R R^T) x  (Moore-Penrose, eq. (9), Theorem 1).
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "tribos/feti/SparseCholesky.hpp"

namespace tribos::feti {

class SubdomainSolver {
 public:
  /// Picks the fixing nodes from `coords` (local node coordinates), builds K_reg and
  /// factorises it with `factorization` (see makeSparseCholesky). `system.R` must be the
  /// orthonormal kernel basis of system.K. The solver keeps references to nothing: it
  /// copies R. Safe to call concurrently for different objects.
  void compute(const fem::SubdomainSystem& system, const std::vector<std::array<double, 3>>& coords,
               Factorization factorization, const SparseCholeskyOptions& options = {});

  /// y = K^+ x for nrhs column-major vectors of length n (Lemma 1's generalised inverse).
  void applyGeneralizedInverse(const double* x, double* y, int nrhs = 1) const;
  /// y = K^dagger x (Moore-Penrose), nrhs column-major vectors (x and y may alias).
  void applyPseudoInverse(const double* x, double* y, int nrhs = 1) const;

  /// The order of the unknowns of applyPseudoInversePermuted: entry k is dof permutation()[k]
  /// (the factor's fill-reducing order). A caller that keeps its vectors in this order (F
  /// scatters B_s^T straight into it) saves two permutation passes per application.
  const std::vector<LO>& permutation() const { return factor_->permutation(); }
  /// v := K^dagger v for v in the order of permutation(). No allocation; like every method
  /// here, one thread at a time per object.
  void applyPseudoInversePermuted(double* v) const;
  /// v := K^+ v (the factor alone, Lemma 1's generalised inverse) in the same order.
  void applyGeneralizedInversePermuted(double* v) const { factor_->solveInPlace(v); }
  /// The same for v that vanishes outside `dofs` (in the order of permutation()), read there
  /// only on return: F's B_s^T scatters into B_s's dofs and B_s gathers from them. The
  /// backward substitution then skips what those dofs do not reach
  /// (SparseCholesky::setSparseColumns).
  void setSparseDofs(const std::vector<LO>& dofs) { factor_->setSparseColumns(dofs); }
  void applyGeneralizedInverseOnDofs(double* v) const { factor_->solveInPlaceOnColumns(v); }
  /// Bytes one applyGeneralizedInverseOnDofs reads (the factor's part it visits, both
  /// substitutions).
  long long generalizedInverseBytesOnDofs() const { return factor_->solveBytesOnColumns(); }

  LO size() const { return n_; }
  const std::vector<double>& kernel() const { return R_; }  ///< n x 6 column-major, orthonormal
  const std::array<LO, 3>& fixingNodes() const { return fixingNodes_; }
  const SparseCholesky& factor() const { return *factor_; }

 private:
  /// v := (I - R R^T) v in the factor's order: one pass for R^T v, one for the update.
  void removeKernelPermuted(double* v) const;

  LO n_ = 0;
  std::vector<double> R_;
  std::vector<double> kernelRows_;  ///< R in the factor's order, row-major (n x 6)
  mutable std::vector<double> scratch_;  ///< one vector in the factor's order
  std::array<LO, 3> fixingNodes_{};
  std::unique_ptr<SparseCholesky> factor_;
};

/// The three fixing nodes: the node farthest from the centroid, the node farthest from it,
/// the node farthest from the line through both (ALGORITHMS.md 1). Exposed for tests.
std::array<LO, 3> chooseFixingNodes(const std::vector<std::array<double, 3>>& coords);

}  // namespace tribos::feti
