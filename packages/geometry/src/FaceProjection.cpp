/// \file FaceProjection.cpp
/// Closest points on faces (header): the Voronoi regions of a triangle, and one Gauss-Newton
/// loop for the curved faces with a step rule per reference domain.
#include "tribos/geometry/FaceProjection.hpp"

#include <algorithm>
#include <cmath>

#include "VectorMath.hpp"
#include "tribos/core/Format.hpp"

namespace tribos::geometry {

std::string describe(const FaceProjectionOutcome& outcome) {
  const std::string steps = "the projection on a curved master face stopped after " +
                            std::to_string(outcome.steps) + " Gauss-Newton steps";
  switch (outcome.status) {
    case FaceProjectionStatus::Converged:
      return steps + " (converged)";
    case FaceProjectionStatus::Degenerate:
      return steps + " where the face's tangents are linearly dependent (a degenerate face)";
    case FaceProjectionStatus::Unsettled:
      break;
  }
  return steps + ", the last one still " + core::formatNumber(outcome.lastStep) + " reference units (not settled)";
}

std::array<double, 3> closestPointOnTriangle(const Vec3& x, const Vec3& a, const Vec3& b, const Vec3& c) {
  // Voronoi regions of the vertices, then of the edges, else the interior; each test uses
  // the dot products of the edge vectors with x - vertex, so vertex and edge regions give
  // exact 0 / 1 weights (matching meshes pair node-to-node exactly).
  const Vec3 ab = minus(b, a), ac = minus(c, a), ax = minus(x, a);
  const double d1 = dot(ab, ax), d2 = dot(ac, ax);
  if (d1 <= 0.0 && d2 <= 0.0) return {1.0, 0.0, 0.0};
  const Vec3 bx = minus(x, b);
  const double d3 = dot(ab, bx), d4 = dot(ac, bx);
  if (d3 >= 0.0 && d4 <= d3) return {0.0, 1.0, 0.0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    const double t = d1 / (d1 - d3);
    return {1.0 - t, t, 0.0};
  }
  const Vec3 cx = minus(x, c);
  const double d5 = dot(ab, cx), d6 = dot(ac, cx);
  if (d6 >= 0.0 && d5 <= d6) return {0.0, 0.0, 1.0};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    const double t = d2 / (d2 - d6);
    return {1.0 - t, 0.0, t};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) {
    const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0.0, 1.0 - t, t};
  }
  const double inverse = 1.0 / (va + vb + vc);
  const double v = vb * inverse, w = vc * inverse;
  return {1.0 - v - w, v, w};
}

namespace {
/// The Gauss-Newton model of |X(xi) - target|^2 at one point: the metric [a b; b c] of the
/// tangents, the gradient (g0, g1) and the metric's determinant.
struct GaussNewtonModel {
  double a, b, c, g0, g1, det;
};

/// One step within the square [-1, 1]^2 (a bilinear quadrilateral). A step that would leave
/// it along one coordinate stops at its edge, and the other coordinate takes the model's step
/// with the first one fixed there. Returns |d xi| + |d eta|.
double stepWithinSquare(const GaussNewtonModel& m, double& xi, double& eta) {
  double step0 = -(m.c * m.g0 - m.b * m.g1) / m.det, step1 = -(m.a * m.g1 - m.b * m.g0) / m.det;
  const bool outXi = std::abs(xi + step0) > 1.0, outEta = std::abs(eta + step1) > 1.0;
  if (outXi && !outEta) {
    step0 = std::clamp(xi + step0, -1.0, 1.0) - xi;
    step1 = std::clamp(eta - (m.g1 + m.b * step0) / m.c, -1.0, 1.0) - eta;
  } else if (outEta && !outXi) {
    step1 = std::clamp(eta + step1, -1.0, 1.0) - eta;
    step0 = std::clamp(xi - (m.g0 + m.b * step1) / m.a, -1.0, 1.0) - xi;
  } else if (outXi && outEta) {
    step0 = std::clamp(xi + step0, -1.0, 1.0) - xi;
    step1 = std::clamp(eta + step1, -1.0, 1.0) - eta;
  }
  xi += step0;
  eta += step1;
  return std::abs(step0) + std::abs(step1);
}

/// One step within the unit triangle (a 6-node triangle). A step that would leave it stops on
/// the edge it crosses (r = 0, s = 0 or r + s = 1), and the position along that edge takes the
/// model's step restricted to it. Returns |d r| + |d s|.
double stepWithinTriangle(const GaussNewtonModel& m, double& r, double& s) {
  double nr = r - (m.c * m.g0 - m.b * m.g1) / m.det, ns = s - (m.a * m.g1 - m.b * m.g0) / m.det;
  if (nr < 0.0) {  // on r = 0: the model's step in s with r's step fixed at -r
    nr = 0.0;
    ns = std::clamp(s - (m.g1 - m.b * r) / m.c, 0.0, 1.0);
  } else if (ns < 0.0) {  // on s = 0
    ns = 0.0;
    nr = std::clamp(r - (m.g0 - m.b * s) / m.a, 0.0, 1.0);
  } else if (nr + ns > 1.0) {  // on r + s = 1: move along (1, -1) from (r, 1 - r)
    const double k = 1.0 - r - s, curvature = m.a - 2.0 * m.b + m.c;
    const double u = curvature > 0.0 ? -((m.g0 - m.g1) + k * (m.b - m.c)) / curvature : 0.0;
    nr = std::clamp(r + u, 0.0, 1.0);
    ns = 1.0 - nr;
  }
  const double change = std::abs(nr - r) + std::abs(ns - s);
  r = nr;
  s = ns;
  return change;
}

/// Steps this small (reference units) end the iteration: the point no longer moves.
constexpr double kStationaryStep = 1e-15;
}  // namespace

FaceProjectionOutcome closestPointOnCurvedFace(mesh::FaceType type, const FaceCoordinates& x, const Vec3& target,
                                               double& xi0, double& xi1) {
  FaceProjectionOutcome outcome;
  for (int step = 0; step < kMaxProjectionSteps; ++step) {
    const mesh::FaceGeometry g = mesh::faceGeometry(type, x.data(), xi0, xi1);
    const Vec3 residual = minus(g.point, target);
    GaussNewtonModel m;
    m.a = dot(g.tangent0, g.tangent0);
    m.b = dot(g.tangent0, g.tangent1);
    m.c = dot(g.tangent1, g.tangent1);
    m.g0 = dot(g.tangent0, residual);
    m.g1 = dot(g.tangent1, residual);
    m.det = m.a * m.c - m.b * m.b;
    if (!(m.det > 0.0)) {
      outcome.status = FaceProjectionStatus::Degenerate;
      return outcome;
    }
    ++outcome.steps;
    outcome.lastStep = type == mesh::FaceType::Quad4 ? stepWithinSquare(m, xi0, xi1) : stepWithinTriangle(m, xi0, xi1);
    if (outcome.lastStep < kStationaryStep) return outcome;
  }
  if (outcome.lastStep > kProjectionTolerance) outcome.status = FaceProjectionStatus::Unsettled;
  return outcome;
}

}  // namespace tribos::geometry
