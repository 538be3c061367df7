// A load history paired again as it goes (issue 41; PairingUpdate.hpp): a joint that slides
// further than its pairs reach, a pin that crosses its clearance in step k. The history is solved
// on one pairing; its first converged step whose state changes the pairing is solved again from
// the step before it, on the pairing of that state, continuing in memory as a restart does
// (RestartState: the tangential displacement reached, measured with the new rows, the
// accumulated slip and the dissipated energies). Steps past that point are solved again.
#include <Teuchos_ParameterList.hpp>

#include <memory>
#include <optional>

#include "PairingUpdate.hpp"
#include "tribos/stack/LinearFetiSolve.hpp"
#include "tribos/stack/SubdomainSetup.hpp"

namespace tribos::stack {

namespace {
using Displacement = std::vector<std::array<double, 3>>;

/// Where a history's pairing changed: the index of the step in its result, the rows of that
/// step's state and the record.
struct PairingChangePoint {
  size_t index = 0;
  std::unique_ptr<feti::ConstraintMatrix> rows;
  PairingUpdateRecord record;
};

/// The first converged step of `result`, from `firstIndex` on, whose state changes the pairing
/// `rows`; none where every one keeps it (`standing` gets the last check's record).
std::optional<PairingChangePoint> firstChange(const Scene& scene, const feti::ConstraintSpec& spec,
                                              const ContactSolveResult& result, const feti::ConstraintMatrix& rows,
                                              size_t firstIndex, int update, MPI_Comm comm,
                                              PairingUpdateRecord& standing) {
  for (size_t i = firstIndex; i < result.steps.size() && result.steps[i].converged; ++i) {
    const Displacement u = stepDisplacement(result, i, scene.mesh.numNodes(), comm);
    standing = changesAt(scene, spec, u, rows, update);
    if (!standing.solvedAgain) continue;
    auto next = std::make_unique<feti::ConstraintMatrix>(rowsAt(scene, spec, u, rows, comm));
    standing.paired = static_cast<long long>(next->contact.size());
    return PairingChangePoint{i, std::move(next), standing};
  }
  return std::nullopt;
}


/// Moves the steps [0, count) of `result` (records and results) to the end of `done`, with the
/// counts of the solve that made them.
void keepSteps(ContactSolveResult& result, size_t count, ContactSolveResult& done) {
  for (size_t i = 0; i < count; ++i) {
    done.steps.push_back(result.steps[i]);
    done.earlierSteps.push_back(std::move(result.earlierSteps[i]));
  }
  done.fApplications += result.fApplications;
  done.factorizationSeconds += result.factorizationSeconds;
  done.solveSeconds += result.solveSeconds;
}

}  // namespace

Displacement stepDisplacement(const ContactSolveResult& result, size_t i, LO numNodes, MPI_Comm comm) {
  const bool earlier = i < result.earlierSteps.size();
  return onEveryRank(earlier ? result.earlierSteps[i].displacement.value : result.displacement.value, numNodes, comm);
}

void tangentialReached(const feti::ConstraintMatrix& rows, const Displacement& u, ContactFields& totals) {
  totals.contactTangentialT1.assign(u.size(), 0.0);
  totals.contactTangentialT2.assign(u.size(), 0.0);
  for (const auto& node : rows.contact) {
    double t1 = 0.0, t2 = 0.0;
    for (const auto& [n, w] : node.sides())
      for (int c = 0; c < 3; ++c) t1 += w * node.t1[c] * u[n][c], t2 += w * node.t2[c] * u[n][c];
    totals.contactTangentialT1[node.slaveNode] = t1;
    totals.contactTangentialT2[node.slaveNode] = t2;
  }
}

RestartState stateAfter(const ContactSolveResult& done, const feti::ConstraintMatrix& rows, const Scene& scene,
                        MPI_Comm comm) {
  RestartState state;
  state.file = "(in memory)";
  state.step = done.steps.back().step;
  state.totals = static_cast<const ContactFields&>(done.earlierSteps.back());
  tangentialReached(rows, stepDisplacement(done, done.steps.size() - 1, scene.mesh.numNodes(), comm), state.totals);
  for (const auto& section : done.steps.back().sections) state.sectionShortening.push_back(section.shortening);
  broadcastRestartState(state, scene, comm);
  return state;
}

ContactSolveResult solveHistoryPairedAsItGoes(const Scene& scene, std::vector<fem::SubdomainSystem> owned,
                                              const feti::ConstraintMatrix& B, const Teuchos::ParameterList& tribos,
                                              MPI_Comm comm, core::Stopwatch runStart, const StepObserver& afterStep,
                                              const HistoryPart& span) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const bool verbose = tribos.sublist("Solver").get<bool>("Verbose");
  const feti::ConstraintSpec spec = span.spec ? *span.spec : constraintSpec(scene);
  ContactSolveResult done;  // the steps before the pairing last changed
  const feti::ConstraintMatrix* rows = &B;  // the pairing the part is solved on
  // Checkpoints see the steps kept so far and the part now being solved, up to its first step
  // whose state changes the pairing: that step will be solved again, and no checkpoint holds it.
  bool stale = false;
  const StepObserver observe = !afterStep ? StepObserver() : [&](const ContactSolveResult& part) {
    if (stale) return;
    const Displacement u = stepDisplacement(part, part.earlierSteps.size() - 1, scene.mesh.numNodes(), comm);
    if ((stale = changesAt(scene, spec, u, *rows, 0).solvedAgain)) return;
    ContactSolveResult all = done;
    all.steps.insert(all.steps.end(), part.steps.begin(), part.steps.end());
    all.earlierSteps.insert(all.earlierSteps.end(), part.earlierSteps.begin(), part.earlierSteps.end());
    afterStep(all);
  };
  ContactSolveResult part = solveOnePairing(scene, std::move(owned), B, tribos, comm, runStart, observe, span);
  const std::string restartFile = part.restartFile;  // Load Steps/Restart From's, as the summary shows it
  const int restartStep = part.restartStep;
  std::unique_ptr<feti::ConstraintMatrix> held;
  std::optional<RestartState> from;  // the state `part` started from, when in memory
  if (span.continueFrom) from = *span.continueFrom;
  // A part restarted from a file checks from its second step on: the file's state is its own.
  size_t firstIndex = span.continueFrom || tribos.sublist("Load Steps").get<std::string>("Restart From").empty() ? 0 : 1;
  std::vector<PairingUpdateRecord> records;
  int changedStep = 0, atThatStep = 0;  // Pairing Updates counts the changes at one step
  for (int k = 1;; ++k) {
    PairingUpdateRecord standing{k};
    auto change = firstChange(scene, spec, part, *rows, firstIndex, k, comm, standing);
    if (change) {
      const int step = part.steps[change->index].step;
      atThatStep = step == changedStep ? atThatStep + 1 : 1;
      changedStep = step;
      if (atThatStep > scene.pairingUpdates) break;  // the check after the solve has the last word
    }
    records.push_back(change ? change->record : standing);
    reportUpdate(records.back(), rank, verbose);
    if (!change) break;
    keepSteps(part, change->index, done);
    held = std::move(change->rows);
    rows = held.get();
    if (!done.steps.empty()) from = stateAfter(done, *rows, scene, comm);
    std::vector<fem::SubdomainSystem> systems;
    assembleOwnedSubdomains(scene, comm, systems);
    stale = false;
    part = solveOnePairing(scene, std::move(systems), *rows, tribos, comm, runStart, observe,
                           {from ? &*from : nullptr, span.lastStep, &spec});
    firstIndex = 0;
  }
  // The result: the steps kept, then the last part's.
  part.steps.insert(part.steps.begin(), done.steps.begin(), done.steps.end());
  part.earlierSteps.insert(part.earlierSteps.begin(), std::make_move_iterator(done.earlierSteps.begin()),
                           std::make_move_iterator(done.earlierSteps.end()));
  part.fApplications += done.fApplications;
  part.factorizationSeconds += done.factorizationSeconds;
  part.solveSeconds += done.solveSeconds;
  part.restartFile = restartFile;
  part.restartStep = restartStep;
  part.pairingUpdates = std::move(records);
  return part;
}

}  // namespace tribos::stack
