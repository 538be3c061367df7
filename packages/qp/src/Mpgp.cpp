#include "tribos/qp/Mpgp.hpp"

#include <Tpetra_Vector.hpp>

#include <algorithm>
#include <cmath>

#include "tribos/qp/Reductions.hpp"

namespace tribos::qp {

MpgpCounters Mpgp::solve(const SymmetricOperator& A, const Vector& b, const SeparableSet& omega, double normA,
                         Vector& x, Vector& g, const std::function<bool(double, const Vector&)>& stop) const {
  MpgpCounters counters;
  const auto map = x.getMap();
  Vector phi(map), beta(map), p(map), Ap(map), reduced(map), gradientProjected(map), trial(map), trialGradient(map);
  Vector z(map), zFull(map), scratch(map);
  const double alphaBar = settings_.stepScale / normA;

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
    omega.splitGradient(x, zFull, z, scratch);
  };
  // After a step that is not a CG step: a fresh search direction.
  auto restartDirection = [&]() {
    preconditionedFreeGradient();
    p.assign(z);
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
  // Gradient projection step x = P(x - alpha g) (proportioning, and the fallback when A
  // is not positive along p).
  auto gradientProjectionStep = [&]() {
    projectedStep(g);
    omega.splitGradient(x, g, phi, beta);
    restartDirection();
    ++counters.proportioningSteps;
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
      omega.splitGradient(x, g, phi, beta);
      restartDirection();
      ++counters.proportioningSteps;
      return;
    }
    x.assign(previousX);
    g.assign(previousG);
    omega.splitGradient(x, g, phi, beta);
    gradientProjectionStep();
  };
  // ||g^P||^2 and the proportioning test's ||beta||^2 and phi~^T phi in one reduction
  // (Reductions.hpp: the bits of three separate ones).
  auto iterationSums = [&]() {
    gradientProjected.update(1.0, phi, 1.0, beta, 0.0);
    omega.reducedFreeGradient(x, phi, alphaBar, reduced);
    return dots(gradientProjected, gradientProjected, beta, beta, reduced, phi);
  };

  omega.project(x);
  gradient();
  omega.splitGradient(x, g, phi, beta);
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
      A.apply(p, Ap);
      ++counters.operatorApplications;
      const auto [pAp, gTp] = dots(p, Ap, g, p);  // one reduction for both
      if (!(pAp > 0.0)) {  // p = 0 or A not positive on p: fall back to a gradient projection
        gradientProjectionStep();
        continue;
      }
      const double alphaCg = gTp / pAp;
      const double alphaFeasible = omega.maxFeasibleStep(x, p);
      if (alphaCg <= alphaFeasible) {
        // Conjugate gradient step on the current face.
        x.update(-alphaCg, p, 1.0);
        if (settings_.cgStep) settings_.cgStep(alphaCg, p);
        g.update(-alphaCg, Ap, 1.0);
        omega.splitGradient(x, g, phi, beta);
        preconditionedFreeGradient();
        const double gammaCg = dot(z, Ap) / pAp;
        p.update(1.0, z, -gammaCg);
        ++counters.cgSteps;
      } else {
        // Expansion: to the boundary, then a projected step with the free gradient.
        x.update(-alphaFeasible, p, 1.0);
        g.update(-alphaFeasible, Ap, 1.0);
        omega.project(x);  // absorb round-off of the step onto the boundary
        omega.splitGradient(x, g, phi, beta);
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
              omega.splitGradient(x, g, phi, beta);
              restartDirection();
              ++counters.expansionSteps;
              continue;
            }
          }
        }
        projectedStep(phi);
        omega.splitGradient(x, g, phi, beta);
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
