/// \file SurfaceNormals.cpp
/// Nodes and nodal normals of a side set (header).
#include "tribos/geometry/SurfaceNormals.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "VectorMath.hpp"
#include "tribos/mesh/ShapeFunctions.hpp"

namespace tribos::geometry {

using Vec3 = std::array<double, 3>;

std::vector<LO> sideSetNodes(const mesh::Mesh& mesh, const mesh::SideSet& set) {
  std::vector<LO> nodes;
  nodes.reserve(3 * set.elements.size());
  for (size_t f = 0; f < set.elements.size(); ++f)
    for (LO n : mesh.faceNodes(set.elements[f], set.sides[f])) nodes.push_back(n);
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  return nodes;
}

namespace {
constexpr double kPi = 3.14159265358979323846;

/// The angle between two vectors (0 where one is zero).
double angleBetween(const Vec3& a, const Vec3& b) {
  const double la = norm(a), lb = norm(b);
  if (!(la > 0.0 && lb > 0.0)) return 0.0;
  return std::acos(std::clamp(dot(a, b) / (la * lb), -1.0, 1.0));
}

/// The interior angle of a face's outline at vertex v (between the edges to its neighbours).
double vertexAngle(const mesh::Mesh& mesh, const mesh::FaceNodes& face, int v) {
  const Vec3& x = mesh.coords[face.node[v]];
  return angleBetween(minus(mesh.coords[face.node[(v + 1) % face.numVertices]], x),
                      minus(mesh.coords[face.node[(v + face.numVertices - 1) % face.numVertices]], x));
}

/// Adds a straight-sided face's unit normal (Mesh::faceNormal) times its corner angle at each
/// vertex to `normal`.
void addStraightFace(const mesh::Mesh& mesh, LO element, int side, std::vector<Vec3>& normal) {
  Vec3 n = mesh.faceNormal(element, side);
  const double length = norm(n);
  if (!(length > 0.0)) return;  // a degenerate face has no direction to give
  for (double& c : n) c /= length;
  const mesh::FaceNodes face = mesh.faceNodes(element, side);
  for (int v = 0; v < face.numVertices; ++v) {
    const double angle = vertexAngle(mesh, face, v);
    for (int d = 0; d < 3; ++d) normal[face.node[v]][d] += angle * n[d];
  }
}

/// The same for a quadratic face (a 6-node triangle), from its own geometry: at each node the
/// normal of the curved face there (tangent0 x tangent1 at the node's reference point: outward,
/// as the catalogue numbers a face's nodes), at a vertex the angle between its two curved edges'
/// tangents, pi at a mid-edge node (it lies on its edge: the same in both faces). Where the
/// mid-edge nodes follow a curved surface (gmsh's 10-node tetrahedra on a sphere) the chord
/// triangle's normal is off the surface's by about half the angle the face spans; the face's own
/// by its second-order error.
void addQuadraticFace(const mesh::Mesh& mesh, const mesh::FaceNodes& face, std::vector<Vec3>& normal) {
  const mesh::FaceType type = mesh::faceType(face.numVertices, face.numNodes);
  const mesh::FaceTypeShape& shape = mesh::faceTypeShape(type);
  std::array<Vec3, mesh::kMaxFaceNodes> x{};
  for (int k = 0; k < face.numNodes; ++k) x[k] = mesh.coords[face.node[k]];
  for (int k = 0; k < face.numNodes; ++k) {
    const double* xi = shape.referenceNodes[k];
    const mesh::FaceGeometry g = mesh::faceGeometry(type, x.data(), xi[0], xi[1]);
    const Vec3 n = g.normal();
    const double length = norm(n);
    if (!(length > 0.0)) continue;
    auto towards = [&](int other) {  // the tangent at node k towards vertex `other`
      const double d0 = shape.referenceNodes[other][0] - xi[0], d1 = shape.referenceNodes[other][1] - xi[1];
      return Vec3{g.tangent0[0] * d0 + g.tangent1[0] * d1, g.tangent0[1] * d0 + g.tangent1[1] * d1,
                  g.tangent0[2] * d0 + g.tangent1[2] * d1};
    };
    const int nv = face.numVertices;
    const double angle = k < nv ? angleBetween(towards((k + 1) % nv), towards((k + nv - 1) % nv)) : kPi;
    for (int d = 0; d < 3; ++d) normal[face.node[k]][d] += angle * n[d] / length;
  }
}
}  // namespace

std::vector<Vec3> summedFaceNormals(const mesh::Mesh& mesh, const mesh::SideSet& set) {
  std::vector<Vec3> normal(mesh.numNodes(), Vec3{0.0, 0.0, 0.0});
  for (size_t f = 0; f < set.elements.size(); ++f) {
    // Every node of the face: a 6-node triangle's mid-edge nodes are contact nodes too, and
    // the master normal is interpolated with its quadratic shape functions.
    const mesh::FaceNodes face = mesh.faceNodes(set.elements[f], set.sides[f]);
    if (face.numNodes > face.numVertices)
      addQuadraticFace(mesh, face, normal);
    else
      addStraightFace(mesh, set.elements[f], set.sides[f], normal);
  }
  return normal;
}

Vec3 inSymmetryPlanes(Vec3 normal, std::uint8_t heldAxes) {
  if (heldAxes == 0) return normal;
  for (int c = 0; c < 3; ++c)
    if ((heldAxes >> c & 1) && std::abs(normal[c]) < 0.2) normal[c] = 0.0;
  const double length = norm(normal);
  if (length > 0.0)
    for (double& c : normal) c /= length;
  return normal;
}

std::vector<Vec3> unitNodalNormals(const mesh::Mesh& mesh, const mesh::SideSet& set, const HeldAxes& held) {
  if (!held.empty() && held.size() != static_cast<size_t>(mesh.numNodes()))
    throw std::invalid_argument("unitNodalNormals: held axes for " + std::to_string(held.size()) + " nodes, the mesh has " +
                                std::to_string(mesh.numNodes()));
  auto n = summedFaceNormals(mesh, set);
  for (size_t node = 0; node < n.size(); ++node) {
    Vec3& v = n[node];
    const double length = norm(v);
    if (length > 0.0)
      for (double& c : v) c /= length;
    if (!held.empty() && length > 0.0) v = inSymmetryPlanes(v, held[node]);
  }
  return n;
}

double coordinateScale(const mesh::Mesh& mesh) {
  double scale = 1.0;
  for (const auto& x : mesh.coords) scale = std::max({scale, std::abs(x[0]), std::abs(x[1]), std::abs(x[2])});
  return scale;
}

}  // namespace tribos::geometry
