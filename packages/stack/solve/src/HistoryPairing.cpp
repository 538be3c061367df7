// A load history paired again as it goes (issue 41; PairingUpdate.hpp): a joint that slides
// further than its pairs reach, a pin that crosses its clearance in step k. Each converged step
// is checked as it is reached; the first whose state changes the pairing ends the part being
// solved (HistoryPart::stopWhen) and is solved again from the step before it, on the pairing of
// that state, continuing in memory as a restart does (RestartState: the tangential displacement
// reached, measured with the new rows, the accumulated slip and the dissipated energies).
#include <Teuchos_ParameterList.hpp>

#include <functional>
#include <memory>
#include <optional>

#include "PairingUpdate.hpp"

#include "tribos/feti/CarriedMultipliers.hpp"
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


/// The multipliers a part starts from and the step whose end they hold (HistoryPart::startLambda).
struct StartMultipliers {
  std::vector<double> lambda;
  int step = 0;
};

/// A step solved again on the pairing `next` starts from its own multipliers on `rows`, carried
/// to `next`: held only where it is the last state of `part` (none otherwise: cold).
StartMultipliers startAfterChange(const ContactSolveResult& part, size_t index, const feti::ConstraintMatrix& rows,
                                  const feti::ConstraintMatrix& next, MPI_Comm comm) {
  if (index + 1 != part.steps.size()) return {};
  return {feti::carryMultipliers(rows, part.contact.lambda, next, comm), part.steps.back().step};
}

/// Moves the steps [0, count) of `result` (records and results) to the end of `done`, with the
/// counts of the solve that made them.
void keepSteps(ContactSolveResult& result, size_t count, ContactSolveResult& done) {
  for (size_t i = 0; i < count; ++i) {
    done.steps.push_back(result.steps[i]);
    done.earlierSteps.push_back(std::move(result.earlierSteps[i]));
  }
  addPartCounts(result, done);
}

/// Moves every step of `result` (its earlier steps and its last state) to the end of `done`,
/// with the counts of the solve that made them.
void keepAllSteps(ContactSolveResult& result, ContactSolveResult& done) {
  keepSteps(result, result.earlierSteps.size(), done);
  done.steps.push_back(result.steps.back());
  done.earlierSteps.push_back(static_cast<const StepResults&>(result));
}

/// The pairing check of the last converged step of a part being solved, once per step: whether
/// the state changes the pairing `rows` (from the part's step `firstIndex` on).
struct StepCheck {
  const Scene& scene;
  const feti::ConstraintSpec& spec;
  const feti::ConstraintMatrix*& rows;
  size_t firstIndex;
  MPI_Comm comm;
  long long checked = -1;
  bool changed = false;

  bool changes(const ContactSolveResult& part) {
    const long long i = static_cast<long long>(part.earlierSteps.size()) - 1;
    if (i == checked) return changed;
    checked = i;
    changed = i >= static_cast<long long>(firstIndex) &&
              changesAt(scene, spec, stepDisplacement(part, static_cast<size_t>(i), scene.mesh.numNodes(), comm), *rows, 0)
                  .solvedAgain;
    return changed;
  }
  /// A part solved next: its steps counted from 0, all checked.
  void newPart() {
    checked = -1;
    firstIndex = 0;
  }
};
}  // namespace

void observeAfter(ContactSolveResult& done, const ContactSolveResult& part, const StepObserver& afterStep) {
  ContactSolveResult all = done;
  all.steps.insert(all.steps.end(), part.steps.begin(), part.steps.end());
  all.earlierSteps.insert(all.earlierSteps.end(), part.earlierSteps.begin(), part.earlierSteps.end());
  afterStep(all);
  releaseWrittenSteps(done);
}

void prependSteps(ContactSolveResult& done, ContactSolveResult& last) {
  last.steps.insert(last.steps.begin(), done.steps.begin(), done.steps.end());
  last.earlierSteps.insert(last.earlierSteps.begin(), std::make_move_iterator(done.earlierSteps.begin()),
                           std::make_move_iterator(done.earlierSteps.end()));
  addPartCounts(done, last);
}

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

