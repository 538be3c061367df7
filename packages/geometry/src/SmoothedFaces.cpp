/// \file SmoothedFaces.cpp
/// Nagata's curved faces (header).
#include "tribos/geometry/SmoothedFaces.hpp"

#include <cmath>

#include "VectorMath.hpp"

namespace tribos::geometry {

Vec3 nagataEdgeCoefficient(const Vec3& xa, const Vec3& xb, const Vec3& na, const Vec3& nb) {
  const Vec3 d = minus(xb, xa);
  const double length = norm(d);
  const double da = dot(d, na), db = dot(d, nb);
  if (std::abs(da) <= 1e-12 * length && std::abs(db) <= 1e-12 * length) return {0.0, 0.0, 0.0};
  const double gamma = dot(na, nb);
  if (!(gamma >= std::cos(kCreaseAngle))) return {0.0, 0.0, 0.0};
  // c = p n_a + q n_b with [1 gamma; gamma 1] (p, q) = (d.n_a, -d.n_b).
  const double det = 1.0 - gamma * gamma;
  if (!(det > 1e-14)) return {0.0, 0.0, 0.0};  // parallel normals but d not in their plane: no curve fits
  const double p = (da + gamma * db) / det, q = (-db - gamma * da) / det;
  return {p * na[0] + q * nb[0], p * na[1] + q * nb[1], p * na[2] + q * nb[2]};
}

SmoothedFace::SmoothedFace(mesh::FaceType type, const FaceCoordinates& x, const std::array<Vec3, 4>& n)
    : type_(type) {
  const int vertices = type == mesh::FaceType::Tri3 ? 3 : type == mesh::FaceType::Quad4 ? 4 : 0;
  for (int k = 0; k < vertices; ++k) {
    edgeC_[k] = nagataEdgeCoefficient(x[k], x[(k + 1) % vertices], n[k], n[(k + 1) % vertices]);
    curved_ = curved_ || edgeC_[k] != Vec3{0.0, 0.0, 0.0};
  }
}

Vec3 SmoothedFace::offset(double xi0, double xi1) const {
  Vec3 o{0.0, 0.0, 0.0};
  if (!curved_) return o;
  std::array<double, 4> bubble{};
  if (type_ == mesh::FaceType::Tri3) {
    const double L[3] = {1.0 - xi0 - xi1, xi0, xi1};
    for (int k = 0; k < 3; ++k) bubble[k] = L[k] * L[(k + 1) % 3];
  } else {
    // Vertices (-1,-1), (1,-1), (1,1), (-1,1): edges along xi0 at xi1 = -1, along xi1 at xi0 = 1, ...
    bubble[0] = (1.0 - xi0 * xi0) * (1.0 - xi1) / 8.0;
    bubble[1] = (1.0 - xi1 * xi1) * (1.0 + xi0) / 8.0;
    bubble[2] = (1.0 - xi0 * xi0) * (1.0 + xi1) / 8.0;
    bubble[3] = (1.0 - xi1 * xi1) * (1.0 - xi0) / 8.0;
  }
  // Along an edge t (1 - t) = (1 - s^2) / 4 with s in [-1, 1]; the blend across is (1 -+ r) / 2.
  for (int k = 0; k < 4; ++k)
    for (int c = 0; c < 3; ++c) o[c] -= bubble[k] * edgeC_[k][c];
  return o;
}

std::array<double, 2> referenceFromWeights(mesh::FaceType type, const std::array<double, kMaxMasterFaceNodes>& w) {
  if (type == mesh::FaceType::Tri3) return {w[1], w[2]};
  const double xi0 = -w[0] + w[1] + w[2] - w[3], xi1 = -w[0] - w[1] + w[2] + w[3];
  return {xi0, xi1};
}

}  // namespace tribos::geometry
