/// \file MortarNormalProjection.cpp
/// Projection along the slave's normal field (header).
#include "MortarNormalProjection.hpp"

#include <cmath>

#include "VectorMath.hpp"

namespace tribos::geometry {

namespace {
/// A Newton step below this (reference units) ends the steps.
constexpr double kStepTolerance = 1e-13;

/// Solves [a b c] z = r (columns a, b, c) by Cramer's rule; false if the columns are (nearly)
/// dependent.
bool solve3(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& r, Vec3& z) {
  auto det = [](const Vec3& p, const Vec3& q, const Vec3& s) {
    return p[0] * (q[1] * s[2] - q[2] * s[1]) - q[0] * (p[1] * s[2] - p[2] * s[1]) + s[0] * (p[1] * q[2] - p[2] * q[1]);
  };
  const double d = det(a, b, c);
  const double scale = norm(a) * norm(b) * norm(c);
  if (!(std::abs(d) > 1e-12 * scale)) return false;
  z = {det(r, b, c) / d, det(a, r, c) / d, det(a, b, r) / d};
  return true;
}
}  // namespace

Vec3 SlaveNormalField::at(const SlaveBasis& basis, double xi0, double xi1) const {
  Vec3 n{0.0, 0.0, 0.0};
  const mesh::FaceGeometry g = mesh::faceGeometry(basis.type(), basis.coordinates().data(), xi0, xi1);
  for (int k = 0; k < mesh::faceNodeCount(basis.type()); ++k)
    for (int c = 0; c < 3; ++c) n[c] += g.N[k] * nodal[k][c];
  return n;
}

bool normalsVary(const SlaveNormalField& field, int numNodes) {
  for (int k = 1; k < numNodes; ++k)
    if (norm(minus(field.nodal[k], field.nodal[0])) > 1e-12) return true;
  return false;
}

bool slavePointAlongNormal(const SlaveBasis& basis, const SlaveNormalField& field, const Vec3& y,
                           std::array<double, 2>& xi) {
  // Unknowns (xi0, xi1, g) of y = x(xi) + g n(xi); the Jacobian leaves out g dn/dxi (g is of the
  // gap's size, so the steps still contract by far more than needed).
  double g = 0.0;
  for (int step = 0; step < kMaxProjectionSteps; ++step) {
    const mesh::FaceGeometry geo = mesh::faceGeometry(basis.type(), basis.coordinates().data(), xi[0], xi[1]);
    const Vec3 n = field.at(basis, xi[0], xi[1]);
    Vec3 r = minus(y, geo.point);
    for (int c = 0; c < 3; ++c) r[c] -= g * n[c];
    Vec3 d;
    if (!solve3(geo.tangent0, geo.tangent1, n, r, d)) return false;
    xi = {xi[0] + d[0], xi[1] + d[1]};
    g += d[2];
    if (!(std::abs(xi[0]) + std::abs(xi[1]) < 1e3)) return false;
    if (std::abs(d[0]) + std::abs(d[1]) < kStepTolerance) return true;
  }
  return false;
}

bool masterPointAlongNormal(const MasterSurface& master, LO f, const Vec3& x, const Vec3& n,
                            MasterSurface::Projection& chi, std::array<double, 2>& reference) {
  const mesh::FaceNodes& face = master.faceNodes(f);
  const FaceCoordinates& coordinates = master.faceCoordinates(f);
  const mesh::FaceType type = mesh::faceType(face.numVertices, face.numNodes);
  const mesh::FaceTypeShape& shape = mesh::faceTypeShape(type);
  std::array<double, 2> eta{0.0, 0.0};
  for (int v = 0; v < shape.numVertices; ++v)
    for (int c = 0; c < 2; ++c) eta[c] += shape.referenceNodes[v][c] / shape.numVertices;
  double g = 0.0;
  for (int step = 0; step < kMaxProjectionSteps; ++step) {
    const mesh::FaceGeometry geo = mesh::faceGeometry(type, coordinates.data(), eta[0], eta[1]);
    // Unknowns (eta0, eta1, g) of X(eta) = x + g n.
    Vec3 r = minus(x, geo.point);
    for (int c = 0; c < 3; ++c) r[c] += g * n[c];
    Vec3 d;
    if (!solve3(geo.tangent0, geo.tangent1, {-n[0], -n[1], -n[2]}, r, d)) return false;
    eta = {eta[0] + d[0], eta[1] + d[1]};
    g += d[2];
    if (!(std::abs(eta[0]) + std::abs(eta[1]) < 1e3)) return false;
    if (std::abs(d[0]) + std::abs(d[1]) < kStepTolerance) {
      const mesh::FaceGeometry at = mesh::faceGeometry(type, coordinates.data(), eta[0], eta[1]);
      chi = MasterSurface::Projection{};
      chi.face = f;
      for (int k = 0; k < face.numNodes; ++k) {
        chi.nodes[k] = face.node[k];
        chi.weights[k] = at.N[k];
      }
      chi.point = at.point;
      chi.distance = norm(minus(at.point, x));
      chi.outcome.steps = step + 1;
      chi.outcome.lastStep = std::abs(d[0]) + std::abs(d[1]);
      reference = eta;
      return true;
    }
  }
  return false;
}

bool insideReferenceDomain(mesh::FaceType type, const std::array<double, 2>& xi, double slack) {
  if (type == mesh::FaceType::Quad4) return std::abs(xi[0]) <= 1.0 + slack && std::abs(xi[1]) <= 1.0 + slack;
  return xi[0] >= -slack && xi[1] >= -slack && xi[0] + xi[1] <= 1.0 + slack;
}

}  // namespace tribos::geometry
