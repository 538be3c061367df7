#pragma once
// Internal to feti/: a component of T-FETI (BlockKernels.hpp lists them): from the dual
// solution back to the primal one and its checks: alpha where the inactive rows fix the rigid
// motions (paper (14), G_I G_I^T), u = K^+ (f - B^T lambda) + R alpha, B u, the residuals of
// the discrete problem (equilibrium, energy) and the reactions at eliminated components.
#include <vector>

#include "CoarseSpace.hpp"

namespace tribos::feti {

class PrimalRecovery {
 public:
  PrimalRecovery(const SubdomainSet& subdomains, const CoarseSpace& coarse, const TotalFetiSettings& settings);

  /// alpha from G_I^T alpha = r_I, r = F lambda - d~ given (and changed: zero off the mask,
  /// the combinations added), with G_I G_I^T factorised on rank 0; RigidMotionsUndetermined
  /// where it is singular.
  std::vector<double> rigidBodyCoefficients(DualVector& residual, const std::vector<char>& ownedRowMask,
                                            const std::vector<TotalFeti::RowCombination>& combinations) const;
  void applyB(const std::vector<std::vector<double>>& u, DualVector& y) const;
  double equilibriumResidual(const DualVector& lambda, const std::vector<std::vector<double>>& u,
                             double* forceScale) const;
  std::vector<std::vector<double>> recoverDisplacements(const DualVector& lambda, const std::vector<double>& alpha) const;
  std::vector<EliminatedReaction> eliminatedReactions(const std::vector<std::vector<double>>& u) const;
  double energy(const std::vector<std::vector<double>>& u) const;
  double loadNormInf() const;

 private:
  const SubdomainSet& subdomains_;
  const CoarseSpace& coarse_;
  const TotalFetiSettings& settings_;
};

}  // namespace tribos::feti
