#include "tribos/qp/SmalseM.hpp"

#include <Tpetra_Vector.hpp>

#include <algorithm>
#include <cmath>
#include <memory>

#include "SmalseRun.hpp"
#include "tribos/qp/Reductions.hpp"

namespace tribos::qp {

double EqualityProjector::normQ(const Vector& x, Vector& scratch) const {
  applyQ(x, scratch);
  return norm2(scratch);
}

double normEstimateToleranceFor(const SmalseSettings& s) {
  // ||A_rho|| = max(||A||, rho ||A||_est): from rho = 2 on the second term bounds it for any
  // estimate above half of ||A||, so the estimate sets only the scale of rho, M_0 and the
  // equality test, and a looser Lanczos stop (measured: 1e-3 against 1e-4 saves 5-15 products on
  // the bricks, doc/parameters.md) is safe. Below, alpha_bar depends on ||A|| itself.
  return s.rho >= 2.0 ? s.normEstimateTolerance : std::min(s.normEstimateTolerance, 1e-4);
}

SmalseCounters SmalseM::solve(const SymmetricOperator& A, const EqualityProjector& rawQ, const Vector& c,
                              SeparableSet& omega, Vector& mu, const OuterHook& hook, double knownNormA) const {
  SmalseRun run(settings_, A, rawQ, c, omega, mu);
  if (run.scale(knownNormA)) run.iterate(hook);
  return run.finish();
}

}  // namespace tribos::qp
