#pragma once
// Internal to contact/: how the slip bound g of the friction law is found (step (3) of
// solveContact; paper (7), (20); ALGORITHMS.md 6). A strategy solves for mu by SMALSE-M runs
// and changes the problem's slip bounds between them, or between outer iterations of one run.
// Load steps and several friction laws per scene plug in here: a strategy sees the problem
// only through DualContactProblem (its bounds, the bound mu implies, the change of g).
#include <functional>
#include <memory>

#include "DualContactProblem.hpp"

namespace tribos::contact {

/// One SMALSE-M run from the current mu on the current Omega, its counters added to the
/// result's; `hook` is called after every outer iteration (qp::OuterHook), `knownNormA` > 0
/// skips the norm estimate.
using SmalseRun = std::function<void(const qp::OuterHook& hook, double knownNormA)>;

class SlipBoundStrategy {
 public:
  virtual ~SlipBoundStrategy() = default;
  /// Solves for mu (in place); sets result.converged and result.message, and with Coulomb
  /// result.fixedPointIterations and result.fixedPointChange. Collective.
  virtual void solve(const SmalseRun& run, DualContactProblem& problem, qp::Vector& mu,
                     ContactResult& result) const = 0;
};

/// The strategy of `friction`: a fixed bound (no Coulomb node: one run), Coulomb inexact (g
/// updated between the outer iterations of one run) or exact (a run per Tresca problem).
/// `coulombNodes`: some contact node follows Coulomb's law (DualContactProblem::hasCoulombNodes).
/// `eps`: SMALSE-M's tolerance; `kktTolerance`: the acceptance test's (solveContact (6)).
std::unique_ptr<SlipBoundStrategy> makeSlipBoundStrategy(const FrictionSettings& friction, bool coulombNodes,
                                                         double eps, double kktTolerance);

}  // namespace tribos::contact
