#pragma once
// Internal to qp/: one SMALSE-M solve (paper Section 5, ALGORITHMS.md 4) as named steps:
// the scaling (||A||, ||c||, and the trivial problems), then outer iterations of Step 1 (an
// MPGP inner solve of the penalised problem), Step 3 (the multiplier), Step 4 (M_k) and the
// optional penalty growth, with the caller's hook (the Coulomb fixed point) between them.
// SmalseM::solve is the sequence.
#include <memory>
#include <vector>

#include "EqualityNorm.hpp"
#include "MultiplierRelaxation.hpp"
#include "SmalseOperators.hpp"
#include "tribos/core/Timer.hpp"

namespace tribos::qp {

class SmalseRun {
 public:
  SmalseRun(const SmalseSettings& settings, const SymmetricOperator& A, const EqualityProjector& rawQ, const Vector& c,
            SeparableSet& omega, Vector& mu);
  SmalseRun(const SmalseRun&) = delete;  // the inner solver's callbacks hold `this`
  SmalseRun& operator=(const SmalseRun&) = delete;

  /// ||A|| (estimated unless `knownNormA` > 0) and ||c||, which make rho, M, eta and epsilon
  /// scale-free; false when the problem ends here (non-finite data, A = 0, or c = 0 with 0
  /// feasible), its counters final.
  bool scale(double knownNormA);
  /// Outer iterations until SMALSE-M's criteria hold and the hook does not veto, the cap,
  /// a stop request or non-finite values.
  void iterate(const OuterHook& hook);
  /// The counters, with the times.
  SmalseCounters finish();

 private:
  void buildInnerSolver();
  /// Step 1: mu^k ~ argmin L_rho(mu, beta^k) over Omega to the inner bound.
  MpgpCounters innerSolve(int k);
  /// Steps 3 and 4 and the penalty growth after the inner solve of iteration k; true when
  /// the solve stops (converged and not vetoed, or a stop request).
  bool updateMultipliers(int k, const MpgpCounters& inner, const OuterHook& hook);
  void growPenalty(int k, double ratio, double gmu);
  /// The outer equality test on ||Q mu|| (SmalseSettings::equalityTest).
  bool equalityMet(double gmu, const Vector& x) const;
  bool converged(double gp, double gmu, const Vector& x) const;
  double equalityNorm(const Vector& x);

  const SmalseSettings& s_;
  const SymmetricOperator& A_;
  const EqualityProjector& rawQ_;
  const Vector& c_;
  SeparableSet& omega_;
  Vector& mu_;
  Teuchos::RCP<const Map> map_;
  // The time of the whole solve, and of it what A, M^-1, Q and the hook take (the operators'
  // wrappers add it; A_rho and M^-1 + Q/rho are given rawQ, so that no call counts twice).
  core::Stopwatch watch_;
  double inside_ = 0.0, products_ = 0.0, preconditioning_ = 0.0;  // inside: Q and the hook
  TimedProjector Q_;
  SmalseCounters counters_;
  double normC_ = 0.0, normA_ = 0.0, rho_ = 0.0, normArho_ = 0.0, M_ = 0.0, eta_ = 0.0, eps_ = 0.0;
  std::unique_ptr<PenalisedOperator> Arho_;
  Vector betaT_, b_, g_, Qmu_, previousQmu_, previousB_;  // betaT = G^T beta (the multiplier as a dual vector)
  // g = A_rho mu - b holds for the mu and b of the last inner solve; true until rho changes.
  bool gradientHolds_ = false;
  double previousL_ = 0.0, previousGmu_ = 0.0;
  int slowInARow_ = 0;  ///< outer iterations in a row that missed the rho target ratio
  std::vector<double> equalityHistory_;  ///< ||A|| ||G mu|| / ||c|| per outer iteration (stall test)
  /// Whether ||G mu|| stalled (SmalseSettings::stallWindow) at this outer iteration.
  bool stalled(double equalityResidual);
  MultiplierRelaxation relaxation_;
  // The outer iteration in progress, the last inner ||G mu|| and the inner stopping bound,
  // for the progress of long inner solves.
  int outer_ = 0;
  double innerGmu_ = 0.0, innerBound_ = 0.0;
  std::unique_ptr<PenalisedPreconditioner> preconditioner_;
  std::unique_ptr<TimedOperator> givenPreconditioner_;  // mpgp.preconditioner as it stands, timed
  EqualityNorm innerEquality_;  ///< ||Q mu|| at every inner stop test, followed along CG steps
  std::unique_ptr<Mpgp> mpgp_;
};

}  // namespace tribos::qp
