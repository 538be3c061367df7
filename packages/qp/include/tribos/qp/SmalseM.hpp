#pragma once
/// \file SmalseM.hpp
/// SMALSE-M (paper Section 5; ALGORITHMS.md 4): semi-monotonic augmented Lagrangian for
///     min 1/2 mu^T A mu - mu^T c   s.t.  mu in Omega,  G mu = 0,
/// with the penalised Hessian A_rho = A + rho Q (A = P F P, Q = I - P in T-FETI), the inner
/// problems solved by MPGP to ||g^P|| <= min(M_k ||G mu||, eta), multipliers beta kept as
/// the dual vector G^T beta (updated by rho Q mu), and M_k divided by beta_M when the
/// Lagrangian does not grow enough. A hook after each outer iteration lets the Coulomb
/// fixed point update the slip bounds (inexact successive approximations, eq. (20)).
#include <functional>
#include <string>
#include <vector>

#include "tribos/qp/Mpgp.hpp"

namespace tribos::qp {

/// What SMALSE-M reports after each outer iteration (for progress lines and studies).
struct SmalseProgress {
  int outerIteration = 0;
  int innerIterations = 0;          ///< MPGP iterations of this outer iteration
  double projectedGradient = 0.0;   ///< ||g^P|| / ||c||
  double equalityResidual = 0.0;    ///< ||G mu|| / ||c||
  double M = 0.0;                   ///< M_k relative to ||A||
  long long operatorApplications = 0;  ///< products with A so far
};

struct SmalseSettings {
  double tolerance = 1e-5;     ///< epsilon: stop when ||g^P|| <= eps ||c|| and ||G mu|| <= eps ||c||
  double eta = 1.0;            ///< eta, relative to ||c|| (the paper: eta = ||P h||)
  double rho = 1.0;            ///< rho, relative to ||A|| (the paper: rho = ||P F P||)
  double M0 = 1e-6;            ///< M_0 > 0, relative to ||A|| (M has the units of A); paper: 1e-6
  double betaM = 0.1;          ///< M_{k+1} = betaM M_k when the Lagrangian does not grow enough
  int maxOuterIterations = 100;
  /// "Conventional": ||G mu|| <= eps ||c||;  "Paper": ||G mu|| <= eps M_0 ||mu|| ||c||.
  std::string equalityTest = "Conventional";
  MpgpSettings mpgp;
  int powerIterations = 50;    ///< for ||A||
  double rhoGrowth = 1.0;      ///< > 1: rho *= rhoGrowth when ||G mu|| fell by less than rhoTargetRatio
  double rhoTargetRatio = 0.5;
  double innerFloor = 0.1;     ///< inner solves stop at ||g^P|| <= innerFloor eps ||c|| at the latest
  /// Called on every rank after each outer iteration (before the hook); may be empty.
  std::function<void(const SmalseProgress&)> monitor;
};

struct SmalseCounters {
  int outerIterations = 0, innerIterations = 0, cgSteps = 0, expansionSteps = 0, proportioningSteps = 0;
  long long operatorApplications = 0;  ///< products with A (each = one F application in T-FETI), incl. power method
  double projectedGradient = 0.0;      ///< ||g^P|| / ||c|| at return
  double equalityResidual = 0.0;       ///< ||G mu|| / ||c|| at return
  double normA = 0.0;
  bool converged = false;
};

/// Called after every outer iteration with (k, mu, ||g^P||/||c||, ||G mu||/||c||, M_k), after
/// the multiplier update. It may change Omega (the Coulomb slip bound update g := lambda_nu).
/// It returns true to veto convergence at this iteration (the slip bound moved by more than
/// epsilon): SMALSE-M stops only when its own criteria hold and the hook returned false.
using OuterHook = std::function<bool(int, const Vector&, double, double, double)>;

class SmalseM {
 public:
  explicit SmalseM(SmalseSettings settings = {}) : settings_(settings) {}
  /// Solves from mu (projected on Omega first). A = P F P must map into Ker G; Q projects
  /// onto Im G^T. Omega may be changed by the hook between outer iterations.
  SmalseCounters solve(const SymmetricOperator& A, const EqualityProjector& Q, const Vector& c, SeparableSet& omega,
                       Vector& mu, const OuterHook& hook = nullptr) const;

 private:
  SmalseSettings settings_;
};

}  // namespace tribos::qp
