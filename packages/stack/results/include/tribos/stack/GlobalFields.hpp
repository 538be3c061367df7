#pragma once
/// \file GlobalFields.hpp
/// From subdomain copies back to the user's global mesh (what Exodus results show).
#include <mpi.h>

#include <array>
#include <string>
#include <vector>

#include "tribos/stack/Scene.hpp"

namespace tribos::stack {

struct GlobalDisplacement {
  std::vector<std::array<double, 3>> value;  ///< per global node: mean over its copies (rank 0)
  double maxCopyJump = 0.0;                  ///< largest spread between copies of a node (rank 0)
};

/// Gathers u of the owned subdomains (u[i] of subdomain firstOwned + i) to rank 0.
GlobalDisplacement gatherDisplacement(const Scene& scene, int firstOwned, const std::vector<std::vector<double>>& u,
                                      MPI_Comm comm);

/// Reaction forces on the user's mesh, per global node (rank 0; zero where nothing is
/// prescribed): the force the support exerts on the body, summed over the node's copies.
/// A prescribed-displacement row of B is a unit row on one copy's component, and
/// K u = f - B^T lambda, so the row's reaction is -lambda_r; contact rows that dropped a
/// prescribed component add the contact force on it, which the support takes (doc/theory.md,
/// "Results"). `ownedLambda` holds the
/// multipliers of this rank's rows [B.firstRowOfRank[rank], B.firstRowOfRank[rank + 1]).
/// Collective over `comm`.
std::vector<std::array<double, 3>> gatherReactions(const Scene& scene, const feti::ConstraintMatrix& B,
                                                   const std::vector<feti::EliminatedReaction>& eliminated,
                                                   const std::vector<double>& ownedLambda, MPI_Comm comm);

/// The applied load: the sum of the nodal loads f_s of every subdomain (each traction and
/// volume force is assembled into exactly one subdomain), on every rank. Collective.
std::array<double, 3> totalLoad(const std::vector<fem::SubdomainSystem>& owned, MPI_Comm comm);
/// The sum over every subdomain node of |f| (the nodal load's length), on every rank with the
/// same bits on every number of ranks (for one decomposition): the size of the loads where
/// they cancel in totalLoad (opposite pressures). Collective.
double loadMagnitude(const std::vector<fem::SubdomainSystem>& owned, MPI_Comm comm);

/// Tributary area of every node of a side set (a third of each adjacent triangle's area, a
/// quarter of each quadrilateral's; on a 6-node triangle the integral of the node's transformed
/// basis function, 2/15 of its area at a vertex, 1/5 at a mid-edge node: where the dual mortar
/// multiplier over it is the pressure); zero for nodes off the set. Length mesh.numNodes().
std::vector<double> tributaryArea(const mesh::Mesh& mesh, const std::string& sideSet);

}  // namespace tribos::stack
