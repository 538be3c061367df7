#include "SmalseRun.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "tribos/qp/Reductions.hpp"

namespace tribos::qp {

namespace {
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

SmalseRun::SmalseRun(const SmalseSettings& settings, const SymmetricOperator& A, const EqualityProjector& rawQ,
                     const Vector& c, SeparableSet& omega, Vector& mu)
    : s_(settings),
      A_(A),
      rawQ_(rawQ),
      c_(c),
      omega_(omega),
      mu_(mu),
      map_(mu.getMap()),
      Q_(rawQ, inside_),
      betaT_(map_),
      b_(map_),
      g_(map_),
      Qmu_(map_),
      previousQmu_(map_),
      previousB_(map_),
      innerEquality_(Q_, 10, [this]() { return Arho_ ? Arho_->lastInputCoordinates() : nullptr; }) {}

SmalseCounters SmalseRun::finish() {
  counters_.seconds = watch_.seconds();
  counters_.productSeconds = products_;
  counters_.preconditionerSeconds = preconditioning_;
  counters_.operatorSeconds = inside_ + products_ + preconditioning_;
  return counters_;
}

bool SmalseRun::scale(double knownNormA) {
  // Scale-free parameters: rho and M relative to ||A||, eta relative to ||c|| (= ||P h||) or
  // the caller's rightHandSideScale.
  counters_.normA = knownNormA > 0.0 ? knownNormA
                                     : lanczosNorm(TimedOperator(A_, products_), *map_, s_.normEstimateSteps,
                                                   normEstimateToleranceFor(s_), &counters_.operatorApplications);
  normC_ = norm2(c_);
  if (!std::isfinite(counters_.normA) || !std::isfinite(normC_)) {
    counters_.nonFinite = true;  // a NaN / Inf in A or c: nothing to iterate on
    return false;
  }
  if (counters_.normA == 0.0) {
    // A = 0: the problem is linear and SMALSE-M's scaling is undefined. Only c = 0 with a
    // feasible mu is a (trivially) solved problem.
    omega_.project(mu_);
    counters_.converged = normC_ == 0.0;
    return false;
  }
  if (normC_ == 0.0) {
    // c = 0: the solution is 0 when 0 lies in Omega (it does in Ker G). Otherwise the
    // tolerances need another scale of the gradient: ||A|| ||P_Omega(0)||.
    mu_.putScalar(0.0);
    omega_.project(mu_);
    normC_ = counters_.normA * norm2(mu_);
    if (normC_ == 0.0) {
      counters_.converged = true;
      return false;
    }
  }
  // The caller's scale where c holds more than drives the solution (open gaps), but not so far
  // below ||c|| that epsilon times it falls under the round-off of a gradient of c's size
  // (tiny loads under a large gap never converged: 1e3 units of round-off is the floor).
  if (s_.rightHandSideScale > 0.0)
    normC_ = std::max(s_.rightHandSideScale,
                      1e3 * std::numeric_limits<double>::epsilon() * normC_ / s_.tolerance);
  normA_ = counters_.normA;
  rho_ = s_.rho * normA_;
  // ||A_rho|| = max(||PFP||, rho): PFP and rho Q act on the orthogonal spaces Ker G and Im G^T.
  // The power method's estimate is a lower bound: keep the MPGP step safely below 2/||A_rho||.
  normArho_ = 1.02 * std::max(normA_, rho_);
  M_ = s_.M0 * normA_;
  eta_ = s_.eta * normC_;
  eps_ = s_.tolerance * normC_;
  return true;
}

void SmalseRun::buildInnerSolver() {
  Arho_ = std::make_unique<PenalisedOperator>(A_, rawQ_, rho_, map_, products_);
  betaT_.putScalar(0.0);
  MpgpSettings mpgpSettings = s_.mpgp;
  if (s_.preconditioner) {
    preconditioner_ = std::make_unique<PenalisedPreconditioner>(*s_.preconditioner, rawQ_, rho_, map_, preconditioning_);
    mpgpSettings.preconditioner = preconditioner_.get();
  } else if (s_.mpgp.preconditioner) {
    givenPreconditioner_ = std::make_unique<TimedOperator>(*s_.mpgp.preconditioner, preconditioning_);
    mpgpSettings.preconditioner = givenPreconditioner_.get();
  }
  mpgpSettings.cgStep = [this](double alpha, const Vector& p) { innerEquality_.cgStep(alpha, p); };
  mpgpSettings.gradientFromProduct = [this]() { innerEquality_.gradientFromProduct(); };
  if (s_.innerMonitor)
    mpgpSettings.progress = [this](const MpgpCounters& inner) {
      s_.innerMonitor({outer_, inner.iterations, inner.projectedGradientNorm / normC_,
                       counters_.normA * innerGmu_ / normC_, M_ / counters_.normA,
                       counters_.operatorApplications + inner.operatorApplications, innerBound_ / normC_});
    };
  mpgp_ = std::make_unique<Mpgp>(mpgpSettings);
}

double SmalseRun::equalityNorm(const Vector& x) {
  Q_.applyQ(x, Qmu_);
  return norm2(Qmu_);
}

// ||G mu|| is measured as ||A|| ||Q mu|| in the Conventional outer test and in what is
// reported: the paper states its tests for the problem scaled to ||PFP|| = 1
// (ALGORITHMS.md 4), where ||Q mu|| <= eps ||P h|| compares a multiplier with a gap.
// Unscaled, ||A|| ||Q mu|| has the units of g^P and P h, so the test is invariant under
// A -> sA, c -> sc (the same minimiser) and under mu -> s mu, c -> s c. The inner bound
// M_k ||Q mu|| is consistent with it: M_k = M0 ||A|| carries the same factor. The Paper
// test ||Q mu|| <= eps M0 ||mu|| is scale-free as printed.
bool SmalseRun::equalityMet(double gmu, const Vector& x) const {
  if (s_.equalityTest == EqualityTest::Paper) return gmu <= s_.tolerance * s_.M0 * norm2(x);
  return normA_ * gmu <= eps_;
}

bool SmalseRun::converged(double gp, double gmu, const Vector& x) const { return gp <= eps_ && equalityMet(gmu, x); }

void SmalseRun::iterate(const OuterHook& hook) {
  buildInnerSolver();
  omega_.project(mu_);
  for (int k = 0; k < s_.maxOuterIterations; ++k) {
    const auto inner = innerSolve(k);
    counters_.outerIterations = k + 1;
    counters_.innerIterations += inner.iterations;
    if (inner.nonFinite || !std::isfinite(equalityNorm(mu_))) {
      counters_.nonFinite = true;  // "diverged": never converged, whatever the hook says
      counters_.operatorApplications += inner.operatorApplications;
      counters_.projectedGradient = inner.projectedGradientNorm / normC_;
      return;
    }
    if (updateMultipliers(k, inner, hook)) return;
  }
}

MpgpCounters SmalseRun::innerSolve(int k) {
  // Step 1: mu^k ~ argmin L_rho(mu, beta^k) over Omega with ||g^P|| <= min(M_k ||G mu||, eta)
  // (or the final accuracy reached).
  // b = c - G^T beta moved with beta: g follows it without a product (g = A_rho mu - b), and
  // MPGP keeps that g when the projection onto Omega (changed by the hook) leaves mu in place.
  if (gradientHolds_) previousB_.assign(b_);
  b_.update(1.0, c_, -1.0, betaT_, 0.0);
  if (gradientHolds_) g_.update(1.0, previousB_, -1.0, b_, 1.0);
  outer_ = k + 1;
  innerEquality_.restart();
  // The inner bound never drops below a tenth of the final accuracy: M_k may shrink
  // without limit when the slip bound moves (the Lagrangian is then not monotone), and
  // an inner target under round-off would never be met.
  const auto inner = mpgp_->solve(*Arho_, b_, omega_, normArho_, mu_, g_, [&](double gp, const Vector& x) {
    innerGmu_ = innerEquality_.norm(x, Qmu_);  // every inner iteration: EqualityNorm.hpp
    innerBound_ = std::max(std::min(M_ * innerGmu_, eta_), s_.innerFloor * eps_);
    return gp <= innerBound_ || converged(gp, innerGmu_, x) || (s_.stopRequested && s_.stopRequested());
  }, gradientHolds_);
  gradientHolds_ = true;
  return inner;
}

bool SmalseRun::updateMultipliers(int k, const MpgpCounters& inner, const OuterHook& hook) {
  counters_.cgSteps += inner.cgSteps;
  counters_.expansionSteps += inner.expansionSteps;
  counters_.proportioningSteps += inner.proportioningSteps;
  counters_.operatorApplications += inner.operatorApplications;
  counters_.preconditionerApplications += inner.preconditionerApplications;
  const double gp = inner.projectedGradientNorm;
  // L_rho(mu, beta) = 1/2 mu^T A_rho mu - b^T mu = 1/2 mu^T (g - b) with g = A_rho mu - b.
  Vector gMinusB(map_);
  gMinusB.update(1.0, g_, -1.0, b_, 0.0);
  // ||Q mu|| (Qmu = Q mu from the test above) and mu^T (g - b) in one reduction (the bits of
  // norm2 and dot alone).
  const auto [gmu2, muGminusB] = dots(Qmu_, Qmu_, mu_, gMinusB);
  const double gmu = std::sqrt(gmu2);
  counters_.projectedGradient = gp / normC_;
  counters_.equalityResidual = normA_ * gmu / normC_;
  const double L = 0.5 * muGminusB;
  const bool done = converged(gp, gmu, mu_);

  // Step 3: beta^{k+1} = beta^k + omega rho G mu^k, kept as G^T beta (+= omega rho Q mu);
  // omega = 1 is the paper's step, "Relaxed" takes it from the measured contraction
  // (MultiplierRelaxation.hpp). ratio: that contraction without the relaxation, for rho.
  const bool relaxed = s_.multiplierStep == MultiplierStep::Relaxed;
  double omega = 1.0, ratio = k > 0 ? gmu / previousGmu_ : 1.0;
  if (relaxed && k > 0 && previousGmu_ > 0.0 && gmu > 0.0) {
    omega = relaxation_.next(gmu, previousGmu_, dot(Qmu_, previousQmu_) / (gmu * previousGmu_));
    ratio = relaxation_.unrelaxedRatio();
  }
  if (!done) betaT_.update(omega * rho_, Qmu_, 1.0);
  if (relaxed) previousQmu_.assign(Qmu_);
  // Step 4: M_{k+1} = betaM M_k when the Lagrangian did not grow enough.
  if (k > 0 && L < previousL_ + 0.5 * rho_ * gmu * gmu) M_ *= s_.betaM;
  previousL_ = L;
  growPenalty(k, ratio, gmu);
  previousGmu_ = gmu;
  // Coulomb: the slip bound update (inexact successive approximations) may veto the stop.
  bool veto = false;
  if (hook) {
    ScopedSeconds timed(inside_);
    veto = hook(k, mu_, gp / normC_, normA_ * gmu / normC_, M_ / normA_);
  }
  // After the hook, so that a progress line reports what the hook did in this iteration
  // (the slip-bound change), not what it did in the previous one.
  if (s_.monitor)
    s_.monitor({k + 1, inner.iterations, gp / normC_, normA_ * gmu / normC_, M_ / normA_, counters_.operatorApplications});
  if (done && !veto) {
    counters_.converged = true;
    return true;
  }
  if (!done && stalled(counters_.equalityResidual) && (!s_.stallConfirmed || s_.stallConfirmed(mu_))) {
    counters_.stalled = true;
    return true;
  }
  return s_.stopRequested && s_.stopRequested();
}

bool SmalseRun::stalled(double equalityResidual) {
  equalityHistory_.push_back(equalityResidual);
  const size_t window = static_cast<size_t>(s_.stallWindow), n = equalityHistory_.size();
  return window > 0 && n > window && equalityResidual > 100.0 * s_.tolerance &&
         equalityResidual > 0.5 * equalityHistory_[n - 1 - window];
}

// Optional penalty growth when ||G mu|| decreased by less than the target ratio.
void SmalseRun::growPenalty(int k, double ratio, double gmu) {
  slowInARow_ = k > 0 && ratio > s_.rhoTargetRatio ? slowInARow_ + 1 : 0;
  if (slowInARow_ <= s_.rhoGrowthPatience) return;
  const double factor = k > 0 && s_.rhoGrowth > 1.0 ? rhoFactor(s_, ratio, equalityMet(gmu, mu_)) : 1.0;
  if (!(factor > 1.0)) return;
  gradientHolds_ = false;  // A_rho changes
  rho_ *= factor;
  normArho_ = 1.02 * std::max(counters_.normA, rho_);
  Arho_->setRho(rho_);
  if (preconditioner_) preconditioner_->setRho(rho_);
}

}  // namespace tribos::qp
