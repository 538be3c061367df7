#pragma once
/// \file FaceProjection.hpp
/// The closest point of one face to a point: exactly on a 3-node triangle (its Voronoi
/// regions), by Gauss-Newton steps on a bilinear quadrilateral or a 6-node triangle. One loop
/// serves both curved faces; what differs is the reference domain a step may not leave
/// (the square [-1, 1]^2, the unit triangle), and a step that would leave it stops on the
/// edge it crosses, where the coordinate along that edge takes the step of the Gauss-Newton
/// model restricted to the edge (the closest point of an edge is not where the free step,
/// cut off, would put it).
///
/// A projection that does not settle is reported, not hidden: FaceProjectionStatus says
/// whether the steps stopped because they converged, because the tangents became linearly
/// dependent (a degenerate point of the face) or because the iteration cap was reached with
/// the last step still larger than kProjectionTolerance.
#include <array>
#include <string>

#include "tribos/mesh/ShapeFunctions.hpp"

namespace tribos::geometry {

using Vec3 = std::array<double, 3>;

/// Nodes of a face: 3 (triangle), 4 (quadrilateral) or 6 (6-node triangle).
inline constexpr int kMaxMasterFaceNodes = 6;
using FaceCoordinates = std::array<Vec3, kMaxMasterFaceNodes>;

/// Gauss-Newton steps on one face at most; a step below 1e-15 reference units ends them.
inline constexpr int kMaxProjectionSteps = 50;
/// A projection whose last step (reference units, |d xi_0| + |d xi_1|) is larger than this when
/// the steps end did not settle: counted and reported (ContactSearchResult::unsettledProjections).
inline constexpr double kProjectionTolerance = 1e-9;

enum class FaceProjectionStatus {
  Converged,   ///< the last step below the tolerance
  Degenerate,  ///< the face's tangents are linearly dependent at a point the steps reached
  Unsettled,   ///< kMaxProjectionSteps taken, the last one above kProjectionTolerance
};

struct FaceProjectionOutcome {
  FaceProjectionStatus status = FaceProjectionStatus::Converged;
  int steps = 0;
  double lastStep = 0.0;  ///< |d xi_0| + |d xi_1| of the last step taken
  bool settled() const { return status == FaceProjectionStatus::Converged; }
};

/// "the projection on a curved face stopped after 50 steps, the last one 3.2e-05 reference
/// units (not settled)" and the like, for messages.
std::string describe(const FaceProjectionOutcome& outcome);

/// Closest point of triangle (a, b, c) to x, as barycentric weights (w_a, w_b, w_c):
/// exact (0 or 1) in the vertex and edge regions.
std::array<double, 3> closestPointOnTriangle(const Vec3& x, const Vec3& a, const Vec3& b, const Vec3& c);

/// The point of the curved face (Quad4 or Tri6) with nodes x closest to `target`, from the
/// reference point (xi0, xi1) on (updated in place): Gauss-Newton steps on
/// |X(xi) - target|^2 within the face's reference domain.
FaceProjectionOutcome closestPointOnCurvedFace(mesh::FaceType type, const FaceCoordinates& x, const Vec3& target,
                                               double& xi0, double& xi1);

}  // namespace tribos::geometry
