#pragma once
/// \file MortarQuadrature.hpp
/// Quadrature on a slave face for the dual mortar integrals (private to the package;
/// MortarCoupling.hpp says what is integrated): points, weights, the slave basis phi and its
/// dual psi. A 3-node triangle is cut into kSubdivisions^2 sub-triangles with the 3-point rule
/// exact for quadratics on each (psi = 4 phi - 1); a quadrilateral into kSubdivisions^2
/// sub-squares of its reference square with 2 x 2 Gauss points each (psi = D M^{-1} phi per
/// face, the bilinear dual basis); a 6-node triangle into the sub-triangles with the 6-point
/// rule exact for quartics (the dual of the transformed quadratic basis).
#include <array>
#include <vector>

#include "tribos/geometry/FaceProjection.hpp"
#include "tribos/mesh/ElementTypes.hpp"

namespace tribos::geometry {

/// One quadrature point on a slave face: where it is, its weight times the area element, and
/// the slave shape functions phi_v and their duals psi_v at it (node order of the face).
struct SlavePoint {
  std::array<double, 2> xi;  ///< reference coordinates on the face
  Vec3 x;
  double omega;
  std::array<double, mesh::kMaxFaceNodes> phi, psi;
};

/// The slave basis of one face and its dual, at any point of the face's reference domain
/// (mesh::faceTypeShape: the unit triangle, or the square [-1, 1]^2): psi = A phi with A =
/// 4 I - 1 1^T on a 3-node triangle (psi = 4 phi - 1), A = D M^{-1} on the other faces.
class SlaveBasis {
 public:
  SlaveBasis(const mesh::FaceNodes& face, const FaceCoordinates& x);
  mesh::FaceType type() const { return type_; }
  const FaceCoordinates& coordinates() const { return x_; }
  /// The point at reference coordinates (xi0, xi1), its weight `referenceWeight` (an area of
  /// the reference domain) times the area element there.
  SlavePoint at(double xi0, double xi1, double referenceWeight) const;

 private:
  mesh::FaceType type_;
  FaceCoordinates x_;
  std::array<std::array<double, mesh::kMaxFaceNodes>, mesh::kMaxFaceNodes> dual_{};  ///< A
};

/// The quadrature points of the slave face with `face`'s nodes at x (the composite rules of
/// the header): every point of the face, for D_i = int phi_i and for element-based integration.
std::vector<SlavePoint> slaveFacePoints(const mesh::FaceNodes& face, const FaceCoordinates& x);

/// A point of a rule on the unit triangle: barycentric coordinates and a fraction of its area.
struct TrianglePoint {
  std::array<double, 3> lambda;
  double weight;
};
/// Dunavant's 6-point rule, exact for polynomials of degree 4 on a triangle.
const std::array<TrianglePoint, 6>& quarticTriangleRule();

}  // namespace tribos::geometry
