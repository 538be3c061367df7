#pragma once
// Internal to stack/: the state a load history continues from (Load Steps/Restart From): the
// last converged load step of a tribos result of the same scene. What a step carries to the
// next is the tangential relative displacement reached at every contact node (LoadHistory's
// slip), and the totals the results accumulate (the accumulated slip and the dissipated
// energy); the multipliers are not in the file, so the first step after a restart starts cold.
#include <mpi.h>

#include <array>
#include <string>
#include <utility>
#include <vector>

#include "tribos/stack/ContactFields.hpp"
#include "tribos/stack/Scene.hpp"

namespace tribos::stack {

struct RestartState {
  std::string file;
  int step = 0;  ///< the last converged load step in the file (its global variable load_step)
  /// The file's totals at that step, per global node and interface (every rank):
  /// contactTangentialT1/T2, contactAccumulatedSlip, interfaces[i].dissipatedEnergy and
  /// dissipatedEnergy, and the contact forces contactNormal/T1/T2 (the first new step's warm
  /// start: feti::multipliersFromNodalForces); the other fields are empty.
  ContactFields totals;
  /// The displacement of every global node at the steps asked for (readRestart's
  /// displacementSteps; ConditionSteps.cpp: where conditions that took hold hold their nodes).
  std::vector<std::pair<int, std::vector<std::array<double, 3>>>> displacements;
  /// Per pretension section of the scene, its shortening at that step (global variable
  /// <name>_pretension_shortening).
  std::vector<double> sectionShortening;
};

/// Reads `file` (an Exodus result of a load history of this scene, whose contact nodes are B's).
/// Throws core::InputError naming the file when it cannot be read, is no load-history result,
/// has another mesh or other contact pairs (a slave node's master, tangential displacement off
/// B's slave nodes), lacks an interface of the scene, holds no converged step, or has solved
/// every step of the scene.
/// Also when a step's load_step is not its number (1, 2, ... in order), converged is neither 0
/// nor 1, or a memory value is not finite (or the accumulated slip negative). With
/// `displacementSteps`, the displacements of those up to the last converged step too.
RestartState readRestart(const std::string& file, const Scene& scene, const feti::ConstraintMatrix& B,
                         const std::vector<int>& displacementSteps = {});

/// readRestart on rank 0 of `comm`, its state on every rank (issue 44: each rank read the file
/// itself, and a file replaced while they started gave ranks different states: hangs, or exit 0
/// with a result matching neither file). An error on rank 0 ends every rank (core::onEveryRankOrNone).
/// Collective.
RestartState readRestartOnRoot(const std::string& file, const Scene& scene, const feti::ConstraintMatrix& B,
                               MPI_Comm comm, const std::vector<int>& displacementSteps = {});

/// Rank 0's `state` (its step and totals: tangential displacements, accumulated slip, dissipated
/// energies; its displacements) on every rank of `comm`: readRestartOnRoot's, and a history continued in memory
/// after a pairing update (PairingUpdate.cpp). Collective.
void broadcastRestartState(RestartState& state, const Scene& scene, MPI_Comm comm);

}  // namespace tribos::stack
