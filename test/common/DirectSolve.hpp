#pragma once
// An independent reference for the T-FETI tests: the globally assembled, undecomposed
// stiffness (fem::assembleGlobal) with the Dirichlet dofs eliminated and tied node pairs
// merged, solved by Amesos2 (KLU2) on one process.
#include <array>
#include <utility>
#include <vector>

#include "tribos/fem/SubdomainSystem.hpp"

namespace tribos::test {

/// u of every global node. `fixedNodes`: u = 0 there. `tied`: (a, b) pairs with u_a = u_b;
/// `tiedZ`: pairs whose z components only are equal (frictionless contact along z).
std::vector<std::array<double, 3>> directSolve(const mesh::Mesh& mesh, const std::vector<fem::Material>& materials,
                                               const fem::Loads& loads, const std::vector<LO>& fixedNodes,
                                               const std::vector<std::pair<LO, LO>>& tied,
                                               const std::vector<std::pair<LO, LO>>& tiedZ = {});

/// Frictionless node-to-node contact with normal +z and zero gap (the two bricks), solved on
/// the undecomposed mesh by a primal-dual active set method: each iteration ties the z
/// components of the active pairs (directSolve), then activates penetrating pairs and
/// releases pairs in tension, until the active set repeats. Independent of T-FETI and QP.
std::vector<std::array<double, 3>> directFrictionlessContact(const mesh::Mesh& mesh,
                                                             const std::vector<fem::Material>& materials,
                                                             const fem::Loads& loads, const std::vector<LO>& fixedNodes,
                                                             const std::vector<std::pair<LO, LO>>& pairs,
                                                             int* iterations = nullptr);

}  // namespace tribos::test
