// Contact decided by the deformed bodies: the pairing after each solve (PairingUpdate.hpp).
#include "PairingUpdate.hpp"

#include <Teuchos_ParameterList.hpp>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>

#include "ConditionSteps.hpp"

#include "tribos/core/PhaseTimer.hpp"
#include "tribos/feti/CarriedMultipliers.hpp"
#include "tribos/stack/LinearFetiSolve.hpp"
#include "tribos/stack/SubdomainSetup.hpp"

namespace tribos::stack {

std::vector<std::array<double, 3>> onEveryRank(std::vector<std::array<double, 3>> u, LO numNodes, MPI_Comm comm) {
  u.resize(numNodes);
  MPI_Bcast(u.data(), 3 * numNodes, MPI_DOUBLE, 0, comm);
  return u;
}

namespace {

/// Contact nodes paired on the deformed bodies whose slave node has slid along its master,
/// since the state `pairedAt` they were paired at, by more than kRelinearise of the spread of
/// their master nodes: their weights were taken where the solve did not leave them (a node
/// paired while inside the master, which the solve then pushed back along a curved wall), so they
/// are paired again where the bodies are now. Only the tangential drift counts: the weights of a
/// face do not change as the node approaches it along the normal, and a drift below this (a
/// patch whose bodies' Poisson expansions differ by 1.4 % of a face) keeps the rows, and with them
/// the contact patch test's exact answer.
constexpr double kRelinearise = 2.5e-2;

long long movedSincePairing(const mesh::Mesh& mesh, const feti::ConstraintMatrix& pairing,
                            const std::vector<std::array<double, 3>>& pairedAt,
                            const std::vector<std::array<double, 3>>& u) {
  long long moved = 0;
  for (const auto& node : pairing.contact) {
    if (!node.pairedDeformed) continue;
    std::array<double, 3> slide{};
    for (int c = 0; c < 3; ++c)
      slide[c] = (u[node.slaveNode][c] - pairedAt[node.slaveNode][c]) -
                 (u[node.masterNode][c] - pairedAt[node.masterNode][c]);
    const double along = slide[0] * node.normal[0] + slide[1] * node.normal[1] + slide[2] * node.normal[2];
    double drift = 0.0, spread = 0.0;
    for (int c = 0; c < 3; ++c) drift += std::pow(slide[c] - along * node.normal[c], 2);
    for (LO a : node.masterNodes)
      for (LO b : node.masterNodes) {
        double d = 0.0;
        for (int c = 0; c < 3; ++c) d += std::pow(mesh.coords[a][c] - mesh.coords[b][c], 2);
        spread = std::max(spread, d);
      }
    moved += std::sqrt(drift) > kRelinearise * std::sqrt(spread);
  }
  return moved;
}

/// A solve whose pairing the deformed bodies still change, with no Pairing Updates left to solve
/// again: not converged, however its own KKT residuals read (the hertz sphere with the default
/// Search Distance ended "converged" at 4.5 times the normal force of its settled pairing).
void notSettled(const PairingUpdateRecord& r, int updates, contact::ContactResult& result) {
  if (!result.converged) return;
  result.converged = false;
  result.message = "the pairing on the deformed bodies did not settle within Solver/Pairing Updates = " +
                   std::to_string(updates) + " (after the last solve " + std::to_string(r.newlyInside) +
                   " slave nodes without rows lie inside the master, " + std::to_string(r.movedOn) +
                   " slid past their master nodes, " + std::to_string(r.relinearised) +
                   " moved since they were paired there): raise Pairing Updates, or Contact/Search Distance to "
                   "pair the nodes that may touch before the solve";
}

}  // namespace

/// The update's line (rank 0, Solver/Verbose; the summary's pairing_updates hold them all).
void reportUpdate(const PairingUpdateRecord& r, int rank, bool verbose) {
  if (rank != 0 || !verbose) return;
  std::cout << "  pairing on the deformed bodies (update " << r.update << "): " << r.paired << " slave nodes paired, "
            << r.newlyInside << " without rows inside the master, " << r.movedOn << " slid past their master nodes, "
            << r.relinearised << " moved since they were paired there"
            << (r.solvedAgain                                              ? ": solving again on this pairing"
                : r.newlyInside + r.movedOn + r.relinearised > 0 ? ": no update left to solve again"
                                                                  : ": the pairing stands")
            << "\n";
}

feti::ConstraintMatrix rowsAt(const Scene& scene, const feti::ConstraintSpec& of,
                              const std::vector<std::array<double, 3>>& u, const feti::ConstraintMatrix& solved,
                              MPI_Comm comm) {
  int rank = 0, numRanks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &numRanks);
  feti::ConstraintSpec spec = of;
  spec.pairingDisplacement = &u;
  spec.solvedPairing = &solved;
  core::ScopedPhase phase("Contact: rows on the deformed bodies");  // the summary's timers
  return feti::buildConstraintMatrix(scene.mesh, scene.decomposition, spec, numRanks, rank);
}


