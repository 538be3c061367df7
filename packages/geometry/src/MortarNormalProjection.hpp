#pragma once
/// \file MortarNormalProjection.hpp
/// Projection along the slave's normal field for the segment-based mortar integrals (private
/// to the package; MortarSegments.hpp). Popp, Gee & Wall (2009) and Popp et al. (2010) map a
/// master node onto the slave face along the interpolated slave normals, and a slave point onto
/// the master along its own normal: the same line both ways, so the segments' pieces and their
/// points agree.
///
/// Why not the closest points: on a faceted curved fit the slave facets are parallel to the
/// master facets they face, offset by the interference δ, and a master vertex's closest point on
/// a slave facet lies δ tan(α/2) from the slave vertex facing it (α the angle between
/// neighbouring facets). The kink of the master's hat function then falls inside the slave
/// node's support, which reads a sliver of the next facet, and the weighted gap of every slave
/// node at a polygon corner came out 1.07e-5 mm off (0.1 % of δ), which cost 14 % of
/// the nodal pressure on the shrink fit of test/integration/shrink_fit.xml (hexahedra, 48 slave
/// against 24 master facets on the quarter circle). Along the normal field the master vertex
/// maps onto the slave vertex facing it.
///
/// The field is the contact normals of the face's paired nodes (ContactPair::normal, the
/// direction of their rows) interpolated with the face's shape functions. A face whose normals
/// are all alike keeps the closest points (the same line on a flat face, and its results bit for
/// bit as before).
#include <array>

#include "MortarQuadrature.hpp"
#include "tribos/geometry/MasterSurface.hpp"

namespace tribos::geometry {

/// The contact normals at the nodes of one slave face (face node order).
struct SlaveNormalField {
  std::array<Vec3, mesh::kMaxFaceNodes> nodal{};
  /// The interpolated normal (not of unit length) at reference point xi.
  Vec3 at(const SlaveBasis& basis, double xi0, double xi1) const;
};

/// Whether two of the face's nodal normals differ by more than round-off (1e-12): only then
/// does the field differ from the closest-point projection.
bool normalsVary(const SlaveNormalField& field, int numNodes);

/// The reference point xi of the slave face (extended beyond its edges) whose normal line
/// passes through y: y = x(xi) + g n(xi), by Newton steps from `xi` (a start near it, the closest
/// point). False where the steps degenerate or do not settle.
bool slavePointAlongNormal(const SlaveBasis& basis, const SlaveNormalField& field, const Vec3& y,
                           std::array<double, 2>& xi);

/// Where the line x + g n meets master face f (extended beyond its edges), as a projection on f:
/// its point, the master shape functions there, and |g n| as its distance. `reference` is set
/// to the point's reference coordinates on f. False where the line is parallel to the face or
/// the steps do not settle.
bool masterPointAlongNormal(const MasterSurface& master, LO f, const Vec3& x, const Vec3& n,
                            MasterSurface::Projection& chi, std::array<double, 2>& reference);

/// Whether reference point xi lies in the reference domain of `type`, to `slack`.
bool insideReferenceDomain(mesh::FaceType type, const std::array<double, 2>& xi, double slack);

}  // namespace tribos::geometry
