/// \file SurfaceNormals.cpp
/// Nodes and nodal normals of a side set (header).
#include "tribos/geometry/SurfaceNormals.hpp"

#include <algorithm>
#include <cmath>

#include "VectorMath.hpp"

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

/// The interior angle of a face's outline at vertex v (between the edges to its neighbours).
double vertexAngle(const mesh::Mesh& mesh, const mesh::FaceNodes& face, int v) {
  const Vec3& x = mesh.coords[face.node[v]];
  const Vec3 a = minus(mesh.coords[face.node[(v + 1) % face.numVertices]], x);
  const Vec3 b = minus(mesh.coords[face.node[(v + face.numVertices - 1) % face.numVertices]], x);
  const double la = norm(a), lb = norm(b);
  if (!(la > 0.0 && lb > 0.0)) return 0.0;
  return std::acos(std::clamp(dot(a, b) / (la * lb), -1.0, 1.0));
}
}  // namespace

std::vector<Vec3> summedFaceNormals(const mesh::Mesh& mesh, const mesh::SideSet& set) {
  std::vector<Vec3> normal(mesh.numNodes(), Vec3{0.0, 0.0, 0.0});
  for (size_t f = 0; f < set.elements.size(); ++f) {
    Vec3 n = mesh.faceNormal(set.elements[f], set.sides[f]);
    const double length = norm(n);
    if (!(length > 0.0)) continue;  // a degenerate face has no direction to give
    for (double& c : n) c /= length;
    // Every node of the face: a 6-node triangle's mid-edge nodes are contact nodes too, and
    // the master normal is interpolated with its quadratic shape functions. A mid-edge node
    // lies on its edge (the angle there is a straight one, the same in both faces).
    const mesh::FaceNodes face = mesh.faceNodes(set.elements[f], set.sides[f]);
    for (int k = 0; k < face.numNodes; ++k) {
      const double angle = k < face.numVertices ? vertexAngle(mesh, face, k) : kPi;
      for (int d = 0; d < 3; ++d) normal[face.node[k]][d] += angle * n[d];
    }
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
  auto n = summedFaceNormals(mesh, set);
  for (size_t node = 0; node < n.size(); ++node) {
    Vec3& v = n[node];
    const double length = norm(v);
    if (length > 0.0)
      for (double& c : v) c /= length;
    if (node < held.size() && length > 0.0) v = inSymmetryPlanes(v, held[node]);
  }
  return n;
}

double coordinateScale(const mesh::Mesh& mesh) {
  double scale = 1.0;
  for (const auto& x : mesh.coords) scale = std::max({scale, std::abs(x[0]), std::abs(x[1]), std::abs(x[2])});
  return scale;
}

}  // namespace tribos::geometry
