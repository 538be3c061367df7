/// \file SurfaceBoundary.cpp
/// The boundary of a master surface and the points beside it (header).
#include "SurfaceBoundary.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "VectorMath.hpp"

namespace tribos::geometry {

namespace {
/// The corner nodes of edge k of a face, the smaller first.
std::pair<LO, LO> edgeKey(const mesh::FaceNodes& face, int k) {
  const LO a = face.node[k], b = face.node[(k + 1) % face.numVertices];
  return {std::min(a, b), std::max(a, b)};
}

/// Whether node v of a face lies on its edge k (its two corners, and its mid-edge node).
bool onEdge(const mesh::FaceNodes& face, int v, int k) {
  return v == k || v == (k + 1) % face.numVertices || (face.numNodes == 6 && v == 3 + k);
}
}  // namespace

std::vector<std::uint8_t> boundaryEdges(const std::vector<mesh::FaceNodes>& faces) {
  std::map<std::pair<LO, LO>, int> uses;
  for (const auto& face : faces)
    for (int k = 0; k < face.numVertices; ++k) ++uses[edgeKey(face, k)];
  std::vector<std::uint8_t> edges(faces.size(), 0);
  for (size_t f = 0; f < faces.size(); ++f)
    for (int k = 0; k < faces[f].numVertices; ++k)
      if (uses[edgeKey(faces[f], k)] == 1) edges[f] |= static_cast<std::uint8_t>(1 << k);
  return edges;
}

double besideTheSurface(const mesh::FaceNodes& face, const FaceCoordinates& coords, std::uint8_t edges,
                        const std::array<double, kMaxMasterFaceNodes>& weights, const Vec3& point,
                        const Vec3& normal, const Vec3& x) {
  constexpr double kOnTheEdge = 1e-9;  // shape functions of the nodes off an edge vanish on it
  Vec3 centre{0.0, 0.0, 0.0};
  for (int v = 0; v < face.numVertices; ++v)
    for (int d = 0; d < 3; ++d) centre[d] += coords[v][d] / face.numVertices;
  double beside = 0.0;
  for (int k = 0; k < face.numVertices; ++k) {
    if (!(edges & (1 << k))) continue;
    bool on = true;
    for (int v = 0; v < face.numNodes && on; ++v) on = onEdge(face, v, k) || std::abs(weights[v]) <= kOnTheEdge;
    if (!on) continue;
    // The outward co-normal: from the face's centre to the edge, perpendicular to the edge
    // (its chord) and to the normal.
    const Vec3& a = coords[k];
    const Vec3 along = minus(coords[(k + 1) % face.numVertices], a);
    const double length2 = dot(along, along);
    if (!(length2 > 0.0)) continue;
    Vec3 coNormal = minus(a, centre);
    const double t = dot(coNormal, along) / length2;
    for (int d = 0; d < 3; ++d) coNormal[d] -= t * along[d];
    const double n = dot(coNormal, normal);  // after the chord: the normal is (nearly) across it
    for (int d = 0; d < 3; ++d) coNormal[d] -= n * normal[d];
    const double size = norm(coNormal);
    if (!(size > 0.0)) continue;
    beside = std::max(beside, dot(minus(x, point), coNormal) / size);
  }
  return beside;
}

}  // namespace tribos::geometry
