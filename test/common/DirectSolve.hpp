#pragma once
// An independent reference for the T-FETI tests: the globally assembled, undecomposed
// stiffness (fem::assembleGlobal) with the Dirichlet dofs eliminated and tied node pairs
// merged, solved by Amesos2 (KLU2) on one process.
#include <array>
#include <utility>
#include <vector>

#include "tribos/fem/SubdomainSystem.hpp"

namespace tribos::test {

/// u of every global node. `fixedNodes`: u = 0 there. `tied`: (a, b) pairs with u_a = u_b.
std::vector<std::array<double, 3>> directSolve(const mesh::Mesh& mesh, const std::vector<fem::Material>& materials,
                                               const fem::Loads& loads, const std::vector<LO>& fixedNodes,
                                               const std::vector<std::pair<LO, LO>>& tied);

}  // namespace tribos::test