PairingUpdateRecord changesAt(const Scene& scene, const feti::ConstraintSpec& of,
                              const std::vector<std::array<double, 3>>& u, const feti::ConstraintMatrix& solved,
                              int update) {
  feti::ConstraintSpec spec = of;
  spec.pairingDisplacement = &u;
  spec.solvedPairing = &solved;
  core::ScopedPhase phase("Contact: pairing check on the deformed bodies");  // the summary's timers
  const auto [newlyInside, movedOn] = feti::pairingChanges(scene.mesh, spec);
  PairingUpdateRecord record{update, static_cast<long long>(solved.contact.size()), newlyInside, movedOn};
  record.solvedAgain = newlyInside + movedOn > 0;
  return record;
}

ContactSolveResult solveContactScene(const Scene& scene, std::vector<fem::SubdomainSystem> owned,
                                     const feti::ConstraintMatrix& B, const Teuchos::ParameterList& tribos,
                                     MPI_Comm comm, core::Stopwatch runStart, const StepObserver& afterStep) {
  const ContactRun run{scene, tribos, comm, runStart, afterStep};
  if (scene.loadHistory && conditionRuns(scene).size() > 1)  // conditions switched between steps
    return solveConditionRuns(run, std::move(owned), B);
  if (scene.pairingUpdates == 0) return solveOnePairing(run, std::move(owned), B);
  if (scene.loadHistory) return solveHistoryPairedAsItGoes(run, std::move(owned), B);
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const feti::ConstraintSpec spec = constraintSpec(scene);
  const ContactRun unobserved = run.observedBy({});
  ContactSolveResult out = solveOnePairing(unobserved, std::move(owned), B);
  std::vector<PairingUpdateRecord> records;
  std::unique_ptr<feti::ConstraintMatrix> current;  // the pairing of `out` when not B
  std::vector<std::array<double, 3>> pairedAt;        // the state `current` was paired at
  ContactSolveResult spent;  // the counts of the solves before the last
  // Every solve's pairing is checked, the last one's too: one that Pairing Updates leaves no
  // solve for is not converged (its rows were built where the bodies were not left).
  for (int k = 1; out.contact.converged || out.penetrated; ++k) {
    const auto u = onEveryRank(out.displacement.value, scene.mesh.numNodes(), comm);
    const feti::ConstraintMatrix& solved = current ? *current : B;
    PairingUpdateRecord record = changesAt(scene, spec, u, solved, k);
    if (current) record.relinearised = movedSincePairing(scene.mesh, *current, pairedAt, u);
    const bool changed = record.solvedAgain || record.relinearised > 0;
    record.solvedAgain = changed && k <= scene.pairingUpdates;
    std::unique_ptr<feti::ConstraintMatrix> next;
    if (record.solvedAgain) {  // only then are the rows built
      next = std::make_unique<feti::ConstraintMatrix>(rowsAt(scene, spec, u, solved, comm));
      record.paired = static_cast<long long>(next->contact.size());
    }
    records.push_back(record);
    reportUpdate(record, rank, tribos.sublist("Solver").get<bool>("Verbose"));
    if (changed && !record.solvedAgain) notSettled(record, scene.pairingUpdates, out.contact);
    if (!record.solvedAgain) break;
    // The systems went into the last solve's factors: assembled and factorised again (the scene
    // keeps its subdomains' elements for this, stack::keepRankData).
    std::vector<fem::SubdomainSystem> systems;
    assembleOwnedSubdomains(scene, comm, systems);
    addPartCounts(out, spent);  // the solve that is superseded counts too
    HistoryPart warm;  // from the multipliers of the solve before, carried to the new rows
    warm.startLambda = feti::carryMultipliers(solved, out.contact.lambda, *next, comm);
    out = solveOnePairing(unobserved, std::move(systems), *next, warm);
    current = std::move(next);
    pairedAt = u;
  }
  out.pairingUpdates = std::move(records);
  addPartCounts(spent, out);
  return out;
}

}  // namespace tribos::stack
