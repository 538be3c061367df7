#include "tribos/qp/Mpgp.hpp"

#include <algorithm>
#include <cmath>

#include "MpgpRun.hpp"

namespace tribos::qp {

MpgpCounters Mpgp::solve(const SymmetricOperator& A, const Vector& b, const SeparableSet& omega, double normA,
                         Vector& x, Vector& g, const std::function<bool(double, const Vector&)>& stop,
                         bool gradientGiven) const {
  MpgpRun run(settings_, A, b, omega, normA, x, g);
  MpgpCounters& counters = run.counters;
  run.start(gradientGiven);
  for (;;) {
    const auto [gradientProjectedNorm2, betaNorm2, reducedPhi] = run.iterationSums();
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
    if (betaNorm2 <= settings_.gamma * settings_.gamma * reducedPhi)
      run.proportionalStep();
    else
      run.proportioningStep();
  }
  return counters;
}

}  // namespace tribos::qp
