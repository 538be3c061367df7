// Closest points on curved faces (geometry/FaceProjection.hpp): the one Gauss-Newton loop
// against a brute-force sample of the face on warped quadrilaterals and bowed 6-node
// triangles, for targets over the face, beyond its edges and beyond its corners; and the
// outcome it reports where the steps cannot settle (a face whose tangents are parallel).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "tribos/geometry/FaceProjection.hpp"

using namespace tribos;
using geometry::FaceCoordinates;
using geometry::Vec3;

namespace {
double distance(const Vec3& a, const Vec3& b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

/// The smallest distance from target to the face over a fine grid of its reference domain.
double bruteForceDistance(mesh::FaceType type, const FaceCoordinates& x, const Vec3& target) {
  const int n = 400;
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      double xi0 = double(i) / n, xi1 = double(j) / n;
      if (type == mesh::FaceType::Quad4) {
        xi0 = 2 * xi0 - 1;
        xi1 = 2 * xi1 - 1;
      } else if (xi0 + xi1 > 1.0) {
        continue;
      }
      best = std::min(best, distance(mesh::faceGeometry(type, x.data(), xi0, xi1).point, target));
    }
  return best;
}

/// Projects 40 random targets from `box` (x and y ranges, then the height range) on the face
/// and checks each against brute force; returns how many did not settle. A projection that
/// did not settle is reported as Unsettled, never as converged, and its point is still no
/// farther than the brute-force sample's.
int expectClosestAgainstBruteForce(mesh::FaceType type, const FaceCoordinates& x, double start0, double start1,
                                   const std::array<double, 4>& box) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> u(box[0], box[1]), height(box[2], box[3]);
  int unsettled = 0;
  for (int sample = 0; sample < 40; ++sample) {
    const Vec3 target{u(random), u(random), height(random)};
    double xi0 = start0, xi1 = start1;
    const auto outcome = geometry::closestPointOnCurvedFace(type, x, target, xi0, xi1);
    if (!outcome.settled()) {
      ++unsettled;
      EXPECT_EQ(outcome.status, geometry::FaceProjectionStatus::Unsettled) << geometry::describe(outcome);
      EXPECT_EQ(outcome.steps, geometry::kMaxProjectionSteps);
      EXPECT_GT(outcome.lastStep, geometry::kProjectionTolerance);
    }
    const double found = distance(mesh::faceGeometry(type, x.data(), xi0, xi1).point, target);
    // The grid's spacing bounds how much closer brute force can get; never farther than it.
    EXPECT_LE(found, bruteForceDistance(type, x, target) + 1e-12)
        << "target (" << target[0] << ", " << target[1] << ", " << target[2] << ")";
  }
  return unsettled;
}
}  // namespace

TEST(FaceProjection, warpedQuadrilateralMatchesBruteForce) {
  // Targets over the face, beyond its edges and corners, up to 0.6 off it: all settle.
  const FaceCoordinates x{{{0, 0, 0}, {1, 0, 0.2}, {1.1, 1, -0.1}, {0, 0.9, 0.25}}};
  EXPECT_EQ(expectClosestAgainstBruteForce(mesh::FaceType::Quad4, x, 0.0, 0.0, {-0.8, 1.8, -0.6, 0.6}), 0);
}

TEST(FaceProjection, bowedSixNodeTriangleMatchesBruteForce) {
  // Targets near the face (within a tenth of its size off it, as slave nodes and quadrature
  // points are) settle. Far targets (up to 0.6 off it, beyond its edges) need not: Gauss-Newton
  // converges only linearly where the residual is large against the face's curvature, and the
  // cap of 50 steps leaves some unsettled (measured: 2 of these 40, last steps 1.6e-7 and
  // 2.1e-5) — reported as Unsettled, their points still as close as brute force finds.
  const FaceCoordinates x{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.5, 0, 0.12}, {0.5, 0.5, -0.1}, {0, 0.5, 0.08}}};
  EXPECT_EQ(expectClosestAgainstBruteForce(mesh::FaceType::Tri6, x, 1.0 / 3, 1.0 / 3, {0.0, 0.5, -0.1, 0.1}), 0);
  const int farUnsettled =
      expectClosestAgainstBruteForce(mesh::FaceType::Tri6, x, 1.0 / 3, 1.0 / 3, {-0.8, 1.8, -0.6, 0.6});
  RecordProperty("far_targets_unsettled", farUnsettled);
}

TEST(FaceProjection, parallelTangentsAreReportedDegenerate) {
  // All four nodes on one line: the tangents are parallel everywhere, no step is defined.
  const FaceCoordinates x{{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}}};
  double xi0 = 0.0, xi1 = 0.0;
  const auto outcome = geometry::closestPointOnCurvedFace(mesh::FaceType::Quad4, x, {1.0, 1.0, 0.0}, xi0, xi1);
  EXPECT_EQ(outcome.status, geometry::FaceProjectionStatus::Degenerate);
  EXPECT_FALSE(outcome.settled());
  EXPECT_EQ(outcome.steps, 0);
  EXPECT_NE(geometry::describe(outcome).find("degenerate"), std::string::npos) << geometry::describe(outcome);
}

TEST(FaceProjection, aFlatQuadrilateralSettlesInFewSteps) {
  // A flat parallelogram: the bilinear map is affine, Gauss-Newton is exact in one step (the
  // second step confirms it).
  const FaceCoordinates x{{{0, 0, 0}, {2, 0, 0}, {2.5, 1, 0}, {0.5, 1, 0}}};
  double xi0 = 0.0, xi1 = 0.0;
  const auto outcome = geometry::closestPointOnCurvedFace(mesh::FaceType::Quad4, x, {1.3, 0.4, 0.7}, xi0, xi1);
  EXPECT_EQ(outcome.status, geometry::FaceProjectionStatus::Converged);
  EXPECT_LE(outcome.steps, 3);
  const Vec3 p = mesh::faceGeometry(mesh::FaceType::Quad4, x.data(), xi0, xi1).point;
  EXPECT_NEAR(p[0], 1.3, 1e-14);
  EXPECT_NEAR(p[1], 0.4, 1e-14);
  EXPECT_EQ(p[2], 0.0);
}
