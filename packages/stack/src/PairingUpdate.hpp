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
#include <vector>

#include "Restart.hpp"
#include "tribos/stack/ContactSolve.hpp"

namespace tribos::stack {

/// One solve on one pairing (ContactSolve.cpp): solveContactScene without pairing updates. A
/// load history continues from `continueFrom` where given (a state in memory, every rank),
/// else from Load Steps/Restart From or step 1.
ContactSolveResult solveOnePairing(const Scene& scene, std::vector<fem::SubdomainSystem> owned,
                                   const feti::ConstraintMatrix& B, const Teuchos::ParameterList& tribos, MPI_Comm comm,
                                   core::Stopwatch runStart, const StepObserver& afterStep = {},
                                   const RestartState* continueFrom = nullptr);

/// A load history paired again as it goes (HistoryPairing.cpp): after the history is solved on
/// the pairing `B`, its first converged step whose state changes the pairing (newly inside,
/// moved on) is solved again, from the step before it, on the pairing of that state; and so on,
/// at most Scene::pairingUpdates times at one step. The result's pairingUpdates get one entry
/// per check that changed the pairing, and one for the check that found it standing.
ContactSolveResult solveHistoryPairedAsItGoes(const Scene& scene, std::vector<fem::SubdomainSystem> owned,
                                              const feti::ConstraintMatrix& B, const Teuchos::ParameterList& tribos,
                                              MPI_Comm comm, core::Stopwatch runStart, const StepObserver& afterStep);

/// The contact rows at the displacement `u` (every rank), this rank's part: each slave node keeps
/// its pairing in `solved` unless the bodies at x + u show it wrong (feti::ConstraintSpec::
/// pairingDisplacement), and the record of what changed.
feti::ConstraintMatrix rowsAt(const Scene& scene, const std::vector<std::array<double, 3>>& u,
                              const feti::ConstraintMatrix& solved, MPI_Comm comm);
/// Rank 0's displacement per global node (`u`, empty elsewhere) on every rank of `comm`.
std::vector<std::array<double, 3>> onEveryRank(std::vector<std::array<double, 3>> u, LO numNodes, MPI_Comm comm);
/// What a pairing at the displacement `u` would change against `solved` (feti::pairingChanges:
/// the searches alone), as update `update`; `paired` is the standing pairing's count.
PairingUpdateRecord changesAt(const Scene& scene, const std::vector<std::array<double, 3>>& u,
                              const feti::ConstraintMatrix& solved, int update);
/// The update's line on rank 0 when `verbose`.
void reportUpdate(const PairingUpdateRecord& r, int rank, bool verbose);

}  // namespace tribos::stack
