#pragma once
/// \file SmoothedFaces.hpp
/// Curved surfaces from faceted ones for the mortar gap (Contact/Surface Geometry = Smoothed,
/// MortarCoupling.hpp). Nagata (2005): each edge of a
/// linear face (3-node triangle, 4-node quadrilateral) becomes the quadratic curve through its
/// two nodes whose tangents there are normal to the nodal normals, x(t) = x_a + d t - c t (1 - t)
/// with d = x_b - x_a and c in the plane of n_a, n_b solving c . n_a = d . n_a, c . n_b = -d . n_b;
/// the face is the linear interpolation minus the edges' c times their bubble functions (on a
/// triangle L_a L_b, on a quadrilateral (1 - s^2) (1 -+ r) / 8 with s along the edge).
///
/// Why: a circle of radius R in linear faces of size h has a sag of h^2 / (8 R) between its
/// nodes; two such surfaces with different divisions (a shaft and its bore meshed from CAD)
/// differ by that much, which is as large as a shrink fit's interference at h = 1 mm on R = 20
/// (0.006 against 0.01 mm): the fit force came out 26-43 % high on gmsh's hexahedra and
/// tetrahedra. The Nagata curve of a circle's chord with the circle's normals at its ends
/// deviates from the circle by O(h^4). The gap is then measured between the smoothed surfaces;
/// the mortar weights (the displacements' interpolation) stay those of the faces.
///
/// An edge whose normals are alike (|d . n| below 1e-12 |d| at both ends: a flat surface) or
/// differ by more than kCreaseAngle (a crease, not a curved surface) stays straight.
#include <array>

#include "tribos/geometry/FaceProjection.hpp"

namespace tribos::geometry {

/// Normals differing by more than this (radians) across an edge mark a crease: the edge stays
/// straight (a body's corner is not rounded).
inline constexpr double kCreaseAngle = 0.5;

/// The Nagata coefficient c of the edge from x_a to x_b with unit nodal normals n_a, n_b (zero
/// where it stays straight: header).
Vec3 nagataEdgeCoefficient(const Vec3& xa, const Vec3& xb, const Vec3& na, const Vec3& nb);

/// The displacement of a linear face's smoothed surface from the face at reference point xi:
/// x_smoothed(xi) = x_face(xi) + offset(xi).
class SmoothedFace {
 public:
  SmoothedFace() = default;
  /// `type` Tri3 or Quad4 (any other: no offset); x and n the vertices' positions and unit
  /// normals (face node order).
  SmoothedFace(mesh::FaceType type, const FaceCoordinates& x, const std::array<Vec3, 4>& n);
  Vec3 offset(double xi0, double xi1) const;

 private:
  mesh::FaceType type_ = mesh::FaceType::Tri6;
  std::array<Vec3, 4> edgeC_{};  ///< edge k from vertex k to vertex k + 1
  bool curved_ = false;
};

/// The reference point of a linear face from its shape function values (a triangle's
/// barycentric weights, a quadrilateral's bilinear ones: both reproduce the reference
/// coordinates exactly).
std::array<double, 2> referenceFromWeights(mesh::FaceType type, const std::array<double, kMaxMasterFaceNodes>& w);

}  // namespace tribos::geometry
