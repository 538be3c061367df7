#pragma once
// Internal to stack/: displacement conditions switched per step (Load Steps/<name>/Active,
// issue 43: a plate gripped only after the bolt is tightened). In T-FETI a condition is rows of
// B, so a history whose conditions change is solved in runs of steps with the same conditions,
// each on its own B, assembled and factorised again, continuing in memory from the state the run
// before left (as a restart does: the tangential displacement reached, measured with the new
// rows, the accumulated slip, the dissipated energies). A condition that takes hold at step a > 1
// holds its nodes where step a - 1 left them and moves them by its Displacement times its factor
// from there (u_c = u_c(a - 1) + factor x value_c): a grip that does not pull the body back to
// where the mesh had it.
#include <mpi.h>

#include <array>
#include <map>
#include <vector>

#include "PairingUpdate.hpp"
#include "tribos/stack/ContactSolve.hpp"

namespace tribos::stack {

/// Steps [first, last] of a history with the same displacement conditions.
struct ConditionRun {
  int first = 1, last = 1;
};

/// The runs of steps over which Scene::conditionActive does not change, in order (one run
/// when no condition switches).
std::vector<ConditionRun> conditionRuns(const Scene& scene);

/// For each displacement condition that holds in step `k`, the step after which it took hold
/// (the step before its run of holding steps; 0: from the start, at the reference); -1 for a
/// condition that does not hold in step k.
std::vector<int> heldSince(const Scene& scene, int k);

/// The constraints of the steps of the run starting at step `first`: the conditions that hold
/// then, each held from the displacement at heldSince (`at` holds those states, every rank).
feti::ConstraintSpec constraintSpecAt(const Scene& scene, int first,
                                      const std::map<int, std::vector<std::array<double, 3>>>& at);

/// A load history whose conditions switch (more than one run): each run solved on its own B
/// (`B` and `owned` serve the run of step 1), paired as it goes where Scene::pairingUpdates,
/// from Load Steps/Restart From's state when given. Steps, counts and pairing updates of every
/// run in one result; `afterStep` sees every step converged so far. Collective.
ContactSolveResult solveConditionRuns(const ContactRun& contactRun, std::vector<fem::SubdomainSystem> owned,
                                      const feti::ConstraintMatrix& B);

}  // namespace tribos::stack
