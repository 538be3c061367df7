#include "tribos/qp/SmalseM.hpp"

#include <Tpetra_Vector.hpp>

#include <algorithm>
#include <cmath>
#include <memory>

#include "EqualityNorm.hpp"
#include "MultiplierRelaxation.hpp"
#include "TimedOperators.hpp"
#include "tribos/qp/Reductions.hpp"

namespace tribos::qp {

double EqualityProjector::normQ(const Vector& x, Vector& scratch) const {
  applyQ(x, scratch);
  return norm2(scratch);
}

namespace {
/// A_rho = A + rho Q (the penalised Hessian of paper (19)). Counts products with A only.
class PenalisedOperator : public SymmetricOperator {
 public:
  PenalisedOperator(const SymmetricOperator& A, const EqualityProjector& Q, double rho, const Teuchos::RCP<const Map>& map,
                    double& seconds)
      : A_(A), projected_(dynamic_cast<const ProjectedOperator*>(&A)), Q_(Q), rho_(rho), tmp_(map), seconds_(seconds) {}
  void setRho(double rho) { rho_ = rho; }
  void apply(const Vector& x, Vector& y) const override {
    ScopedSeconds timed(seconds_);
    if (projected_) {
      projected_->applyPlusComplement(x, y, rho_);  // Q x from the P x that A computes
      return;
    }
    A_.apply(x, y);
    Q_.applyQ(x, tmp_);
    y.update(rho_, tmp_, 1.0);
  }

 private:
  const SymmetricOperator& A_;
  const ProjectedOperator* projected_;  ///< A, when it can add Q x without a projection
  const EqualityProjector& Q_;
  double rho_;
  mutable Vector tmp_;
  double& seconds_;  ///< time in products (SmalseCounters::operatorSeconds)
};

/// M^-1 + Q / rho: the inner preconditioner of A_rho (paper (19)) from one of PFP on Ker G.
class PenalisedPreconditioner : public SymmetricOperator {
 public:
  PenalisedPreconditioner(const SymmetricOperator& M, const EqualityProjector& Q, double rho,
                          const Teuchos::RCP<const Map>& map, double& seconds)
      : M_(M), projected_(dynamic_cast<const ProjectedOperator*>(&M)), Q_(Q), rho_(rho), tmp_(map), seconds_(seconds) {}
  void setRho(double rho) { rho_ = rho; }
  void apply(const Vector& x, Vector& y) const override {
    ScopedSeconds timed(seconds_);
    if (projected_) {
      projected_->applyPlusComplement(x, y, 1.0 / rho_);
      return;
    }
    M_.apply(x, y);
    Q_.applyQ(x, tmp_);
    y.update(1.0 / rho_, tmp_, 1.0);
  }

