#pragma once
// Internal to feti/: displacement components prescribed to 0 and eliminated from K_s instead
// of enforced by rows of B (FETI/Displacement Conditions = Automatic or Eliminated;
// ConstraintSpec::zeroComponents). Why: rows u_c = 0 on most nodes of a thin plane-strain slice make
// F ill-conditioned however it is preconditioned (the Hertz cylinder at hc 0.05: kappa 4 478
// with the rows, 20 without them; doc/measurements/curved_iterations.md).
#include <array>
#include <vector>

#include "tribos/fem/SubdomainSystem.hpp"

namespace tribos::feti {

/// What the elimination took out of one subdomain's system: the rows of K_s and the loads
/// at the eliminated dofs, for their reactions K u - f.
struct EliminatedRows {
  std::vector<LO> dof;          ///< ascending local dofs
  std::vector<LO> rowPtr{0};    ///< dof.size() + 1
  std::vector<LO> colInd;
  std::vector<double> values;
  std::vector<double> load;     ///< f_s at each dof as last given (setLoads)
};

/// Removes `dofs` (ascending) from `system`: their rows are kept in the result, rows and
/// columns of K set to 0 but the diagonal (so that K_s u = f gives u = 0 there), and R
/// replaced by the rigid modes that vanish at those dofs (orthonormal, first), the other
/// columns 0: G's rows for those modes vanish, and the coarse problem pins them (CoarseProblem).
/// The live column count is returned in `liveModes`.
EliminatedRows eliminateComponents(fem::SubdomainSystem& system, const std::vector<LO>& dofs, int& liveModes);

/// How firmly `dofs` (local dofs of a subdomain with nodes at `coords`) hold the rigid modes
/// they restrain: the smallest eigenvalue of (C R)^T (C R) above the vanishing ones, R the
/// orthonormal rigid modes (1: a mode held at every dof; +inf: none held). A small value is a
/// mode held at a few dofs only (a corner, a short edge): eliminated there, K_s keeps a nearly
/// rigid motion whose compliance enters F (ConstraintMatrix keeps such subdomains' rows).
double weakestRestraint(const std::vector<std::array<double, 3>>& coords, const std::vector<LO>& dofs);

/// f at the eliminated dofs kept (EliminatedRows::load) and set to 0.
void eliminateLoads(std::vector<double>& f, EliminatedRows& rows);

/// The reaction at each eliminated dof: (K_s u)_dof - f_dof with the rows as they were.
std::vector<double> eliminatedReactions(const EliminatedRows& rows, const std::vector<double>& u);

}  // namespace tribos::feti
