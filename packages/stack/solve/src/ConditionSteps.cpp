#include "ConditionSteps.hpp"

#include <Teuchos_DefaultMpiComm.hpp>
#include <Teuchos_ParameterList.hpp>

#include <memory>
#include <optional>
#include <string>

#include "PairingUpdate.hpp"
#include "tribos/core/Errors.hpp"
#include "tribos/core/PhaseTimer.hpp"
#include "tribos/feti/Solvability.hpp"
#include "tribos/stack/LinearFetiSolve.hpp"
#include "tribos/stack/SubdomainSetup.hpp"

namespace tribos::stack {

using Displacement = std::vector<std::array<double, 3>>;

std::vector<ConditionRun> conditionRuns(const Scene& scene) {
  std::vector<ConditionRun> runs{{1, 1}};
  for (int k = 2; k <= scene.loadSteps; ++k) {
    bool same = true;
    for (const auto& active : scene.conditionActive)
      same = same && active[static_cast<size_t>(k - 1)] == active[static_cast<size_t>(k - 2)];
    if (same)
      runs.back().last = k;
    else
      runs.push_back({k, k});
  }
  return runs;
}

std::vector<int> heldSince(const Scene& scene, int k) {
  std::vector<int> since;
  for (const auto& active : scene.conditionActive) {
    if (!active[static_cast<size_t>(k - 1)]) {
      since.push_back(-1);
      continue;
    }
    int a = k;
    while (a > 1 && active[static_cast<size_t>(a - 2)]) --a;
    since.push_back(a - 1);
  }
  return since;
}

feti::ConstraintSpec constraintSpecAt(const Scene& scene, int first, const std::map<int, Displacement>& at) {
  feti::ConstraintSpec spec = constraintSpec(scene);
  spec.presentConditions.clear();
  for (int since : heldSince(scene, first)) {
    spec.presentConditions.push_back(since >= 0);
    spec.conditionBase.push_back(since > 0 ? &at.at(since) : nullptr);
  }
  return spec;
}

namespace {
/// Every step after which some condition takes hold: the states conditions hold their nodes at.
std::vector<int> holdingStates(const Scene& scene) {
  std::vector<int> states;
  for (const auto& run : conditionRuns(scene))
    for (int since : heldSince(scene, run.first))
      if (since > 0) states.push_back(since);
  return states;
}

/// Appends the steps of a solved run (its records, its earlier steps' results and its last
/// state's) and its counts to `done`.
void appendRun(const ContactSolveResult& run, ContactSolveResult& done) {
  done.steps.insert(done.steps.end(), run.steps.begin(), run.steps.end());
  done.earlierSteps.insert(done.earlierSteps.end(), run.earlierSteps.begin(), run.earlierSteps.end());
  done.earlierSteps.push_back(static_cast<const StepResults&>(run));
  addPartCounts(run, done);
  done.pairingUpdates.insert(done.pairingUpdates.end(), run.pairingUpdates.begin(), run.pairingUpdates.end());
}

/// The B of a run after the first: its conditions; with pairing updates, each slave node paired as
/// the state before it left the bodies (`previous`'s pairing unless x + u shows it wrong). Checked
/// for bodies left free (feti::requireRestrainedBodies: exit 2 naming them).
std::unique_ptr<feti::ConstraintMatrix> runRows(const Scene& scene, feti::ConstraintSpec spec,
                                                const ContactSolveResult& done, const feti::ConstraintMatrix& previous,
                                                MPI_Comm comm) {
  int rank = 0, numRanks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &numRanks);
  Displacement u;
  if (scene.pairingUpdates > 0 && !done.steps.empty()) {
    u = stepDisplacement(done, done.steps.size() - 1, scene.mesh.numNodes(), comm);
    spec.pairingDisplacement = &u;
    spec.solvedPairing = &previous;
  }
  core::ScopedPhase phase("Contact: rows of the switched conditions");  // the summary's timers
  auto rows = std::make_unique<feti::ConstraintMatrix>(
      feti::buildConstraintMatrix(scene.mesh, scene.decomposition, spec, numRanks, rank));
  const Teuchos::MpiComm<int> world(comm);
  feti::requireRestrainedBodies(scene.mesh, scene.decomposition, *rows, &world);
  return rows;
}
}  // namespace

