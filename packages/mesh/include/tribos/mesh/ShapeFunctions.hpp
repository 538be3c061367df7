#pragma once
/// \file ShapeFunctions.hpp
/// Isoparametric shape functions and quadrature of the element types (ElementTypes.hpp) and of
/// their faces: what the element kernels, the element checks and the face loads share.
/// Reference elements: tetrahedra on the unit simplex (r, s, t >= 0, r + s + t <= 1),
/// hexahedra on [-1, 1]^3, prisms on the unit triangle (r, s) times t in [-1, 1].
#include <array>
#include <vector>

#include "tribos/mesh/ElementTypes.hpp"

namespace tribos::mesh {

struct QuadraturePoint {
  double xi[3];
  double weight;
};

/// The rule an element's stiffness is integrated with: exact for undistorted elements
/// (1 point for the linear tetrahedron, 4 for the quadratic, 2x2x2 Gauss for the hexahedron,
/// 3 x 2 for the prism).
const std::vector<QuadraturePoint>& volumeRule(ElementType type);

/// N[k] and dN[k][d] = dN_k/dxi_d at the reference point xi (k < numNodes of the type).
void shapeFunctions(ElementType type, const double xi[3], double N[], double dN[][3]);

/// The Jacobian J[d][i] = dx_d/dxi_i at xi of the element with nodes x, and its
/// determinant; dN as shapeFunctions gives it.
double jacobian(ElementType type, const double (*x)[3], const double dN[][3], double J[3][3]);

/// The reference coordinates of node k of a type (vertices, then mid-edge nodes).
void referenceNode(ElementType type, int k, double xi[3]);

/// Stresses at the nodes from their values at the volumeRule points, row-major E[k][q]
/// (numNodes x number of points): the least-squares fit of the point values by the vertex
/// (linear) shape functions of the type's family, evaluated at node k. Square, so an exact
/// interpolation, for every type with more than one point (8 Gauss points and the trilinear
/// functions of the hexahedron, 3 x 2 and the prism's, 4 and the linear tetrahedron's for the
/// quadratic one, whose strain is linear); the one-point tetrahedron keeps its constant.
const std::vector<double>& nodalExtrapolation(ElementType type);

/// Volume (the sum of det J over volumeRule) and the smallest det J at the quadrature points
/// and at the vertices, times the reference volume: a negative one marks an inverted corner.
struct ElementMeasure {
  double volume;
  double smallestScaledJacobian;
};
ElementMeasure elementMeasure(ElementType type, const double (*x)[3]);

/// Face shapes: a 3-node or 6-node triangle on the unit triangle, a 4-node quadrilateral on
/// [-1, 1]^2 (nodes at (-1,-1), (1,-1), (1,1), (-1,1)).
enum class FaceType { Tri3, Tri6, Quad4 };
FaceType faceType(int numVertices, int numNodes);
/// A rule exact for the consistent load of a constant traction on a flat face (degree 2).
const std::vector<QuadraturePoint>& faceRule(FaceType type);
/// N[k] and dN[k][0..1] at the reference point xi (xi[2] unused).
void faceShapeFunctions(FaceType type, const double xi[3], double N[], double dN[][3]);

/// A face's geometry at a reference point: its shape functions there, the point X and the
/// tangents dX/dxi_0, dX/dxi_1 (their cross product, in the face's node order, points out of
/// the element, its length the area element).
struct FaceGeometry {
  std::array<double, kMaxFaceNodes> N;
  std::array<double, 3> point, tangent0, tangent1;
  std::array<double, 3> normal() const;
  double areaElement() const;
};
/// The geometry of the face with nodes x (vertices first, as FaceNodes) at (xi0, xi1).
FaceGeometry faceGeometry(FaceType type, const std::array<double, 3>* x, double xi0, double xi1);
/// Nodes of a face type: 3, 6 or 4.
int faceNodeCount(FaceType type);

/// The face catalogue: a face type's nodes on its reference cell and how the closest point of
/// a face to a point is found (geometry/MasterSurface.hpp): among the triangles the face is
/// searched as, then, on a curved face, by Gauss-Newton steps on the face itself.
struct FaceTypeShape {
  const char* description;        ///< in messages: "4-node quadrilateral"
  int numVertices, numNodes;
  double referenceNodes[kMaxFaceNodes][2];  ///< (xi0, xi1) of each node, vertices first
  int numSearchTriangles;
  int searchTriangles[4][3];      ///< face node indices of each search triangle
  bool curved;                    ///< not flat in general: Gauss-Newton steps follow the triangle search
};
const FaceTypeShape& faceTypeShape(FaceType type);

}  // namespace tribos::mesh
