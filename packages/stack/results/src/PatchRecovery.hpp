#pragma once
/// \file PatchRecovery.hpp
/// Nodal stresses of linear elements by polynomial preserving recovery (issue 42): at a node,
/// the least-squares quadratic fit of the displacement over the nodes of a patch of elements,
/// differentiated at the node. The stress of a linear element is accurate at its centre only:
/// averaging element values, or extrapolating them from the quadrature points, puts the
/// error of the element's gradient at the surface (measured on a shrink fit's bore: 7.4 % and
/// 5.3 % low/high with 2 mm hexahedra, 0.5 % with this recovery). Quadratic tetrahedra keep
/// the extrapolation from their quadrature points (their strain is linear, exact at the nodes).
#include <array>
#include <vector>

#include "tribos/stack/Results.hpp"
#include "tribos/stack/Scene.hpp"

namespace tribos::stack {

/// Replaces r.nodal at every node whose body (`body[n]`: its block) has only linear elements
/// around it (4-node tetrahedra, 8-node hexahedra, 6-node prisms) by the recovered stress,
/// with that body's material. The patch: the node's elements in its body; at a node on the
/// body's surface, also the elements around their nodes (two rings: a one-ring patch there
/// lies on one side of the node). A patch of fewer than 10 nodes keeps the mean.
/// `displacement`: per global node.
void recoverLinearElementStresses(const Scene& scene, const std::vector<std::array<double, 3>>& displacement,
                                  const std::vector<int>& body, StressResults& r);

}  // namespace tribos::stack
