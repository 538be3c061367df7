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

/// Tributary area of every node of a side set (a third of each adjacent face's area); zero
/// for nodes off the set. Length mesh.numNodes().
std::vector<double> tributaryArea(const mesh::Mesh& mesh, const std::string& sideSet);

}  // namespace tribos::stack