void addPartCounts(const ContactSolveResult& part, ContactSolveResult& into) {
  const qp::SmalseCounters& c = part.contact.counters;
  qp::SmalseCounters& t = into.contact.counters;
  t.outerIterations += c.outerIterations;
  t.innerIterations += c.innerIterations;
  t.cgSteps += c.cgSteps;
  t.expansionSteps += c.expansionSteps;
  t.proportioningSteps += c.proportioningSteps;
  t.operatorApplications += c.operatorApplications;
  t.preconditionerApplications += c.preconditionerApplications;
  t.seconds += c.seconds;
  t.operatorSeconds += c.operatorSeconds;
  t.productSeconds += c.productSeconds;
  t.preconditionerSeconds += c.preconditionerSeconds;
  into.contact.fixedPointIterations += part.contact.fixedPointIterations;
  into.fApplications += part.fApplications;
  into.factorizationSeconds += part.factorizationSeconds;
  into.solveSeconds += part.solveSeconds;
  const feti::OperatorProfile& p = part.profile;
  feti::OperatorProfile& q = into.profile;
  for (auto [from, to] : {std::pair{&p.fApplications, &q.fApplications}, {&p.projections, &q.projections},
                          {&p.coarseSolves, &q.coarseSolves}, {&p.preconditionerApplications, &q.preconditionerApplications},
                          {&p.coarseCoordinates, &q.coarseCoordinates}, {&p.coarseRefinementSteps, &q.coarseRefinementSteps}})
    *to += *from;
  for (auto [from, to] : {std::pair{&p.fSeconds, &q.fSeconds}, {&p.gSeconds, &q.gSeconds},
                          {&p.coarseReduceSeconds, &q.coarseReduceSeconds}, {&p.coarseSolveSeconds, &q.coarseSolveSeconds},
                          {&p.preconditionerSeconds, &q.preconditionerSeconds},
                          {&p.coarseFactorSeconds, &q.coarseFactorSeconds},
                          {&p.rigidCoefficientsSeconds, &q.rigidCoefficientsSeconds}})
    *to += *from;
  q.coarseFactorizations += p.coarseFactorizations;
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

ContactSolveResult solveHistoryPairedAsItGoes(const ContactRun& contactRun, std::vector<fem::SubdomainSystem> owned,
                                              const feti::ConstraintMatrix& B, const HistoryPart& span) {
  const Scene& scene = contactRun.scene;
  const Teuchos::ParameterList& tribos = contactRun.tribos;
  MPI_Comm comm = contactRun.comm;
  const StepObserver& afterStep = contactRun.afterStep;
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const bool verbose = tribos.sublist("Solver").get<bool>("Verbose");
  const feti::ConstraintSpec spec = span.spec ? *span.spec : constraintSpec(scene);
  ContactSolveResult done;  // the steps before the pairing last changed
  const feti::ConstraintMatrix* rows = &B;  // the pairing the part is solved on
  // Each converged step is checked as the part solving it reaches it: a step whose state changes
  // the pairing ends the part there (HistoryPart::stopWhen; it is solved again on the new
  // pairing), and no checkpoint holds it. The checkpoint observer and the stop rule share the check.
  // A part restarted from a file checks from its second step on: the file's state is its own.
  StepCheck check{scene, spec, rows,
                  span.continueFrom || tribos.sublist("Load Steps").get<std::string>("Restart From").empty() ? 0u : 1u,
                  comm};
  const std::function<bool(const ContactSolveResult&)> changesAtStep = [&](const ContactSolveResult& p) {
    return check.changes(p);
  };
  const StepObserver observe = !afterStep ? StepObserver() : [&](const ContactSolveResult& part) {
    if (!changesAtStep(part)) observeAfter(done, part, afterStep);
  };
  HistoryPart first = span;
  first.stopWhen = changesAtStep;
  ContactSolveResult part = solveOnePairing(contactRun.observedBy(observe), std::move(owned), B, first);
  const std::string restartFile = part.restartFile;  // Load Steps/Restart From's, as the summary shows it
  const int restartStep = part.restartStep;
  std::unique_ptr<feti::ConstraintMatrix> held;
  std::optional<RestartState> from;  // the state `part` started from, when in memory
  if (span.continueFrom) from = *span.continueFrom;
  std::vector<PairingUpdateRecord> records;
  int changedStep = 0, atThatStep = 0;  // Pairing Updates counts the changes at one step
  const int lastStep = span.lastStep > 0 ? span.lastStep : scene.loadSteps;
  StartMultipliers start;  // the next part's (HistoryPart::startLambda)
  auto solveNextPart = [&]() {  // from the state after `done`, on `rows`
    if (!done.steps.empty()) from = stateAfter(done, *rows, scene, comm);
    std::vector<fem::SubdomainSystem> systems;
    assembleOwnedSubdomains(scene, comm, systems);
    check.newPart();
    part = solveOnePairing(contactRun.observedBy(observe), std::move(systems), *rows,
                           {from ? &*from : nullptr, span.lastStep, &spec, changesAtStep, std::move(start.lambda),
                            start.step});
  };
  for (int update = 1;;) {
    PairingUpdateRecord standing{update};
    auto change = firstChange(scene, spec, part, *rows, check.firstIndex, update, comm, standing);
    if (change) {
      const int step = part.steps[change->index].step;
      atThatStep = step == changedStep ? atThatStep + 1 : 1;
      changedStep = step;
    }
    if (change && atThatStep > scene.pairingUpdates) {
      // That step keeps this pairing (the check after the solve has the last word); the part
      // stopped there (HistoryPart::stopWhen), so the rest of the history goes on from it.
      if (!part.contact.converged || part.steps.back().step >= lastStep) break;
      start = {part.contact.lambda, part.steps.back().step};  // the same rows: warm, as within a part
      keepAllSteps(part, done);
      solveNextPart();
      continue;
    }
    records.push_back(change ? change->record : standing);
    reportUpdate(records.back(), rank, verbose);
    ++update;
    if (!change) break;
    start = startAfterChange(part, change->index, *rows, *change->rows, comm);
    keepSteps(part, change->index, done);
    held = std::move(change->rows);
    rows = held.get();
    solveNextPart();
  }
  prependSteps(done, part);
  part.restartFile = restartFile;
  part.restartStep = restartStep;
  part.pairingUpdates = std::move(records);
  return part;
}

}  // namespace tribos::stack
