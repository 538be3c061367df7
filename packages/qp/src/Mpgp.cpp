#include "tribos/qp/Mpgp.hpp"

#include <Tpetra_Vector.hpp>

#include <algorithm>
#include <climits>
#include <cmath>

#include "tribos/qp/Reductions.hpp"

namespace tribos::qp {

MpgpCounters Mpgp::solve(const SymmetricOperator& A, const Vector& b, const SeparableSet& omega, double normA,
                         Vector& x, Vector& g, const std::function<bool(double, const Vector&)>& stop,
                         bool gradientGiven) const {
  MpgpCounters counters;
  const auto map = x.getMap();
  Vector phi(map), beta(map), p(map), Ap(map), reduced(map), gradientProjected(map), trial(map), trialGradient(map);
  Vector z(map), zFull(map), scratch(map);
  const double alphaBar = settings_.stepScale / normA;
  // Tangent CG is switched on once this inner solve has taken `tangentCgAfter` proportioning
  // steps (the crawl it is for: CG on a face that holds the friction multipliers, interrupted by
  // proportioning steps that turn them); before, a CG step costs one product with A, not two.
  // A slide that fails to decrease f (a step too long for the linearised face, or round-off in
  // the normals near the solution) switches it off for twice as many proportioning steps as
  // the previous failure did (tangentCgAfter, at least 1, the first time): near round-off the
  // slides fail every few steps, and without the back-off MPGP alternated between them and
  // gradient projection steps without converging (a random QP with tangent CG from the start).
  int slideFrom = settings_.tangentCgAfter, failedSlides = 0;
  bool slide = settings_.tangentCg && slideFrom == 0;
  // phi and beta of a gradient; with tangent CG the active ellipse blocks are free along their tangent.
  auto split = [&](const Vector& at, const Vector& gradientAt, Vector& free, Vector& chopped) {
    omega.splitGradient(at, gradientAt, free, chopped, slide);
  };

  // g = A x - b after any change of x that is not a CG-type update.
  auto gradient = [&]() {
    A.apply(x, g);
    ++counters.operatorApplications;
    g.update(-1.0, b, 1.0);
  };
  // z = chi_F M^-1 phi (preconditioning in face; z = phi without a preconditioner): the
  // restriction to the face keeps CG on it, and z^T phi = phi^T M^-1 phi > 0 keeps z a
  // descent direction. splitGradient's free part of M^-1 phi is exactly that restriction.
  const SymmetricOperator* M = settings_.preconditioner;
  auto preconditionedFreeGradient = [&]() {
    if (!M) {
      z.assign(phi);
      return;
    }
    M->apply(phi, zFull);
    ++counters.preconditionerApplications;
    split(x, zFull, z, scratch);
  };
  // The search direction after a step is used only if the next step starts from it (a CG step
  // or an expansion, both from the product A p), so it is made there (resolveDirection): a
  // proportioning step, or the end of the inner solve, then costs no preconditioner
  // application (with its two projections). It is made from the same phi at the same x as it
  // would have been at once: the same bits. Nothing writes Ap or trialGradient between a CG
  // step and the next step's start, so the product the conjugation needs is still there.
  enum class Direction { Current, Restart, Conjugate } direction = Direction::Current;
  const Vector* conjugateProduct = &Ap;  // (A + H_c) p of the CG step that left Conjugate
  double conjugateCurvature = 0.0;       // its p^T (A + H_c) p
  // After a step that is not a CG step: a fresh search direction, p = z.
  auto restartDirection = [&]() { direction = Direction::Restart; };
  // After a CG step: p = z - gamma p, gamma = z^T (A + H_c) p / p^T (A + H_c) p.
  auto conjugateDirection = [&](const Vector& product, double curvature) {
    direction = Direction::Conjugate;
    conjugateProduct = &product;
    conjugateCurvature = curvature;
  };
  auto resolveDirection = [&]() {
    if (direction == Direction::Current) return;
    preconditionedFreeGradient();
    if (direction == Direction::Restart) {
      p.assign(z);
    } else {
      const double gammaCg = dot(z, *conjugateProduct) / conjugateCurvature;
      p.update(1.0, z, -gammaCg);
    }
    direction = Direction::Current;
  };
  // Saved iterate and gradient, to undo a step that did not decrease f.
  Vector previousX(map), previousG(map);
  int proportioningRun = 0;  // consecutive proportioning steps so far
  // f(x) = 1/2 x^T A x - b^T x = 1/2 x^T (g - b), free given g.
  auto objective = [&](const Vector& at, const Vector& gradientAt) {
    trial.update(1.0, gradientAt, -1.0, b, 0.0);
    return 0.5 * dot(at, trial);
  };
  // x := P(x - alpha_bar d), then g.
  auto projectedStep = [&](const Vector& direction) {
    x.update(-alphaBar, direction, 1.0);
    omega.project(x);
    gradient();
  };
  // Tangent CG on from the proportioning step slideFrom on: phi, beta and p in its split.
  auto startSliding = [&]() {
    if (slide || !settings_.tangentCg || counters.proportioningSteps < slideFrom) return;
    slide = true;
    split(x, g, phi, beta);
    restartDirection();
  };
  // Gradient projection step x = P(x - alpha g) (proportioning, and the fallback when A
  // is not positive along p).
  auto gradientProjectionStep = [&]() {
    projectedStep(g);
    split(x, g, phi, beta);
    restartDirection();
    ++counters.proportioningSteps;
    startSliding();
  };
  // MPRGP's proportioning step: the exact minimiser along the chopped gradient,
  // x := P(x - alpha beta) with alpha = beta^T g / beta^T A beta (= ||beta||^2 / beta^T A beta).
  // On bounds the step is feasible as it stands and g follows from A beta; on an ellipse -beta
  // is tangent to it and the projection brings x back, so g is recomputed. Where A is soft
  // along beta (a multiplier turning on a friction ellipse, coupled weakly), the fixed
  // alpha_bar = 1.9/||A|| step turns it by a fraction of what is needed: measured on a Hertz
  // cylinder, 27 000 consecutive proportioning steps. Kept only if f decreases (else the
  // gradient projection step).
  auto choppedGradientStep = [&]() {
    A.apply(beta, Ap);
    ++counters.operatorApplications;
    // The second derivative along the arc: beta^T A beta plus what the curved boundary adds.
    const auto [betaAp, betaNorm2] = dots(beta, Ap, beta, beta);
    const double betaAbeta = betaAp + omega.boundaryCurvature(x, g, beta);
    // Only where alpha_bar is too short for it: a shorter exact step (e.g. at the sharp end of
    // a flat ellipse) does less than the gradient projection step, which moves the free part too.
    const double alpha = betaAbeta > 0.0 ? betaNorm2 / betaAbeta : 0.0;
    if (!(alpha > alphaBar)) {
      gradientProjectionStep();
      return;
    }
    const double f0 = objective(x, g);
    previousX.assign(x);
    previousG.assign(g);
    x.update(-alpha, beta, 1.0);
    trial.assign(x);
    omega.project(x);
    trial.update(1.0, x, -1.0);
    if (trial.normInf() == 0.0) {
      g.update(-alpha, Ap, 1.0);  // the projection did not move x: g = A x - b exactly
    } else {
      gradient();
    }
    // Kept if it achieves half the decrease alpha/2 ||beta||^2 of the exact step on a flat
    // boundary (a clear margin: a bare f < f0 would be decided by round-off when the projection
    // eats the step, and the choice would differ between rank layouts).
    if (objective(x, g) <= f0 - 0.25 * alpha * betaNorm2) {
      split(x, g, phi, beta);
      restartDirection();
      ++counters.proportioningSteps;
      startSliding();
      return;
    }
    x.assign(previousX);
    g.assign(previousG);
    split(x, g, phi, beta);
    gradientProjectionStep();
  };
  // Tangent CG (linearised face): the CG step moves active ellipse blocks along their tangent;
  // projected back onto the boundary, x is no longer x - alpha p, so g is recomputed (one more
  // product with A) and conjugacy holds only approximately. Kept if f decreased, else false
  // (x and g restored) and the caller takes a gradient projection step. True without a projection
  // correction too (then it is the plain CG step).
  auto slidingCgStep = [&](double alphaCg, double pAp) {
    previousX.assign(x);
    previousG.assign(g);
    x.update(-alphaCg, p, 1.0);
    trial.assign(x);
    omega.project(x);
    trial.update(1.0, x, -1.0);
    if (trial.normInf() == 0.0) {
      if (settings_.cgStep) settings_.cgStep(alphaCg, p);
      g.update(-alphaCg, Ap, 1.0);
    } else {
      gradient();
      // f(x) - f(x0) = (x - x0)^T (g + g0) / 2 exactly for a quadratic: from the step, free of
      // the cancellation in 1/2 x^T (g - b), which decided the test by round-off near the
      // solution (cylinder h0.05: f = -42.6, 8 of 16 slides "failed" with f - f0 between 2e-11
      // and 4e-10; with the difference 1 of 29 fails, and the run needs 1 548 F, not 14 442).
      trial.update(1.0, x, -1.0, previousX, 0.0);
      gradientProjected.update(1.0, g, 1.0, previousG, 0.0);
      const double change = 0.5 * dot(trial, gradientProjected);
      if (!(change < 0.0)) {
        x.assign(previousX);
        g.assign(previousG);
        slide = false;
        const long long wait = static_cast<long long>(std::max(settings_.tangentCgAfter, 1)) << std::min(failedSlides++, 20);
        slideFrom = static_cast<int>(std::min<long long>(counters.proportioningSteps + wait, INT_MAX));
        return false;
      }
    }
    split(x, g, phi, beta);
    conjugateDirection(trialGradient, pAp);  // trialGradient: (A + H_c) p
    ++counters.cgSteps;
    return true;
  };
  // ||g^P||^2 and the proportioning test's ||beta||^2 and phi~^T phi in one reduction
  // (Reductions.hpp: the bits of three separate ones).
  auto iterationSums = [&]() {
    gradientProjected.update(1.0, phi, 1.0, beta, 0.0);
    omega.reducedFreeGradient(x, phi, alphaBar, reduced);
    return dots(gradientProjected, gradientProjected, beta, beta, reduced, phi);
  };

  if (gradientGiven) {
    // g = A x - b for this x: kept unless the projection moves x (one reduction decides it
    // on every rank alike).
    previousX.assign(x);
    omega.project(x);
    trial.update(1.0, x, -1.0, previousX, 0.0);
    if (trial.normInf() != 0.0) gradient();
  } else {
    omega.project(x);
    gradient();
  }
  split(x, g, phi, beta);
  restartDirection();
  for (;;) {
    const auto [gradientProjectedNorm2, betaNorm2, reducedPhi] = iterationSums();
    counters.projectedGradientNorm = std::sqrt(gradientProjectedNorm2);
    // A NaN would fail every comparison and loop to the iteration cap: stop at once (the
    // norm is a global reduction, so every rank stops at the same iteration).
    if (!std::isfinite(counters.projectedGradientNorm)) {
      counters.nonFinite = true;
      break;
    }
    if (stop(counters.projectedGradientNorm, x)) {
      counters.converged = true;
      break;
    }
    if (counters.iterations >= settings_.maxIterations) break;
    // Every rank reaches this point at the same iteration: the callback stays collective-safe.
    const int every = std::max(settings_.progressEvery, 1);
    if (settings_.progress && counters.iterations > 0 && counters.iterations % every == 0) settings_.progress(counters);
    ++counters.iterations;

    // Proportional iterate: the chopped gradient is small against the reduced free one.
    const double proportion = settings_.gamma * settings_.gamma * reducedPhi;
    if (betaNorm2 <= proportion) {
      proportioningRun = 0;
      resolveDirection();
      A.apply(p, Ap);
      ++counters.operatorApplications;
      // Tangent CG: the Hessian on the curved face adds the boundary's curvature term.
      if (slide) {
        trialGradient.assign(Ap);
        omega.addCurvatureProduct(x, g, p, trialGradient);
      }
      const auto [pAp, gTp] = dots(p, slide ? trialGradient : Ap, g, p);  // one reduction for both
      if (!(pAp > 0.0)) {  // p = 0 or A not positive on p: fall back to a gradient projection
        gradientProjectionStep();
        continue;
      }
      const double alphaCg = gTp / pAp;
      const double alphaFeasible = omega.maxFeasibleStep(x, p, slide);
      if (slide && alphaCg <= alphaFeasible) {
        if (!slidingCgStep(alphaCg, pAp)) gradientProjectionStep();
        continue;
      }
      if (alphaCg <= alphaFeasible) {
        // Conjugate gradient step on the current face.
        x.update(-alphaCg, p, 1.0);
        if (settings_.cgStep) settings_.cgStep(alphaCg, p);
        g.update(-alphaCg, Ap, 1.0);
        split(x, g, phi, beta);
        conjugateDirection(Ap, pAp);
        ++counters.cgSteps;
      } else {
        // Expansion: to the boundary, then a projected step with the free gradient.
        x.update(-alphaFeasible, p, 1.0);
        g.update(-alphaFeasible, Ap, 1.0);
        omega.project(x);  // absorb round-off of the step onto the boundary
        split(x, g, phi, beta);
        if (settings_.optimalExpansion) {
          // Projected step with the exact minimiser along -phi (one more product with A),
          // kept only if it decreases f (monotonicity safeguard); else the fixed alpha_bar.
          A.apply(phi, Ap);
          ++counters.operatorApplications;
          const auto [phiAphi, phiPhi] = dots(phi, Ap, phi, phi);
          const double alphaOpt = phiAphi > 0.0 ? phiPhi / phiAphi : 0.0;
          if (alphaOpt > alphaBar) {
            reduced.update(1.0, g, -1.0, b, 0.0);
            const double fHalf = 0.5 * dot(x, reduced);
            trial.update(1.0, x, -alphaOpt, phi, 0.0);
            omega.project(trial);
            A.apply(trial, trialGradient);
            ++counters.operatorApplications;
            trialGradient.update(-1.0, b, 1.0);
            reduced.update(1.0, trialGradient, -1.0, b, 0.0);
            if (0.5 * dot(trial, reduced) <= fHalf) {
              x.assign(trial);
              g.assign(trialGradient);
              split(x, g, phi, beta);
              restartDirection();
              ++counters.expansionSteps;
              continue;
            }
          }
        }
        projectedStep(phi);
        split(x, g, phi, beta);
        restartDirection();
        ++counters.expansionSteps;
      }
    } else {
      // Proportioning: release the constraints. A gradient projection step first; when the
      // chopped gradient still dominates right after one, it is stiff for alpha_bar: the
      // exact step along it.
      if (settings_.choppedProportioning && proportioningRun > 0)
        choppedGradientStep();
      else
        gradientProjectionStep();
      ++proportioningRun;
    }
  }
  return counters;
}

}  // namespace tribos::qp
