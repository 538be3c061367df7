// The step kinds of MPGP (MpgpRun.hpp): proportional iterates take a CG step on the face
// (plain, or sliding along the active friction ellipses) or an expansion step; the others a
// proportioning step (gradient projection, or the exact step along the chopped gradient).
#include <Tpetra_Vector.hpp>

#include <algorithm>
#include <climits>

#include "MpgpRun.hpp"
#include "tribos/qp/Reductions.hpp"

namespace tribos::qp {

void MpgpRun::proportionalStep() {
  proportioningRun_ = 0;
  resolveDirection();
  A_.apply(p_, Ap_);
  ++counters.operatorApplications;
  // Tangent CG: the Hessian on the curved face adds the boundary's curvature term.
  if (slide_) {
    trialGradient_.assign(Ap_);
    omega_.addCurvatureProduct(x_, g_, p_, trialGradient_);
  }
  const auto [pAp, gTp] = dots(p_, slide_ ? trialGradient_ : Ap_, g_, p_);  // one reduction for both
  if (!(pAp > 0.0)) {  // p = 0 or A not positive on p: fall back to a gradient projection
    gradientProjectionStep();
    return;
  }
  const double alphaCg = gTp / pAp;
  const double alphaFeasible = omega_.maxFeasibleStep(x_, p_, slide_);
  if (slide_ && alphaCg <= alphaFeasible) {
    if (!slidingCgStep(alphaCg, pAp)) gradientProjectionStep();
  } else if (alphaCg <= alphaFeasible) {
    cgStep(alphaCg, pAp);
  } else {
    expansionStep(alphaFeasible);
  }
}

void MpgpRun::proportioningStep() {
  // Proportioning: release the constraints. A gradient projection step first; when the
  // chopped gradient still dominates right after one, it is stiff for alpha_bar: the exact
  // step along it.
  if (settings_.choppedProportioning && proportioningRun_ > 0)
    choppedGradientStep();
  else
    gradientProjectionStep();
  ++proportioningRun_;
}

// Conjugate gradient step on the current face.
void MpgpRun::cgStep(double alphaCg, double pAp) {
  x_.update(-alphaCg, p_, 1.0);
  if (settings_.cgStep) settings_.cgStep(alphaCg, p_);
  g_.update(-alphaCg, Ap_, 1.0);
  split(x_, g_, phi_, beta_);
  conjugateDirection(Ap_, pAp);
  ++counters.cgSteps;
}

// Expansion: to the boundary, then a projected step with the free gradient (the exact one
// along -phi when it decreases f, else the fixed alpha_bar).
void MpgpRun::expansionStep(double alphaFeasible) {
  x_.update(-alphaFeasible, p_, 1.0);
  g_.update(-alphaFeasible, Ap_, 1.0);
  omega_.project(x_);  // absorb round-off of the step onto the boundary
  split(x_, g_, phi_, beta_);
  if (settings_.optimalExpansion && optimalExpansionStep()) return;
  projectedStep(phi_);
  split(x_, g_, phi_, beta_);
  restartDirection();
  ++counters.expansionSteps;
}

// Projected step with the exact minimiser along -phi (one more product with A), kept only if
// it decreases f (monotonicity safeguard); false: not taken.
bool MpgpRun::optimalExpansionStep() {
  A_.apply(phi_, Ap_);
  ++counters.operatorApplications;
  const auto [phiAphi, phiPhi] = dots(phi_, Ap_, phi_, phi_);
  const double alphaOpt = phiAphi > 0.0 ? phiPhi / phiAphi : 0.0;
  if (!(alphaOpt > alphaBar_)) return false;
  reduced_.update(1.0, g_, -1.0, b_, 0.0);
  const double fHalf = 0.5 * dot(x_, reduced_);
  trial_.update(1.0, x_, -alphaOpt, phi_, 0.0);
  omega_.project(trial_);
  A_.apply(trial_, trialGradient_);
  ++counters.operatorApplications;
  trialGradient_.update(-1.0, b_, 1.0);
  reduced_.update(1.0, trialGradient_, -1.0, b_, 0.0);
  if (!(0.5 * dot(trial_, reduced_) <= fHalf)) return false;
  x_.assign(trial_);
  g_.assign(trialGradient_);
  if (settings_.gradientFromProduct) settings_.gradientFromProduct();  // the last product was A trial
  split(x_, g_, phi_, beta_);
  restartDirection();
  ++counters.expansionSteps;
  return true;
}

// x := P(x - alpha d) with the previous x and g kept (to undo the step); whether the
// projection moved x (one reduction: every rank alike).
bool MpgpRun::tentativeProjectedStep(double alpha, const Vector& d) {
  previousX_.assign(x_);
  previousG_.assign(g_);
  x_.update(-alpha, d, 1.0);
  trial_.assign(x_);
  omega_.project(x_);
  trial_.update(1.0, x_, -1.0);
  return trial_.normInf() != 0.0;
}

// Gradient projection step x = P(x - alpha g) (proportioning, and the fallback when A is not
// positive along p).
void MpgpRun::gradientProjectionStep() {
  projectedStep(g_);
  split(x_, g_, phi_, beta_);
  restartDirection();
  ++counters.proportioningSteps;
  startSliding();
}

// MPRGP's proportioning step: the exact minimiser along the chopped gradient,
// x := P(x - alpha beta) with alpha = beta^T g / beta^T A beta (= ||beta||^2 / beta^T A beta).
// On bounds the step is feasible as it stands and g follows from A beta; on an ellipse -beta
// is tangent to it and the projection brings x back, so g is recomputed. Where A is soft
// along beta (a multiplier turning on a friction ellipse, coupled weakly), the fixed
// alpha_bar = 1.9/||A|| step turns it by a fraction of what is needed: measured on a Hertz
// cylinder, 27 000 consecutive proportioning steps. Kept only if f decreases (else the
// gradient projection step).
void MpgpRun::choppedGradientStep() {
  A_.apply(beta_, Ap_);
  ++counters.operatorApplications;
  // The second derivative along the arc: beta^T A beta plus what the curved boundary adds.
  const auto [betaAp, betaNorm2] = dots(beta_, Ap_, beta_, beta_);
  const double betaAbeta = betaAp + omega_.boundaryCurvature(x_, g_, beta_);
  // Only where alpha_bar is too short for it: a shorter exact step (e.g. at the sharp end of
  // a flat ellipse) does less than the gradient projection step, which moves the free part too.
  const double alpha = betaAbeta > 0.0 ? betaNorm2 / betaAbeta : 0.0;
  if (!(alpha > alphaBar_)) {
    gradientProjectionStep();
    return;
  }
  const double f0 = objective(x_, g_);
  if (!tentativeProjectedStep(alpha, beta_)) {
    g_.update(-alpha, Ap_, 1.0);  // the projection did not move x: g = A x - b exactly
  } else {
    gradient();
  }
  // Kept if it achieves half the decrease alpha/2 ||beta||^2 of the exact step on a flat
  // boundary (a clear margin: a bare f < f0 would be decided by round-off when the projection
  // eats the step, and the choice would differ between rank layouts).
  if (objective(x_, g_) <= f0 - 0.25 * alpha * betaNorm2) {
    split(x_, g_, phi_, beta_);
    restartDirection();
    ++counters.proportioningSteps;
    startSliding();
    return;
  }
  x_.assign(previousX_);
  g_.assign(previousG_);
  split(x_, g_, phi_, beta_);
  gradientProjectionStep();
}

// Tangent CG (linearised face): the CG step moves active ellipse blocks along their tangent;
// projected back onto the boundary, x is no longer x - alpha p, so g is recomputed (one more
// product with A) and conjugacy holds only approximately. Kept if f decreased, else false (x
// and g restored) and the caller takes a gradient projection step. True without a projection
// correction too (then it is the plain CG step).
bool MpgpRun::slidingCgStep(double alphaCg, double pAp) {
  if (!tentativeProjectedStep(alphaCg, p_)) {
    if (settings_.cgStep) settings_.cgStep(alphaCg, p_);
    g_.update(-alphaCg, Ap_, 1.0);
  } else {
    gradient();
    // f(x) - f(x0) = (x - x0)^T (g + g0) / 2 exactly for a quadratic: from the step, free of
    // the cancellation in 1/2 x^T (g - b), which decided the test by round-off near the
    // solution (cylinder h0.05: f = -42.6, 8 of 16 slides "failed" with f - f0 between 2e-11
    // and 4e-10; with the difference 1 of 29 fails, and the run needs 1 548 F, not 14 442).
    trial_.update(1.0, x_, -1.0, previousX_, 0.0);
    gradientProjected_.update(1.0, g_, 1.0, previousG_, 0.0);
    const double change = 0.5 * dot(trial_, gradientProjected_);
    if (!(change < 0.0)) {
      x_.assign(previousX_);
      g_.assign(previousG_);
      slide_ = false;
      const long long wait = static_cast<long long>(std::max(settings_.tangentCgAfter, 1))
                             << std::min(failedSlides_++, 20);
      slideFrom_ = static_cast<int>(std::min<long long>(counters.proportioningSteps + wait, INT_MAX));
      return false;
    }
  }
  split(x_, g_, phi_, beta_);
  conjugateDirection(trialGradient_, pAp);  // trialGradient: (A + H_c) p
  ++counters.cgSteps;
  return true;
}

}  // namespace tribos::qp
