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
  Vec3 x;
  double omega;
  std::array<double, mesh::kMaxFaceNodes> phi, psi;
};

/// The quadrature points of the slave face with `face`'s nodes at x.
std::vector<SlavePoint> slaveFacePoints(const mesh::FaceNodes& face, const FaceCoordinates& x);

}  // namespace tribos::geometry
