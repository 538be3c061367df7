#pragma once
// Internal to feti/: the pairs of one contact interface before they become rows (ContactRows.cpp),
// found on the reference mesh or on the deformed bodies (DeformedPairing.cpp).
#include <vector>

#include "ConstraintRows.hpp"
#include "tribos/feti/ConstraintMatrix.hpp"
#include "tribos/geometry/ContactSearch.hpp"
#include "tribos/geometry/MortarCoupling.hpp"
#include "tribos/mesh/Mesh.hpp"

namespace tribos::feti::rows {

/// The pairs of one interface: its search and the master side of each pair.
struct InterfacePairs {
  geometry::ContactSearchResult search;
  std::vector<geometry::MortarRow> masterSides;
  long long unsettledQuadraturePoints = 0;  ///< mortar quadrature points whose projection did not settle
  /// Per pair: found on the deformed bodies (ContactNode::pairedDeformed); empty: none was.
  std::vector<char> deformed;
  GO newlyInside = 0, movedOn = 0;  ///< ContactInterfaceRows's counts
};

/// Per node, the axes a displacement condition holds it along while it is free along another
/// (geometry::HeldAxes: the nodes on symmetry planes, whose contact normals lie in them).
geometry::HeldAxes heldAxes(const Prescribed& prescribed);

/// The search and the master sides of interface `spec` on `mesh` (ContactRows.cpp); `held` as
/// heldAxes gives it.
InterfacePairs pairsOf(const mesh::Mesh& mesh, const ContactInterfaceSpec& spec, const geometry::HeldAxes& held);

/// The pairs of interface `index` of `spec` when the pairing follows the deformed bodies
/// (ConstraintSpec::pairingDisplacement, solvedPairing): each slave node keeps its pairing or
/// takes the one at x + u (`deformed`: the mesh at x + u), by the rules of
/// ConstraintSpec::pairingDisplacement (DeformedPairing.cpp).
/// The mesh at x + u.
mesh::Mesh deformedMesh(const mesh::Mesh& mesh, const std::vector<std::array<double, 3>>& u);

InterfacePairs pairsOnTheDeformedBodies(const mesh::Mesh& mesh, const mesh::Mesh& deformed, const ConstraintSpec& spec,
                                        int index, const geometry::HeldAxes& held);

}  // namespace tribos::feti::rows
