// Nagata's curved faces (geometry/SmoothedFaces.hpp, Contact/Surface Geometry = Smoothed): a
// face cut from a cylinder follows the cylinder far closer than its chord does; flat faces and
// creases stay as they are.
#include <gtest/gtest.h>

#include <cmath>

#include "tribos/geometry/SmoothedFaces.hpp"

namespace {
using tribos::geometry::FaceCoordinates;
using tribos::geometry::SmoothedFace;
using tribos::geometry::Vec3;
using tribos::mesh::FaceType;

constexpr double kRadius = 20.0;

Vec3 onCylinder(double theta, double z) { return {kRadius * std::cos(theta), kRadius * std::sin(theta), z}; }
Vec3 radial(double theta) { return {std::cos(theta), std::sin(theta), 0.0}; }
double radiusOf(const Vec3& x) { return std::hypot(x[0], x[1]); }

/// The point of the smoothed face at reference coordinates (xi0, xi1) from the face's own point.
Vec3 smoothedPoint(const Vec3& onFace, const SmoothedFace& face, double xi0, double xi1) {
  const Vec3 o = face.offset(xi0, xi1);
  return {onFace[0] + o[0], onFace[1] + o[1], onFace[2] + o[2]};
}
}  // namespace

TEST(SmoothedFaces, aCylindersQuadrilateralFollowsTheCylinder) {
  // 0.1 rad of a radius-20 cylinder: the chord's midpoint lies R (1 - cos 0.05) = 0.025 inside.
  const double a = 0.0, b = 0.1;
  FaceCoordinates x{};
  x[0] = onCylinder(a, 0.0), x[1] = onCylinder(b, 0.0), x[2] = onCylinder(b, 1.0), x[3] = onCylinder(a, 1.0);
  const SmoothedFace face(FaceType::Quad4, x, {radial(a), radial(b), radial(b), radial(a)});
  for (double xi0 : {-0.5, 0.0, 0.5})
    for (double xi1 : {-1.0, 0.0, 0.7}) {
      Vec3 chord{};
      const double N[4] = {(1 - xi0) * (1 - xi1) / 4, (1 + xi0) * (1 - xi1) / 4, (1 + xi0) * (1 + xi1) / 4,
                           (1 - xi0) * (1 + xi1) / 4};
      for (int k = 0; k < 4; ++k)
        for (int c = 0; c < 3; ++c) chord[c] += N[k] * x[k][c];
      const Vec3 smooth = smoothedPoint(chord, face, xi0, xi1);
      EXPECT_GT(kRadius - radiusOf(chord), 0.01 * (1 - xi0 * xi0)) << "the chord sags";
      EXPECT_NEAR(radiusOf(smooth), kRadius, 1e-4) << "at (" << xi0 << ", " << xi1 << ")";
      EXPECT_DOUBLE_EQ(smooth[2], chord[2]) << "no offset along the axis";
    }
}

TEST(SmoothedFaces, aCylindersTriangleFollowsTheCylinder) {
  const double a = 0.0, b = 0.1;
  FaceCoordinates x{};
  x[0] = onCylinder(a, 0.0), x[1] = onCylinder(b, 0.0), x[2] = onCylinder(b, 1.0);
  const SmoothedFace face(FaceType::Tri3, x, {radial(a), radial(b), radial(b), Vec3{}});
  for (const auto& [r, s] : {std::pair{1.0 / 3, 1.0 / 3}, std::pair{0.5, 0.0}, std::pair{0.5, 0.5}}) {
    Vec3 chord{};
    const double L[3] = {1 - r - s, r, s};
    for (int k = 0; k < 3; ++k)
      for (int c = 0; c < 3; ++c) chord[c] += L[k] * x[k][c];
    EXPECT_NEAR(radiusOf(smoothedPoint(chord, face, r, s)), kRadius, 1e-4) << "at (" << r << ", " << s << ")";
  }
}

TEST(SmoothedFaces, flatFacesAndCreasesStayAsTheyAre) {
  FaceCoordinates x{};
  x[0] = {0, 0, 0}, x[1] = {1, 0, 0}, x[2] = {1, 1, 0}, x[3] = {0, 1, 0};
  const Vec3 up{0, 0, 1};
  const SmoothedFace flat(FaceType::Quad4, x, {up, up, up, up});
  const Vec3 o = flat.offset(0.3, -0.2);
  EXPECT_EQ(o[0], 0.0);
  EXPECT_EQ(o[1], 0.0);
  EXPECT_EQ(o[2], 0.0);
  // Normals 90 degrees apart across every edge: a body's corner, not a curved surface.
  const Vec3 side{1, 0, 0};
  const SmoothedFace crease(FaceType::Quad4, x, {up, side, up, side});
  const Vec3 c = crease.offset(0.0, 0.0);
  EXPECT_EQ(c[0], 0.0);
  EXPECT_EQ(c[1], 0.0);
  EXPECT_EQ(c[2], 0.0);
}
