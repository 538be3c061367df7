#include "tribos/contact/ContactSolver.hpp"

#include <algorithm>
#include <memory>

#include "ContactRecovery.hpp"
#include "DualContactProblem.hpp"
#include "SlipBoundStrategy.hpp"
#include "tribos/core/Errors.hpp"
#include "tribos/core/PhaseTimer.hpp"
#include "tribos/feti/DualOperators.hpp"

#include <Teuchos_TestForException.hpp>
#include <Tpetra_Vector.hpp>

#include <stdexcept>

namespace tribos::contact {

namespace {
/// The counters of the SMALSE-M runs of one solve, summed into ContactResult::counters; the
/// products with A of the earlier runs (exact Coulomb) are added to the progress reported.
class RunTally {
 public:
  explicit RunTally(qp::SmalseCounters& total) : total_(total) {}
  void add(const qp::SmalseCounters& k) {
    total_.outerIterations += k.outerIterations;
    total_.innerIterations += k.innerIterations;
    total_.cgSteps += k.cgSteps;
    total_.expansionSteps += k.expansionSteps;
    total_.proportioningSteps += k.proportioningSteps;
    total_.operatorApplications += k.operatorApplications;
    total_.preconditionerApplications += k.preconditionerApplications;
    total_.seconds += k.seconds;
    total_.operatorSeconds += k.operatorSeconds;
    total_.productSeconds += k.productSeconds;
    total_.preconditionerSeconds += k.preconditionerSeconds;
    applicationsBefore_ = total_.operatorApplications;
    total_.projectedGradient = k.projectedGradient;
    total_.equalityResidual = k.equalityResidual;
    total_.normA = k.normA;
    total_.converged = k.converged;
    total_.nonFinite = total_.nonFinite || k.nonFinite;
    total_.stalled = total_.stalled || k.stalled;
  }
  qp::SmalseProgress withEarlierRuns(qp::SmalseProgress p) const {
    p.operatorApplications += applicationsBefore_;
    return p;
  }

