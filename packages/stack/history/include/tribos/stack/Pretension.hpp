#pragma once
// Internal to stack/: bolt pretension sections (Pretension/<name>, issue 43: a preload had to be
// faked by a bolt meshed too short and calibrated by trial). A section is a cut through a bolt
// given as a Bonded interface between its two parts. In T-FETI the cut's tied normal rows are
// gluing rows; a pretension gives them a prescribed jump, the shortening s: (u_slave - chi
// u_master) . nu = s, the two sides pulled into each other, so that the bolt is stretched and
// the section carries its tension, -sum rowScale lambda_N over its rows. Given a Shortening, s
// is ramped over the section's steps; given a Force, s is found in each of those steps by secant
// iterations on F(s), each a solve of the step from the same state (F is linear in s where the
// rest of the scene is, nearly so with contact). After its steps a section is locked: s stays,
// and its force follows the other loads.
#include <mpi.h>

#include <functional>
#include <string>
#include <vector>

#include "tribos/contact/ContactSolver.hpp"
#include "tribos/stack/SolveResults.hpp"
#include "tribos/stack/LoadHistory.hpp"

namespace Teuchos {
class ParameterList;
}

namespace tribos::stack {

/// The tension section p of `history` carries in a solved state (its multipliers `lambda` on
/// this rank's rows): -sum rowScale lambda over its normal rows, the same bits on every layout.
/// Collective.
double sectionForce(const LoadHistory& history, size_t p, const std::vector<double>& lambda, MPI_Comm comm);

/// The state of each section after a step (the summary's steps[k].pretension).
std::vector<SectionState> sectionStates(const LoadHistory& history, const std::vector<double>& lambda,
                                        MPI_Comm comm);

/// One try of a step at `position`: `solve` (one solve of the step with the shortenings in
/// `history`, warm from the result it is given) once where no Force section acts at this
/// position, else until each such section carries its force (target x min(position / steps, 1))
/// within its Force Tolerance, at most kMaxSectionSolves solves: secant iterations, the first
/// slope from the last step's or from a probe. The result of the last solve, not converged (its
/// message naming the section) where a force was not reached; `solves` counts them.
constexpr int kMaxSectionSolves = 12;
contact::ContactResult solveWithSectionForces(
    LoadHistory& history, double position, const contact::ContactResult& start, MPI_Comm comm,
    const std::function<contact::ContactResult(const contact::ContactResult& warm)>& solve, int& solves);

}  // namespace tribos::stack