 private:
  const SymmetricOperator& M_;
  const ProjectedOperator* projected_;  ///< M, when it can add Q x / rho without a projection
  const EqualityProjector& Q_;
  double rho_;
  mutable Vector tmp_;
  double& seconds_;
};

/// The factor for rho after an outer iteration that reduced ||G mu|| by the ratio r (> 1: grow).
/// "Ratio": rho growth whenever r missed the target. "Model": the augmented-Lagrangian rate
/// r = 1 / (1 + rho s) (s: the curvature that the active constraints give the dual function
/// on Im G^T) solved for the rho that gives the target: rho (1/r_t - 1) / (1/r - 1), at most
/// rho growth; not once the equality test holds (r is then round-off and inner accuracy).
double rhoFactor(const SmalseSettings& s, double r, bool equalityMet) {
  if (s.rhoGrowth <= 1.0 || !(r > s.rhoTargetRatio)) return 1.0;
  if (s.rhoUpdate != RhoUpdate::Model) return s.rhoGrowth;
  if (equalityMet) return 1.0;
  if (r >= 1.0) return s.rhoGrowth;
  return std::min(s.rhoGrowth, (1.0 / s.rhoTargetRatio - 1.0) / (1.0 / r - 1.0));
}
}  // namespace

double normEstimateToleranceFor(const SmalseSettings& s) {
  // ||A_rho|| = max(||A||, rho ||A||_est): from rho = 2 on the second term bounds it for any
  // estimate above half of ||A||, so the estimate sets only the scale of rho, M_0 and the
  // equality test, and a looser Lanczos stop (measured: 1e-3 against 1e-4 saves 5-15 products on
  // the bricks, doc/parameters.md) is safe. Below, alpha_bar depends on ||A|| itself.
  return s.rho >= 2.0 ? s.normEstimateTolerance : std::min(s.normEstimateTolerance, 1e-4);
}

SmalseCounters SmalseM::solve(const SymmetricOperator& A, const EqualityProjector& rawQ, const Vector& c,
                              SeparableSet& omega, Vector& mu, const OuterHook& hook, double knownNormA) const {
  const SmalseSettings& s = settings_;
  SmalseCounters counters;
  // The time of the whole solve, and of it what A, M^-1, Q and the hook take (the operators'
  // wrappers add it; A_rho and M^-1 + Q/rho are given rawQ, so that no call counts twice).
  const core::Stopwatch watch;
  double inside = 0.0, products = 0.0, preconditioning = 0.0;  // inside: Q and the hook
  const TimedProjector Q(rawQ, inside);
  auto finish = [&]() {
    counters.seconds = watch.seconds();
    counters.productSeconds = products;
    counters.preconditionerSeconds = preconditioning;
    counters.operatorSeconds = inside + products + preconditioning;
    return counters;
  };
  const auto map = mu.getMap();
  // Scale-free parameters: rho and M relative to ||A||, eta relative to ||c|| (= ||P h||).
  counters.normA = knownNormA > 0.0 ? knownNormA
                                    : lanczosNorm(TimedOperator(A, products), *map, s.normEstimateSteps,
                                                  normEstimateToleranceFor(s),
                                                  &counters.operatorApplications);
  double normC = norm2(c);
  if (!std::isfinite(counters.normA) || !std::isfinite(normC)) {
    counters.nonFinite = true;  // a NaN / Inf in A or c: nothing to iterate on
    return finish();
  }
  if (counters.normA == 0.0) {
    // A = 0: the problem is linear and SMALSE-M's scaling is undefined. Only c = 0 with a
    // feasible mu is a (trivially) solved problem.
    omega.project(mu);
    counters.converged = normC == 0.0;
    return finish();
  }
  if (normC == 0.0) {
    // c = 0: the solution is 0 when 0 lies in Omega (it does in Ker G). Otherwise the
    // tolerances need another scale of the gradient: ||A|| ||P_Omega(0)||.
    mu.putScalar(0.0);
    omega.project(mu);
    normC = counters.normA * norm2(mu);
    if (normC == 0.0) {
      counters.converged = true;
      return finish();
    }
  }
  double rho = s.rho * counters.normA;
  // ||A_rho|| = max(||PFP||, rho): PFP and rho Q act on the orthogonal spaces Ker G and Im G^T.
  // The power method's estimate is a lower bound: keep the MPGP step safely below 2/||A_rho||.
  double normArho = 1.02 * std::max(counters.normA, rho);
  double M = s.M0 * counters.normA;
  const double eta = s.eta * normC, eps = s.tolerance * normC;
  PenalisedOperator Arho(A, rawQ, rho, map, products);
  Vector betaT(map), b(map), g(map), Qmu(map), previousQmu(map);  // betaT = G^T beta (the multiplier as a dual vector)
  Vector previousB(map);
  // g = A_rho mu - b holds for the mu and b of the last inner solve; true until rho changes.
  bool gradientHolds = false;
  betaT.putScalar(0.0);
  double previousL = 0.0, previousGmu = 0.0;
  MultiplierRelaxation relaxation;
  const bool relaxed = s.multiplierStep == MultiplierStep::Relaxed;
  // The outer iteration in progress, the last inner ||G mu|| and the inner stopping bound,
  // for the progress of long inner solves.
  int outer = 0;
  double innerGmu = 0.0, innerBound = 0.0;
  MpgpSettings mpgpSettings = s.mpgp;
  std::unique_ptr<PenalisedPreconditioner> preconditioner;
  std::unique_ptr<TimedOperator> givenPreconditioner;  // mpgp.preconditioner as it stands, timed
  if (s.preconditioner) {
    preconditioner = std::make_unique<PenalisedPreconditioner>(*s.preconditioner, rawQ, rho, map, preconditioning);
    mpgpSettings.preconditioner = preconditioner.get();
  } else if (s.mpgp.preconditioner) {
    givenPreconditioner = std::make_unique<TimedOperator>(*s.mpgp.preconditioner, preconditioning);
    mpgpSettings.preconditioner = givenPreconditioner.get();
  }
  // ||Q mu|| at every inner stop test, followed along CG steps where Q allows it.
  EqualityNorm innerEquality(Q);
  mpgpSettings.cgStep = [&](double alpha, const Vector& p) { innerEquality.cgStep(alpha, p); };
  if (s.innerMonitor)
    mpgpSettings.progress = [&](const MpgpCounters& inner) {
      s.innerMonitor({outer, inner.iterations, inner.projectedGradientNorm / normC, counters.normA * innerGmu / normC,
                      M / counters.normA, counters.operatorApplications + inner.operatorApplications,
                      innerBound / normC});
    };
  const Mpgp mpgp(mpgpSettings);
  auto equalityNorm = [&](const Vector& x) {
    Q.applyQ(x, Qmu);
    return norm2(Qmu);
  };
  // ||G mu|| is measured as ||A|| ||Q mu|| in the Conventional outer test and in what is
  // reported: the paper states its tests for the problem scaled to ||PFP|| = 1
  // (ALGORITHMS.md 4), where ||Q mu|| <= eps ||P h|| compares a multiplier with a gap.
  // Unscaled, ||A|| ||Q mu|| has the units of g^P and P h, so the test is invariant under
  // A -> sA, c -> sc (the same minimiser) and under mu -> s mu, c -> s c. The inner bound
  // M_k ||Q mu|| is consistent with it: M_k = M0 ||A|| carries the same factor. The Paper
  // test ||Q mu|| <= eps M0 ||mu|| is scale-free as printed.
  const double normA = counters.normA;
  auto equalityMet = [&](double gmu, const Vector& x) {
    if (s.equalityTest == EqualityTest::Paper) return gmu <= s.tolerance * s.M0 * norm2(x);
    return normA * gmu <= eps;
  };
  auto smalseConverged = [&](double gp, double gmu, const Vector& x) { return gp <= eps && equalityMet(gmu, x); };

  omega.project(mu);
  for (int k = 0; k < s.maxOuterIterations; ++k) {
    // Step 1: mu^k ~ argmin L_rho(mu, beta^k) over Omega with ||g^P|| <= min(M_k ||G mu||, eta)
    // (or the final accuracy reached).
    // b = c - G^T beta moved with beta: g follows it without a product (g = A_rho mu - b), and
    // MPGP keeps that g when the projection onto Omega (changed by the hook) leaves mu in place.
    if (gradientHolds) previousB.assign(b);
    b.update(1.0, c, -1.0, betaT, 0.0);
    if (gradientHolds) g.update(1.0, previousB, -1.0, b, 1.0);
    outer = k + 1;
    innerEquality.restart();
    // The inner bound never drops below a tenth of the final accuracy: M_k may shrink
    // without limit when the slip bound moves (the Lagrangian is then not monotone), and
    // an inner target under round-off would never be met.
    const auto inner = mpgp.solve(Arho, b, omega, normArho, mu, g, [&](double gp, const Vector& x) {
      innerGmu = innerEquality.norm(x, Qmu);  // every inner iteration: EqualityNorm.hpp
      innerBound = std::max(std::min(M * innerGmu, eta), s.innerFloor * eps);
      return gp <= innerBound || smalseConverged(gp, innerGmu, x) || (s.stopRequested && s.stopRequested());
    }, gradientHolds);
    gradientHolds = true;
    counters.outerIterations = k + 1;
    counters.innerIterations += inner.iterations;
    if (inner.nonFinite || !std::isfinite(equalityNorm(mu))) {
      counters.nonFinite = true;  // "diverged": never converged, whatever the hook says
      counters.operatorApplications += inner.operatorApplications;
      counters.projectedGradient = inner.projectedGradientNorm / normC;
      break;
    }
    counters.cgSteps += inner.cgSteps;
    counters.expansionSteps += inner.expansionSteps;
    counters.proportioningSteps += inner.proportioningSteps;
    counters.operatorApplications += inner.operatorApplications;
    counters.preconditionerApplications += inner.preconditionerApplications;
    const double gp = inner.projectedGradientNorm;
    // L_rho(mu, beta) = 1/2 mu^T A_rho mu - b^T mu = 1/2 mu^T (g - b) with g = A_rho mu - b.
    Vector gMinusB(map);
    gMinusB.update(1.0, g, -1.0, b, 0.0);
    // ||Q mu|| (Qmu = Q mu from the test above) and mu^T (g - b) in one reduction (the bits of
    // norm2 and dot alone).
    const auto [gmu2, muGminusB] = dots(Qmu, Qmu, mu, gMinusB);
    const double gmu = std::sqrt(gmu2);
    counters.projectedGradient = gp / normC;
    counters.equalityResidual = normA * gmu / normC;
    const double L = 0.5 * muGminusB;
    const bool done = smalseConverged(gp, gmu, mu);

    // Step 3: beta^{k+1} = beta^k + omega rho G mu^k, kept as G^T beta (+= omega rho Q mu);
    // omega = 1 is the paper's step, "Relaxed" takes it from the measured contraction
    // (MultiplierRelaxation.hpp). ratio: that contraction without the relaxation, for rho.
    double omega = 1.0, ratio = k > 0 ? gmu / previousGmu : 1.0;
    if (relaxed && k > 0 && previousGmu > 0.0 && gmu > 0.0) {
      omega = relaxation.next(gmu, previousGmu, dot(Qmu, previousQmu) / (gmu * previousGmu));
      ratio = relaxation.unrelaxedRatio();
    }
    if (!done) betaT.update(omega * rho, Qmu, 1.0);
    if (relaxed) previousQmu.assign(Qmu);
    // Step 4: M_{k+1} = betaM M_k when the Lagrangian did not grow enough.
    if (k > 0 && L < previousL + 0.5 * rho * gmu * gmu) M *= s.betaM;
    previousL = L;
    // Optional penalty growth when ||G mu|| decreased by less than the target ratio.
    const double factor = k > 0 && s.rhoGrowth > 1.0 ? rhoFactor(s, ratio, equalityMet(gmu, mu)) : 1.0;
    if (factor > 1.0) {
      gradientHolds = false;  // A_rho changes
      rho *= factor;
      normArho = 1.02 * std::max(counters.normA, rho);
      Arho.setRho(rho);
      if (preconditioner) preconditioner->setRho(rho);
    }
    previousGmu = gmu;
    // Coulomb: the slip bound update (inexact successive approximations) may veto the stop.
    bool veto = false;
    if (hook) {
      ScopedSeconds timed(inside);
      veto = hook(k, mu, gp / normC, normA * gmu / normC, M / normA);
    }
    // After the hook, so that a progress line reports what the hook did in this iteration
    // (the slip-bound change), not what it did in the previous one.
    if (s.monitor)
      s.monitor({k + 1, inner.iterations, gp / normC, normA * gmu / normC, M / normA, counters.operatorApplications});
    if (done && !veto) {
      counters.converged = true;
      break;
    }
    if (s.stopRequested && s.stopRequested()) break;
  }
  return finish();
}

}  // namespace tribos::qp
