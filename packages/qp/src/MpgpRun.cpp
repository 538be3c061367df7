#include "MpgpRun.hpp"

#include <Tpetra_Vector.hpp>

#include "tribos/qp/Reductions.hpp"

namespace tribos::qp {

MpgpRun::MpgpRun(const MpgpSettings& settings, const SymmetricOperator& A, const Vector& b, const SeparableSet& omega,
                 double normA, Vector& x, Vector& g)
    : settings_(settings),
      A_(A),
      b_(b),
      omega_(omega),
      x_(x),
      g_(g),
      alphaBar_(settings.stepScale / normA),
      phi_(x.getMap()),
      beta_(x.getMap()),
      p_(x.getMap()),
      Ap_(x.getMap()),
      reduced_(x.getMap()),
      gradientProjected_(x.getMap()),
      trial_(x.getMap()),
      trialGradient_(x.getMap()),
      z_(x.getMap()),
      zFull_(x.getMap()),
      scratch_(x.getMap()),
      previousX_(x.getMap()),
      previousG_(x.getMap()),
      // Tangent CG is switched on once this inner solve has taken `tangentCgAfter`
      // proportioning steps (the crawl it is for: CG on a face that holds the friction
      // multipliers, interrupted by proportioning steps that turn them); before, a CG step
      // costs one product with A, not two. A slide that fails to decrease f (a step too long
      // for the linearised face, or round-off in the normals near the solution) switches it
      // off for twice as many proportioning steps as the previous failure did (tangentCgAfter,
      // at least 1, the first time): near round-off the slides fail every few steps, and
      // without the back-off MPGP alternated between them and gradient projection steps
      // without converging (a random QP with tangent CG from the start).
      slideFrom_(settings.tangentCgAfter),
      slide_(settings.tangentCg && settings.tangentCgAfter == 0),
      conjugateProduct_(&Ap_) {}

// phi and beta of a gradient; with tangent CG the active ellipse blocks are free along their tangent.
void MpgpRun::split(const Vector& at, const Vector& gradientAt, Vector& free, Vector& chopped) const {
  omega_.splitGradient(at, gradientAt, free, chopped, slide_);
}

// g = A x - b after any change of x that is not a CG-type update.
void MpgpRun::gradient() {
  A_.apply(x_, g_);
  ++counters.operatorApplications;
  if (settings_.gradientFromProduct) settings_.gradientFromProduct();
  g_.update(-1.0, b_, 1.0);
}

// z = chi_F M^-1 phi (preconditioning in face; z = phi without a preconditioner): the
// restriction to the face keeps CG on it, and z^T phi = phi^T M^-1 phi > 0 keeps z a descent
// direction. splitGradient's free part of M^-1 phi is exactly that restriction.
void MpgpRun::preconditionedFreeGradient() {
  const SymmetricOperator* M = settings_.preconditioner;
  if (!M) {
    z_.assign(phi_);
    return;
  }
  M->apply(phi_, zFull_);
  ++counters.preconditionerApplications;
  split(x_, zFull_, z_, scratch_);
}

// The search direction after a step is used only if the next step starts from it (a CG step
// or an expansion, both from the product A p), so it is made there (resolveDirection): a
// proportioning step, or the end of the inner solve, then costs no preconditioner application
// (with its two projections). It is made from the same phi at the same x as it would have
// been at once: the same bits. Nothing writes Ap or trialGradient between a CG step and the
// next step's start, so the product the conjugation needs is still there.
// After a CG step: p = z - gamma p, gamma = z^T (A + H_c) p / p^T (A + H_c) p.
void MpgpRun::conjugateDirection(const Vector& product, double curvature) {
  direction_ = Direction::Conjugate;
  conjugateProduct_ = &product;
  conjugateCurvature_ = curvature;
}

void MpgpRun::resolveDirection() {
  if (direction_ == Direction::Current) return;
  preconditionedFreeGradient();
  if (direction_ == Direction::Restart) {
    p_.assign(z_);
  } else {
    const double gammaCg = dot(z_, *conjugateProduct_) / conjugateCurvature_;
    p_.update(1.0, z_, -gammaCg);
  }
  direction_ = Direction::Current;
}

// f(x) = 1/2 x^T A x - b^T x = 1/2 x^T (g - b), free given g.
double MpgpRun::objective(const Vector& at, const Vector& gradientAt) {
  trial_.update(1.0, gradientAt, -1.0, b_, 0.0);
  return 0.5 * dot(at, trial_);
}

// x := P(x - alpha_bar d), then g.
void MpgpRun::projectedStep(const Vector& direction) {
  x_.update(-alphaBar_, direction, 1.0);
  omega_.project(x_);
  gradient();
}

// Tangent CG on from the proportioning step slideFrom on: phi, beta and p in its split.
void MpgpRun::startSliding() {
  if (slide_ || !settings_.tangentCg || counters.proportioningSteps < slideFrom_) return;
  slide_ = true;
  split(x_, g_, phi_, beta_);
  restartDirection();
}

void MpgpRun::start(bool gradientGiven) {
  if (gradientGiven) {
    // g = A x - b for this x: kept unless the projection moves x (one reduction decides it
    // on every rank alike).
    previousX_.assign(x_);
    omega_.project(x_);
    trial_.update(1.0, x_, -1.0, previousX_, 0.0);
    if (trial_.normInf() != 0.0) gradient();
  } else {
    omega_.project(x_);
    gradient();
  }
  split(x_, g_, phi_, beta_);
  restartDirection();
}

// ||g^P||^2 and the proportioning test's ||beta||^2 and phi~^T phi in one reduction
// (Reductions.hpp: the bits of three separate ones).
std::array<double, 3> MpgpRun::iterationSums() {
  gradientProjected_.update(1.0, phi_, 1.0, beta_, 0.0);
  omega_.reducedFreeGradient(x_, phi_, alphaBar_, reduced_);
  const auto [gradientProjectedNorm2, betaNorm2, reducedPhi] =
      dots(gradientProjected_, gradientProjected_, beta_, beta_, reduced_, phi_);
  return {gradientProjectedNorm2, betaNorm2, reducedPhi};
}

}  // namespace tribos::qp
