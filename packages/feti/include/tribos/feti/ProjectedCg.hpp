#pragma once
/// \file ProjectedCg.hpp
/// Linear T-FETI: the dual problem with equality constraints only (no contact, or contact
/// rows treated as equalities: bonded bodies),
///     min 1/2 lambda^T F lambda - lambda^T d~   s.t.  G lambda = e,
/// solved by preconditioned conjugate gradients on P F P from lambda_0 = lambda_Im
/// (paper Section 4.2; Farhat-Mandel-Roux's projected CG). Belos's CG can carry the
/// projector (left preconditioner P D P, initial residual P h) and gives the same counts and
/// condition estimates, but its sums are not layout-independent and its exact P F P costs a
/// projection more per product; measured and kept out (doc/design.md, "Linear solve").
#include <functional>
#include <string>
#include <vector>

#include "tribos/feti/TotalFeti.hpp"

namespace tribos::feti {

struct ProjectedCgSettings {
  double tolerance = 1e-8;          ///< stop when ||P r|| <= tolerance ||P h||, h = d~ - F lambda_Im
  int maxIterations = 1000;
  DualPreconditioner preconditioner = DualPreconditioner::None;
  /// A budget asked before every iteration; true stops the iterations (not converged).
  /// Called on every rank at the same iterations (it may communicate). May be empty.
  std::function<bool()> stopRequested;
};

struct ProjectedCgResult {
  bool converged = false;
  int iterations = 0;
  double relativeResidual = 0.0;   ///< ||P r|| / ||P h||
  double conditionEstimate = 0.0;  ///< kappa of the (preconditioned) P F P on Ker G, from Lanczos
  double lambdaMin = 0.0, lambdaMax = 0.0;
  long long fApplications = 0;
};

/// Solves for lambda (overwritten; needs no initial value). Collective.
ProjectedCgResult solveProjectedCg(const TotalFeti& feti, DualVector& lambda, const ProjectedCgSettings& settings);

/// Extreme eigenvalues of the CG Lanczos tridiagonal built from the step lengths alpha_k and
/// the ratios beta_k (kept separate for tests): returns {min, max}.
std::pair<double, double> lanczosExtremes(const std::vector<double>& alpha, const std::vector<double>& beta);

}  // namespace tribos::feti
