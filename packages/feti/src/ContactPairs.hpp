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
  /// The gaps measured on the smoothed surfaces (ContactInterfaceRows::smoothedSurfaces), and
  /// whether Surface Geometry = Automatic chose them (facetsDominate).
  bool smoothed = false, smoothedByChoice = false;
  double searchDistance = 0.0;  ///< the reach its search had (searchReach)
};

/// The search distance of interface `spec` on `mesh`: its Search Distance, or where that is 0
/// (the default), the size of the slave surface's largest face (the largest distance between
/// two nodes of a face): a gap that may close within the elements' own scale is searched, a
/// node a face or more away is not (a clearance larger than that is given by the user).
double searchReach(const mesh::Mesh& mesh, const ContactInterfaceSpec& spec);

/// Per node, the axes a displacement condition holds it along while it is free along another
/// (geometry::HeldAxes: the nodes on symmetry planes, whose contact normals lie in them).
geometry::HeldAxes heldAxes(const Prescribed& prescribed);

/// The search and the master sides of interface `spec` on `mesh` (ContactRows.cpp); `held` as
/// heldAxes gives it. Surface Geometry = Automatic is decided here, on this mesh: a caller
/// that searches the deformed bodies passes the reference's choice (DeformedPairing.cpp).
InterfacePairs pairsOf(const mesh::Mesh& mesh, const ContactInterfaceSpec& spec, const geometry::HeldAxes& held);

/// Surface Geometry = Automatic takes the smoothed surfaces where both hold:
/// - facetsDominate: the master's facets sag between its nodes (the largest
///   geometry::MortarRow::facetSag of `faceted`, rows measured on the faces) by a tenth or more
///   of the fit the interface closes (its largest initial overlap, Interference added to every
///   overlap): a fit whose facets count as gap. Never on an interface with nothing to close (a
///   Hertz contact, a clearance) nor on a bonded one.
/// - smoothedFitsBetter: the overlaps of that fit are more even on the smoothed surfaces than on
///   the faces (the range of the overlaps). A fit meshed on a curved surface (a shaft in a bore
///   from CAD: both sides' nodes on circles) has even overlaps between smooth surfaces; a fit
///   meant to be faceted (a polygon in its offset) has them even between the faces.
/// doc/contact_surfaces.md, "Faceted curved surfaces".
bool facetsDominate(const mesh::Mesh& mesh, const ContactInterfaceSpec& spec,
                    const std::vector<geometry::MortarRow>& faceted);
bool smoothedFitsBetter(const mesh::Mesh& mesh, const ContactInterfaceSpec& spec,
                        const std::vector<geometry::MortarRow>& faceted,
                        const std::vector<geometry::MortarRow>& smoothed);

/// The mesh at x + u.
mesh::Mesh deformedMesh(const mesh::Mesh& mesh, const std::vector<std::array<double, 3>>& u);

/// The pairs of interface `index` of `spec` when the pairing follows the deformed bodies
/// (ConstraintSpec::pairingDisplacement, solvedPairing): each slave node keeps its pairing or
/// takes the one at x + u (`deformed`: the mesh at x + u), by the rules of
/// ConstraintSpec::pairingDisplacement (DeformedPairing.cpp).
InterfacePairs pairsOnTheDeformedBodies(const mesh::Mesh& mesh, const mesh::Mesh& deformed, const ConstraintSpec& spec,
                                        int index, const geometry::HeldAxes& held);

}  // namespace tribos::feti::rows