 private:
  qp::SmalseCounters& total_;
  long long applicationsBefore_ = 0;
};

/// SMALSE-M's settings for this solve: the preconditioner in face and the progress reports
/// (with the earlier runs' products and the slip bound's last change).
qp::SmalseSettings smalseSettingsFor(const qp::SmalseSettings& given, const FrictionSettings& friction,
                                     const qp::SymmetricOperator* preconditioner, const RunTally& tally,
                                     const DualContactProblem& problem, const ContactResult& result) {
  qp::SmalseSettings settings = given;
  if (preconditioner) settings.preconditioner = preconditioner;
  if (friction.overloaded)
    settings.stallConfirmed = [&friction, &problem](const qp::Vector& mu) {
      return friction.overloaded(problem.interfaceNormalForces(mu));
    };
  // A diverging Coulomb fixed point (SlipBoundStrategy) ends the run as a stop request does;
  // the flag is the same on every rank (the slip-bound change is global).
  settings.stopRequested = [stop = given.stopRequested, &result] {
    return result.fixedPointDiverged || (stop && stop());
  };
  if (friction.progress)
    settings.monitor = [&friction, &tally, &result](const qp::SmalseProgress& p) {
      friction.progress(tally.withEarlierRuns(p), result.fixedPointChange);
    };
  if (given.innerMonitor)
    settings.innerMonitor = [&given, &tally](const qp::SmalseProgress& p) {
      given.innerMonitor(tally.withEarlierRuns(p));
    };
  return settings;
}

/// More rounds of the inexact Coulomb fixed point, from where it stopped, when SMALSE-M
/// converged and every KKT residual but the stick rule holds: a node whose slip bound g was
/// still below F lambda_nu slid under g, and is inside Coulomb's cone by then (stick) while it
/// moved. Its global change passed the slip-bound test, but the fixed point had not settled
/// there. Measured: the normal step of the Cattaneo sphere at eps = 1e-7 (stick rule 1.7e-3)
/// and of the Cattaneo cylinder at 1e-6 (7.1e-4) ended not converged; with the rounds they
/// converge (the sphere's step in 2124 PFP, against 1311 to the failure), and the cylinder's
/// stick sizes and tractions at 1e-6 are those at 1e-7 to 3 digits.
constexpr int kStickRuleRounds = 3;

bool onlyTheStickRuleFailed(const FrictionSettings& friction, double kktTolerance, const ContactResult& result) {
  // "Paper" stops as the paper does, and the gate then judges it (doc/parameters.md): no rounds.
  if (!friction.successiveApproximations() || friction.fixedPoint != FixedPoint::Inexact ||
      friction.slipBoundTest != SlipBoundTest::Epsilon)
    return false;
  if (!result.counters.converged || result.counters.nonFinite) return false;
  const KktReport& k = result.kkt;
  for (double value : {k.equilibrium, k.equality, k.nonPenetration, k.complementarity, k.normalSign,
                       k.frictionAdmissibility, k.slipRule})
    if (!(value <= kktTolerance)) return false;
  return k.stickRule > kktTolerance;
}
}  // namespace

bool FrictionSettings::successiveApproximations() const {
  return std::any_of(laws.begin(), laws.end(), [](const FrictionLaw& law) { return law.boundFollowsNormalForce(); });
}

ContactResult solveContact(const feti::TotalFeti& feti, const feti::ConstraintMatrix& B,
                           const FrictionSettings& friction, const qp::SmalseSettings& smalseSettings,
                           feti::DualPreconditioner preconditioner, const WarmStart& warm) {
  const std::vector<double>& initialLambda = warm.lambda;
  ContactResult result;
  // (1), (2) The homogenised dual problem (paper (19)) and Omega(g) (DualContactProblem).
  DualContactProblem problem(feti, B, friction);

  // (3) Solve: SMALSE-M runs on A = P F P and Q = I - P, the slip bound found as the friction
  // law asks (SlipBoundStrategy).
  const double eps = smalseSettings.tolerance;
  // Every KKT residual of the result must be below this for "converged" (step (6)); the
  // status tests use it as their relative tolerance too.
  const double kktTolerance = std::max(100.0 * eps, 1e-8);
  const feti::ProjectedDualOperator A(feti);
  const feti::CoarseSpaceProjector Q(feti);
  std::unique_ptr<feti::ProjectedDualPreconditioner> M;
  if (preconditioner != feti::DualPreconditioner::None)
    M = std::make_unique<feti::ProjectedDualPreconditioner>(feti, preconditioner);
  RunTally tally(result.counters);
  qp::SmalseSettings settings = smalseSettingsFor(smalseSettings, friction, M.get(), tally, problem, result);
  settings.rightHandSideScale = problem.stoppingScale();
  const qp::SmalseM smalse(settings);
  auto mu = feti.createDualVector();
  mu->putScalar(0.0);
  if (!initialLambda.empty()) {  // its own scope: the views end before impliedSlip reads mu
    // A warm start (a load step from the last): mu = lambda - lambda_Im, g from its lambda_nu.
    auto m = mu->getLocalViewHost(Tpetra::Access::ReadWrite);
    const auto lIm = feti.lambdaIm().getLocalViewHost(Tpetra::Access::ReadOnly);
    TEUCHOS_TEST_FOR_EXCEPTION(initialLambda.size() != m.extent(0), std::invalid_argument,
                               "tribos::contact::solveContact: the initial lambda has " << initialLambda.size()
                                   << " values for " << m.extent(0) << " owned rows");
    for (size_t i = 0; i < m.extent(0); ++i) m(i, 0) = initialLambda[i] - lIm(i, 0);
  }
  if (!initialLambda.empty() && friction.successiveApproximations()) problem.setSlipBounds(problem.impliedSlip(*mu));
  const SmalseRun run = [&](const qp::OuterHook& hook, double knownNormA) {
    if (!(knownNormA > 0.0)) knownNormA = warm.normA;
    tally.add(smalse.solve(A, Q, problem.rightHandSide(), problem.omega(), *mu, hook, knownNormA));
  };
  const auto strategy = makeSlipBoundStrategy(friction, problem.hasCoulombNodes(), eps, kktTolerance);
  for (int round = 0;; ++round) {
    {
      core::ScopedPhase phase("Contact: SMALSE-M");
      strategy->solve(run, problem, *mu, result);
    }
    if (result.counters.nonFinite) {
      result.converged = false;
      result.message = "diverged: non-finite values (NaN or Inf) in the dual iterations; check the loads, the "
                       "materials and Solver parameters for non-finite or extreme values";
    }
    // (4) lambda = mu + lambda_Im; alpha over the rows where the dual constraints are inactive
    // (ALGORITHMS.md 7); u = K^dagger (f - B^T lambda) + R alpha.
    core::ScopedPhase phase("Contact: recovery and KKT");
    result.lambda.clear();  // a later round recovers and reports afresh
    result.nodes.clear();
    result.statusCounts = {0, 0, 0};
    result.note.clear();
    result.kkt = {};
    const auto recovered = recoverPrimal(feti, B, problem, *mu, kktTolerance, result);
    // (5) KKT residuals of the discrete problem and the contact status per node.
    reportKkt(feti, B, problem, recovered, result);
    // (6) "Converged" only if the discrete KKT conditions hold too (to max(100 eps, 1e-8)).
    gateOnKkt(kktTolerance, result);
    if (result.converged || round >= kStickRuleRounds || !onlyTheStickRuleFailed(friction, kktTolerance, result)) break;
  }
  return result;
}

}  // namespace tribos::contact
