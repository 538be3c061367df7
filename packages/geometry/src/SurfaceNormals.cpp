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

std::vector<Vec3> summedFaceNormals(const mesh::Mesh& mesh, const mesh::SideSet& set) {
  std::vector<Vec3> normal(mesh.numNodes(), Vec3{0.0, 0.0, 0.0});
  for (size_t f = 0; f < set.elements.size(); ++f) {
    const Vec3 n = mesh.faceNormal(set.elements[f], set.sides[f]);
    // Every node of the face: a 6-node triangle's mid-edge nodes are contact nodes too, and
    // the master normal is interpolated with its quadratic shape functions.
    for (LO node : mesh.faceNodes(set.elements[f], set.sides[f]))
      for (int d = 0; d < 3; ++d) normal[node][d] += n[d];
  }
  return normal;
}

std::vector<Vec3> unitNodalNormals(const mesh::Mesh& mesh, const mesh::SideSet& set) {
  auto n = summedFaceNormals(mesh, set);
  for (auto& v : n) {
    const double length = norm(v);
    if (length > 0.0)
      for (double& c : v) c /= length;
  }
  return n;
}

double coordinateScale(const mesh::Mesh& mesh) {
  double scale = 1.0;
  for (const auto& x : mesh.coords) scale = std::max({scale, std::abs(x[0]), std::abs(x[1]), std::abs(x[2])});
  return scale;
}

}  // namespace tribos::geometry
