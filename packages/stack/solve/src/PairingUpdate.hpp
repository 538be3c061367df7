#pragma once
// Internal to stack/: contact decided by the deformed bodies (issue 41). A solve on the pairing
// of the reference mesh can leave a slave node that had no rows (beyond Search Distance: a pin in
// a clearance hole) inside the master body, or a paired node slid past the master nodes of its
// rows (a joint slipping further than an element). After the solve the slave nodes are paired
// again at x + u (feti::ConstraintSpec::pairingDisplacement: the gaps still from the reference,
// so the rows constrain the total displacement as before); where that finds either case, the
// problem is built on the new pairing and solved again, up to Solver/Pairing Updates times.
// Where it finds neither, the first result stands bit for bit.
#include <mpi.h>

#include <array>
#include <functional>
#include <vector>

#include "tribos/stack/Restart.hpp"
#include "tribos/stack/ContactSolve.hpp"

namespace tribos::stack {

/// What every solve of one contact run shares: the scene, its validated list, the communicator,
/// the run's start (Solver/Max Seconds counts from it) and the observer of converged steps.
struct ContactRun {
  const Scene& scene;
  const Teuchos::ParameterList& tribos;
  MPI_Comm comm;
  core::Stopwatch runStart;
  StepObserver afterStep;
  /// The same run with another observer (a part's own, or none).
  ContactRun observedBy(StepObserver observer) const {
    ContactRun run = *this;
    run.afterStep = std::move(observer);
    return run;
  }
};

/// The part of a load history one solve covers (HistoryPairing.cpp, ConditionSteps.cpp).
struct HistoryPart {
  /// The state it continues from (in memory, every rank); null: Load Steps/Restart From, or step 1.
  const RestartState* continueFrom = nullptr;
  int lastStep = 0;  ///< its last step; 0: the scene's last
  /// The constraints its B was built from, which a pairing update builds its rows from again;
  /// null: constraintSpec(scene).
  const feti::ConstraintSpec* spec = nullptr;
  /// Asked with the result so far after each converged step before the last: true ends the
  /// history there (HistoryRun::stopAfter). Collective.
  std::function<bool(const ContactSolveResult&)> stopWhen;
  /// The multipliers its first solve starts from, on this rank's rows of its B (carried from
  /// another pairing: feti::carryMultipliers), and the step whose end they hold (0: a solve
  /// without steps); empty: the first solve starts cold.
  std::vector<double> startLambda;
  int startLambdaStep = 0;
};

/// One solve on one pairing (ContactSolve.cpp): solveContactScene without pairing updates; a
/// load history over the steps of `part`.
ContactSolveResult solveOnePairing(const ContactRun& contactRun, std::vector<fem::SubdomainSystem> owned,
                                   const feti::ConstraintMatrix& B, const HistoryPart& part = {});

/// A load history paired again as it goes (HistoryPairing.cpp): each converged step is checked
/// as it is reached; the first whose state changes the pairing (newly inside, moved on) ends the
/// part being solved and is solved again, from the step before it, on the pairing of that state;
/// and so on, at most Scene::pairingUpdates times at one step (then the step keeps its pairing
/// and the history goes on from it). The result's pairingUpdates get one entry per check that
/// changed the pairing, and one for the check that found it standing; its counts are every
/// part's. Over the steps of `part` (its spec: what the rows are built from).
ContactSolveResult solveHistoryPairedAsItGoes(const ContactRun& contactRun, std::vector<fem::SubdomainSystem> owned,
                                              const feti::ConstraintMatrix& B, const HistoryPart& part = {});

/// The contact rows at the displacement `u` (every rank), this rank's part, of the constraints
/// `spec`: each slave node keeps its pairing in `solved` unless the bodies at x + u show it wrong
/// (feti::ConstraintSpec::pairingDisplacement), and the record of what changed.
feti::ConstraintMatrix rowsAt(const Scene& scene, const feti::ConstraintSpec& spec,
                              const std::vector<std::array<double, 3>>& u, const feti::ConstraintMatrix& solved,
                              MPI_Comm comm);
/// Rank 0's displacement per global node (`u`, empty elsewhere) on every rank of `comm`.
std::vector<std::array<double, 3>> onEveryRank(std::vector<std::array<double, 3>> u, LO numNodes, MPI_Comm comm);
/// What a pairing at the displacement `u` would change against `solved` (feti::pairingChanges:
/// the searches alone), as update `update`; `paired` is the standing pairing's count.
PairingUpdateRecord changesAt(const Scene& scene, const feti::ConstraintSpec& spec,
                              const std::vector<std::array<double, 3>>& u, const feti::ConstraintMatrix& solved,
                              int update);
/// Step i's displacement (rank 0's: an earlier step's, or the last state's), on every rank.
std::vector<std::array<double, 3>> stepDisplacement(const ContactSolveResult& result, size_t i, LO numNodes,
                                                    MPI_Comm comm);
/// The tangential displacement each contact node of `rows` has reached at `u`, u_slave - chi
/// u_master along t1 and t2 (per global node, every rank): what the next step's friction
/// measures its slip from, for rows whose frames and weights changed.
void tangentialReached(const feti::ConstraintMatrix& rows, const std::vector<std::array<double, 3>>& u,
                       ContactFields& totals);
/// The state a history continues from after the steps of `done` (its last one), measured with
/// the rows it continues on (this rank's part; the state is rank 0's, on every rank). Collective.
RestartState stateAfter(const ContactSolveResult& done, const feti::ConstraintMatrix& rows, const Scene& scene,
                        MPI_Comm comm);
/// Adds the additive counts of a part of a history solved on its own operators (its SMALSE-M
/// counters, fixed-point iterations, F applications, factorisation and solve seconds, the
/// operators' counts and times) to `into`: a history solved in parts counts every part's work,
/// the steps a later part solved again included.
void addPartCounts(const ContactSolveResult& part, ContactSolveResult& into);
/// The result of a history solved in parts: the steps of `done` (moved), then those of `last`,
/// and every part's counts.
void prependSteps(ContactSolveResult& done, ContactSolveResult& last);

/// `afterStep` shown the steps of `done` then those of `part` (the part being solved after
/// them); then `done`'s written steps released but its last (a part may continue from it again).
void observeAfter(ContactSolveResult& done, const ContactSolveResult& part, const StepObserver& afterStep);
/// The update's line on rank 0 when `verbose`.
void reportUpdate(const PairingUpdateRecord& r, int rank, bool verbose);

}  // namespace tribos::stack
