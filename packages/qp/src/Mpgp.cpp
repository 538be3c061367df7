#include "tribos/qp/Mpgp.hpp"

#include <Tpetra_Vector.hpp>

#include <algorithm>
#include <cmath>

namespace tribos::qp {

MpgpCounters Mpgp::solve(const SymmetricOperator& A, const Vector& b, const SeparableSet& omega, double normA,
                         Vector& x, Vector& g, const std::function<bool(double, const Vector&)>& stop) const {
  MpgpCounters counters;
  const auto map = x.getMap();
  Vector phi(map), beta(map), p(map), Ap(map), reduced(map), gradientProjected(map), trial(map), trialGradient(map);
  const double alphaBar = settings_.stepScale / normA;

  // g = A x - b after any change of x that is not a CG-type update.
  auto gradient = [&]() {
    A.apply(x, g);
    ++counters.operatorApplications;
    g.update(-1.0, b, 1.0);
  };
  // Gradient projection step x = P(x - alpha_bar g) (proportioning, and the fallback when A
  // is not positive along p).
  auto gradientProjectionStep = [&]() {
    x.update(-alphaBar, g, 1.0);
    omega.project(x);
    gradient();
    omega.splitGradient(x, g, phi, beta);
    p.assign(phi);
    ++counters.proportioningSteps;
  };
  auto projectedGradientNorm = [&]() {
    gradientProjected.update(1.0, phi, 1.0, beta, 0.0);
    return gradientProjected.norm2();
  };

  omega.project(x);
  gradient();
  omega.splitGradient(x, g, phi, beta);
  p.assign(phi);
  for (;;) {
    counters.projectedGradientNorm = projectedGradientNorm();
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
    omega.reducedFreeGradient(x, phi, alphaBar, reduced);
    const double betaNorm2 = beta.dot(beta);
    const double proportion = settings_.gamma * settings_.gamma * reduced.dot(phi);
    if (betaNorm2 <= proportion) {
      A.apply(p, Ap);
      ++counters.operatorApplications;
      const double pAp = p.dot(Ap);
      if (!(pAp > 0.0)) {  // p = 0 or A not positive on p: fall back to a gradient projection
        gradientProjectionStep();
        continue;
      }
      const double alphaCg = g.dot(p) / pAp;
      const double alphaFeasible = omega.maxFeasibleStep(x, p);
      if (alphaCg <= alphaFeasible) {
        // Conjugate gradient step on the current face.
        x.update(-alphaCg, p, 1.0);
        g.update(-alphaCg, Ap, 1.0);
        omega.splitGradient(x, g, phi, beta);
        const double gammaCg = phi.dot(Ap) / pAp;
        p.update(1.0, phi, -gammaCg);
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
          const double phiAphi = phi.dot(Ap);
          const double alphaOpt = phiAphi > 0.0 ? phi.dot(phi) / phiAphi : 0.0;
          if (alphaOpt > alphaBar) {
            reduced.update(1.0, g, -1.0, b, 0.0);
            const double fHalf = 0.5 * x.dot(reduced);
            trial.update(1.0, x, -alphaOpt, phi, 0.0);
            omega.project(trial);
            A.apply(trial, trialGradient);
            ++counters.operatorApplications;
            trialGradient.update(-1.0, b, 1.0);
            reduced.update(1.0, trialGradient, -1.0, b, 0.0);
            if (0.5 * trial.dot(reduced) <= fHalf) {
              x.assign(trial);
              g.assign(trialGradient);
              omega.splitGradient(x, g, phi, beta);
              p.assign(phi);
              ++counters.expansionSteps;
              continue;
            }
          }
        }
        x.update(-alphaBar, phi, 1.0);
        omega.project(x);
        gradient();
        omega.splitGradient(x, g, phi, beta);
        p.assign(phi);
        ++counters.expansionSteps;
      }
    } else {
      // Proportioning: release the constraints with a gradient projection step.
      gradientProjectionStep();
    }
  }
  return counters;
}

}  // namespace tribos::qp