namespace {
/// Before any solve: the B of every run after the first must hold every body (its conditions
/// alone decide that, not where they hold): a condition switched off that leaves a body free is
/// exit 2 naming the body and the step, before step 1 is solved rather than after.
void requireEveryRunRestrained(const Scene& scene, MPI_Comm comm) {
  int rank = 0, numRanks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &numRanks);
  const Teuchos::MpiComm<int> world(comm);
  for (const auto& run : conditionRuns(scene)) {
    if (run.first == 1) continue;  // the driver checked step 1's
    feti::ConstraintSpec spec = constraintSpec(scene);
    spec.presentConditions.clear();
    for (int since : heldSince(scene, run.first)) spec.presentConditions.push_back(since >= 0);
    const auto rows = feti::buildConstraintMatrix(scene.mesh, scene.decomposition, spec, numRanks, rank);
    try {
      feti::requireRestrainedBodies(scene.mesh, scene.decomposition, rows, &world);
    } catch (const core::InputError& e) {
      throw core::InputError("Load Steps: in steps " + std::to_string(run.first) + " to " + std::to_string(run.last) +
                             " (the displacement conditions switched by Active): " + e.what());
    }
  }
}
}  // namespace

ContactSolveResult solveConditionRuns(const ContactRun& contactRun, std::vector<fem::SubdomainSystem> owned,
                                      const feti::ConstraintMatrix& B) {
  const Scene& scene = contactRun.scene;
  MPI_Comm comm = contactRun.comm;
  const StepObserver& afterStep = contactRun.afterStep;
  requireEveryRunRestrained(scene, comm);
  const std::string restartFile = contactRun.tribos.sublist("Load Steps").get<std::string>("Restart From");
  std::map<int, Displacement> at;  // the states conditions hold their nodes at
  std::optional<RestartState> from;
  int firstStep = 1;
  if (!restartFile.empty()) {
    from = readRestartOnRoot(restartFile, scene, B, comm, holdingStates(scene));
    firstStep = from->step + 1;
    for (auto& [k, u] : from->displacements) at[k] = std::move(u);
    from->displacements.clear();
  }
  ContactSolveResult done, result;
  const StepObserver observe = !afterStep ? StepObserver() : [&](const ContactSolveResult& part) {
    observeAfter(done, part, afterStep);
  };
  std::unique_ptr<feti::ConstraintMatrix> rows;  // the run's B after the first
  for (const auto& run : conditionRuns(scene)) {
    if (run.last < firstStep) continue;
    const feti::ConstraintSpec spec = constraintSpecAt(scene, run.first, at);
    std::vector<fem::SubdomainSystem> systems;
    if (run.first == 1) {
      systems = std::move(owned);
    } else {
      rows = runRows(scene, spec, done, rows ? *rows : B, comm);
      assembleOwnedSubdomains(scene, comm, systems);  // the last run's went into its factors
      if (!done.steps.empty()) from = stateAfter(done, *rows, scene, comm);
    }
    const feti::ConstraintMatrix& runB = run.first == 1 ? B : *rows;
    const HistoryPart part{from ? &*from : nullptr, run.last, &spec};
    result = scene.pairingUpdates > 0
                 ? solveHistoryPairedAsItGoes(contactRun.observedBy(observe), std::move(systems), runB, part)
                 : solveOnePairing(contactRun.observedBy(observe), std::move(systems), runB, part);
    if (run.last == scene.loadSteps || !result.contact.converged) break;
    at[run.last] = stepDisplacement(result, result.earlierSteps.size(), scene.mesh.numNodes(), comm);
    appendRun(result, done);
    if (!afterStep) continue;
    afterStep(done);  // the run's last step, which its own observer does not see
    releaseWrittenSteps(done);
  }
  // The result: the steps of the runs before, then the last run's.
  prependSteps(done, result);
  result.pairingUpdates.insert(result.pairingUpdates.begin(), done.pairingUpdates.begin(), done.pairingUpdates.end());
  result.restartFile = restartFile;
  result.restartStep = restartFile.empty() ? 0 : firstStep - 1;
  return result;
}

}  // namespace tribos::stack
