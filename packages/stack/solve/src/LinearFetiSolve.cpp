#include "tribos/stack/LinearFetiSolve.hpp"
#include "tribos/stack/FetiSettings.hpp"

#include <Teuchos_DefaultMpiComm.hpp>
#include <Teuchos_ParameterList.hpp>
#include <Tpetra_Vector.hpp>

#include <cmath>
#include <sstream>

#include "tribos/core/PhaseTimer.hpp"
#include "tribos/core/Timer.hpp"
#include "tribos/contact/ContactSolver.hpp"
#include "tribos/stack/GlobalFields.hpp"
#include "tribos/stack/SolveBudget.hpp"
#include "tribos/feti/ProjectedCg.hpp"
#include "tribos/feti/TotalFeti.hpp"

namespace tribos::stack {

feti::ConstraintSpec constraintSpec(const Scene& scene) {
  feti::ConstraintSpec spec;
  spec.dirichletNodeSets = scene.dirichletNodeSets;
  spec.displacementConditions = scene.displacementConditions;
  spec.zeroComponents = scene.zeroComponents;
  // The conditions of step 1 (Load Steps/<name>/Active; later steps: ConditionSteps.hpp).
  for (const auto& active : scene.conditionActive) spec.presentConditions.push_back(active.front());
  for (const auto& one : scene.contacts) spec.interfaces.push_back(one.rows);
  return spec;
}

namespace {
// Why projected CG stopped, naming the limit that ended it when it did not converge.
std::string linearSolveMessage(const feti::ProjectedCgResult& solve, const feti::ProjectedCgSettings& cg,
                               const WallClockBudget& budget) {
  if (solve.converged) return "converged";
  std::ostringstream detail;
  detail << "(||P r||/||P h|| = " << solve.relativeResidual << ", tolerance " << cg.tolerance << ")";
  if (budget.ranOut()) return budget.message() + " " + detail.str();
  if (solve.iterations >= cg.maxIterations) return capMessage("FETI/Max Iterations", cg.maxIterations, detail.str());
  return "projected CG broke down: P F P is not positive on Ker G " + detail.str();
}
/// KKT of the discrete problem: equilibrium per subdomain, and B u = c, into `result`.
/// Relative to the largest force, applied or constraint (a scene without loads, driven by
/// prescribed displacements, has only the latter). Returns B u - c (the bonded interfaces'
/// fields read it).
Teuchos::RCP<feti::DualVector> kktResiduals(const feti::TotalFeti& feti, const feti::DualVector& lambda,
                                            const std::vector<std::vector<double>>& u, MPI_Comm comm,
                                            LinearFetiResult& result) {
  double forceScale = 0.0;
  const double equilibrium = feti.equilibriumResidual(lambda, u, &forceScale);
  result.equilibriumResidual = forceScale > 0.0 ? equilibrium / forceScale : equilibrium;
  auto Bu = feti.createDualVector();
  feti.applyB(u, *Bu);
  {
    auto data = Bu->getLocalViewHost(Tpetra::Access::ReadWrite);
    const auto& c = feti.ownedC();
    for (size_t i = 0; i < data.extent(0); ++i) data(i, 0) -= c[i];
  }
  double uNormLocal = 0.0;
  for (const auto& us : u)
    for (double v : us) uNormLocal += v * v;
  double uNorm = 0.0;
  MPI_Allreduce(&uNormLocal, &uNorm, 1, MPI_DOUBLE, MPI_SUM, comm);
  uNorm = std::sqrt(uNorm);
  result.constraintResidual = Bu->norm2() / (uNorm > 0.0 ? uNorm : 1.0);
  return Bu;
}
}  // namespace

LinearFetiResult solveLinearFeti(const Scene& scene, std::vector<fem::SubdomainSystem> owned,
                                 const feti::ConstraintMatrix& B, const Teuchos::ParameterList& fetiList,
                                 double tolerance, MPI_Comm comm, double maxSeconds, core::Stopwatch runStart) {
  LinearFetiResult result;
  const core::Deadline deadline(maxSeconds, runStart);
  WallClockBudget budget(deadline, comm);
  auto teuchosComm = Teuchos::rcp(new Teuchos::MpiComm<int>(comm));
  const int rank = teuchosComm->getRank();

  result.appliedLoad = totalLoad(owned, comm);
  result.appliedLoadMagnitude = loadMagnitude(owned, comm);

  feti::TotalFetiSettings settings = totalFetiSettings(fetiList, true);
  settings.deadline = &deadline;
  const feti::TotalFeti feti(scene.mesh, scene.decomposition, std::move(owned), B, teuchosComm, settings);
  result.factorizationSeconds = feti.factorizationSeconds();

  // Projected CG on P F P (paper Section 4.2), then alpha and u (ALGORITHMS.md 7).
  core::Stopwatch watch;
  feti::ProjectedCgSettings cg;
  cg.tolerance = tolerance;
  cg.maxIterations = fetiList.get<int>("Max Iterations");
  cg.preconditioner = dualPreconditioner(fetiList);
  cg.stopRequested = budget.stopRequest();
  auto lambda = feti.createDualVector();
  const auto solve = [&] {
    core::ScopedPhase phase("Linear: projected CG");
    return feti::solveProjectedCg(feti, *lambda, cg);
  }();
  core::ScopedPhase recovery("Linear: recovery and KKT");
  const auto alpha = feti.rigidBodyCoefficients(*lambda);
  const auto u = feti.recoverDisplacements(*lambda, alpha);
  result.solveSeconds = watch.seconds();
  result.converged = solve.converged;
  result.message = linearSolveMessage(solve, cg, budget);
  result.iterations = solve.iterations;
  result.relativeResidual = solve.relativeResidual;
  result.conditionEstimate = solve.conditionEstimate;
  result.fApplications = feti.fApplications();
  result.factorNonzeros = feti.factorNonzeros();
  result.bytesPerFApplication = feti.bytesPerFApplication();

  const auto Bu = kktResiduals(feti, *lambda, u, comm, result);

  // Global displacement = mean over the copies of a node; the spread of the copies is the
  // gluing error that a user sees.
  auto global = gatherDisplacement(scene, feti.firstOwnedSubdomain(), u, comm);
  result.displacement = std::move(global.value);
  result.maxCopyJump = global.maxCopyJump;
  // Reactions: -lambda of the prescribed-displacement rows, summed per node on rank 0.
  std::vector<double> ownedLambda;
  {
    const auto lam = lambda->getLocalViewHost(Tpetra::Access::ReadOnly);
    for (size_t i = 0; i < lam.extent(0); ++i) ownedLambda.push_back(lam(i, 0));
  }
  result.reaction = gatherReactions(scene, B, feti.eliminatedReactions(u), ownedLambda, comm);
  // Bonded interfaces: their forces are the contact rows' multipliers.
  if (!scene.contacts.empty()) {
    std::vector<double> residual;
    const auto r = Bu->getLocalViewHost(Tpetra::Access::ReadOnly);
    for (size_t i = 0; i < r.extent(0); ++i) residual.push_back(r(i, 0));
    gatherContactFields(scene, B, tiedNodeResults(B, rank, ownedLambda, residual), comm, result);
  }
  return result;
}

}  // namespace tribos::stack
