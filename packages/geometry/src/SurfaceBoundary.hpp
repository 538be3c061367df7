#pragma once
// Internal to geometry/: the boundary of a master surface, where it ends (the rim of a hole,
// the edge of a plate), and whether a point lies beside it rather than over the surface.
#include <cstdint>
#include <vector>

#include "tribos/geometry/FaceProjection.hpp"
#include "tribos/mesh/ElementTypes.hpp"

namespace tribos::geometry {

/// Per face, bit k set where its edge k (vertex k to vertex k + 1, with its mid-edge node
/// 3 + k on a 6-node triangle) belongs to no other face of `faces`: the surface's boundary.
std::vector<std::uint8_t> boundaryEdges(const std::vector<mesh::FaceNodes>& faces);

/// How far point x lies beside the surface: where its closest point (`weights`, the face's
/// shape functions there; `point`, with the surface's unit `normal` there) is on a boundary
/// edge of the face (`edges`, its bits of boundaryEdges), the offset x - point along that
/// edge's outward co-normal (perpendicular to the edge and to the normal, away from the face);
/// 0 where the closest point is inside the surface or x lies over it. A point beside a hole's
/// rim is not over the surface: its closest point on the rim is no point of contact. The
/// co-normal is taken in the tangent plane at the point, not in the plane of the edge and the
/// face's centre: on a curved face (a sphere's 6-node triangle along a symmetry plane) that
/// plane leans, and a node below the edge, in the symmetry plane, read as beside it.
double besideTheSurface(const mesh::FaceNodes& face, const FaceCoordinates& coords, std::uint8_t edges,
                        const std::array<double, kMaxMasterFaceNodes>& weights, const Vec3& point,
                        const Vec3& normal, const Vec3& x);

}  // namespace tribos::geometry
