#pragma once
/// \file MasterSurface.hpp
/// The master surface of a contact interface with its search tree: the closest point of the
/// surface to any point, and the smoothed normal there (the contact search and the mortar
/// integration both ask it).
///
/// The tree holds triangles: a 3-node face itself, a quadrilateral as its two triangles
/// (0,1,2), (0,2,3), a 6-node triangle as the four triangles its mid-edge nodes cut it into.
/// The closest of these is found first; on a curved face the point is then moved onto the
/// bilinear or quadratic face by Gauss-Newton steps (FaceProjection.hpp), and the search
/// reaches as far as faces deviate from their search triangles.
///
/// The normal is the *smoothed* master normal: the interpolation of the master's nodal
/// normals (the outer normals of the faces at each master node weighted by their angles there,
/// in the symmetry planes the node is held on: SurfaceNormals.hpp) with
/// the face's shape functions at the projection. It is continuous over the surface, so the
/// directions at neighbouring slave nodes on a faceted curved surface do not jump from face to
/// face; on a flat master it is the exact face normal.
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "tribos/geometry/FaceProjection.hpp"
#include "tribos/geometry/SurfaceNormals.hpp"
#include "tribos/mesh/Mesh.hpp"

namespace tribos::geometry {

class TriangleTree;

/// A point lies beside the surface, not over it, where its closest point is on the surface's
/// boundary (the rim of a hole, the edge of a plate) and it lies beyond that edge by more than
/// this fraction of the face's size plus kBesideSlope times its offset along the normal
/// (SurfaceBoundary.hpp; the slope absorbs a curved face's normal, which the co-normal is
/// taken against, leaning from the direction in which the point was found):
/// MasterSurface::pairingProjection pairs it with no face. A slave node or mortar point over a hole's clearance is then no contact with
/// the rim (it had the rim's closest point, with a gap along the rim's normal: a bolt head's
/// nodes over the clearance of its hole carried 68 % of the head's pretension).
inline constexpr double kBesideTheSurface = 1e-3;
inline constexpr double kBesideSlope = 0.1;

/// A point is inside the master body where its offset from its closest point makes at most
/// acos(0.9) = 26 degrees with the inward normal there (MasterSurface::pairingProjection): a point
/// beside the surface's edge is not.
inline constexpr double kInsideAlongNormal = 0.9;

class MasterSurface {
 public:
  /// `held`: the nodes on symmetry planes, whose normals lie in them (SurfaceNormals.hpp).
  MasterSurface(const mesh::Mesh& mesh, const std::string& masterSideSet, const HeldAxes& held = {});
  ~MasterSurface();
  MasterSurface(const MasterSurface&) = delete;
  MasterSurface& operator=(const MasterSurface&) = delete;

  struct Projection {
    LO face = -1;  ///< -1: no face within the radius
    std::array<LO, kMaxMasterFaceNodes> nodes{-1, -1, -1, -1, -1, -1};
    std::array<double, kMaxMasterFaceNodes> weights{};  ///< shape functions at the closest point
    std::array<double, 3> point{};
    double distance = 0.0;
    /// How the Gauss-Newton steps on a curved face ended (Converged on a 3-node triangle, at a
    /// node of the face, and where no face is within the radius).
    FaceProjectionOutcome outcome;
  };
  /// The closest point within `radius` (ties: the lower face index). `facesTested` counts
  /// the closest-point evaluations.
  Projection project(const Vec3& x, double radius, long long* facesTested = nullptr) const;
  /// The projection that pairs a point with the surface (issue 41): none for a point beside
  /// the surface (kBesideTheSurface); the closest point within `searchDistance`, or, whatever `searchDistance` says, the closest point of a point inside
  /// the master body: behind the surface along its normal (the offset within
  /// acos(kInsideAlongNormal) of the inward smoothed normal) and at most the size of the face it
  /// projects on deep. A deeper overlap is not a contact this small-strain model can resolve;
  /// the check after the solve (stack) reports it.
  Projection pairingProjection(const Vec3& x, double searchDistance, long long* facesTested = nullptr) const;
  /// The largest distance between two nodes of face f (its size).
  double faceSize(LO face) const { return faceSize_[face]; }
  double largestFaceSize() const { return largestFaceSize_; }
  /// Unit smoothed normal (outward of the master body) interpolated at a projection.
  Vec3 normalAt(const Projection& p) const;
  const std::string& name() const { return name_; }

  /// The faces of the surface (index: position in the master side set), their nodes and
  /// coordinates, and the faces sharing a node with each (itself excluded; ascending): what
  /// the segment-based mortar integration walks (MortarSegments.hpp).
  LO numFaces() const { return static_cast<LO>(faceNodes_.size()); }
  const mesh::FaceNodes& faceNodes(LO face) const { return faceNodes_[face]; }
  const FaceCoordinates& faceCoordinates(LO face) const { return faceCoords_[face]; }
  const std::vector<LO>& neighbours(LO face) const { return neighbours_[face]; }
  /// The unit nodal normal (outward of the master body) of a node of the surface.
  const Vec3& nodalNormal(LO node) const { return nodalNormal_[node]; }

 private:
  /// The closest point on the face of a search triangle, from the triangle's closest point
  /// (barycentric weights); no face if it lies beyond `radius`.
  Projection onFace(LO triangle, const std::array<double, 3>& barycentric, const Vec3& x, double radius) const;

  std::string name_;
  std::unique_ptr<TriangleTree> tree_;
  /// Which face, and which of its search triangles (mesh::FaceTypeShape), each tree triangle is.
  struct SearchTriangle {
    LO face;
    int piece;
  };
  std::vector<SearchTriangle> searchTriangles_;
  std::vector<mesh::FaceNodes> faceNodes_;
  std::vector<FaceCoordinates> faceCoords_;  ///< per face, its nodes' coordinates
  /// How far a face may lie from the triangles it is searched as (a warped quadrilateral's
  /// twist, a 6-node triangle's bowed edges), over all faces: the search reaches this much
  /// farther, and a face is then taken on its own distance. 0 on a surface of 3-node triangles.
  double pieceDeviation_ = 0.0;
  std::vector<Vec3> nodalNormal_;  ///< unit, per global node (zero off the set)
  std::vector<std::vector<LO>> neighbours_;  ///< per face, the faces sharing a node with it
  std::vector<double> faceSize_;             ///< per face, the largest distance between its nodes
  std::vector<std::uint8_t> boundaryEdges_;  ///< per face, its edges on the surface's boundary (SurfaceBoundary.hpp)
  double largestFaceSize_ = 0.0;
};

}  // namespace tribos::geometry
