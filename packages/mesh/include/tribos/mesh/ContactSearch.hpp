#pragma once
/// \file ContactSearch.hpp
/// Contact search and pairing (the paper's transfer mapping chi, DESIGN.md conventions):
/// every node of the slave side set is projected on the master *surface* — the closest
/// point on the faces of the master side set within the search distance, found with a
/// bounding-volume tree over the faces (O(log n) per slave node, no quadratic search).
/// The result per slave node: the master face, the weights of the projection (the face's
/// shape functions there: barycentric on a triangle, bilinear on a quadrilateral; the master
/// displacement there is interpolated with them), the contact normal nu and the signed
/// initial gap d along it. A quadrilateral is searched as its two triangles (0,1,2), (0,2,3),
/// a 6-node triangle as the four triangles its mid-edge nodes cut it into, and the point found
/// is then moved onto the bilinear or quadratic face by Gauss-Newton steps.
///
/// The normal is the *smoothed* master normal at the projection point: the barycentric
/// interpolation of the master's nodal normals (area-weighted means of the outer normals of
/// the faces at each master node), negated so that nu points from the slave into the
/// master. It is continuous over the master surface, so the directions of neighbouring
/// slave nodes on a faceted curved surface do not jump from face to face; on a flat master
/// it is the exact face normal. d = (x_projection - x_slave) . nu: positive for an open
/// gap, negative for an initial overlap (a small overlap is a negative gap, not an error).
/// On matching meshes every slave node lies on a master vertex: weights (1, 0, 0), the
/// pairing is node-to-node.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "tribos/mesh/Mesh.hpp"

namespace tribos::mesh {

/// Nodes of a master face: 3 (triangle), 4 (quadrilateral) or 6 (6-node triangle).
inline constexpr int kMaxMasterFaceNodes = 6;

/// One slave node and its projection on the master surface.
struct ContactPair {
  LO slaveNode = -1;
  LO masterFace = -1;                    ///< index of the face in the master side set
  /// Nodes of that face (global node ids); past the face's own, -1 with weight 0.
  std::array<LO, kMaxMasterFaceNodes> masterNodes{-1, -1, -1, -1, -1, -1};
  /// Shape functions at the projection (sum 1; >= 0 on linear faces, a 6-node triangle's
  /// vertex functions are negative in parts).
  std::array<double, kMaxMasterFaceNodes> weights{};
  std::array<double, 3> normal{};        ///< unit nu, from the slave into the master
  double gap = 0.0;                      ///< signed distance along nu (< 0: initial overlap)
  double distance = 0.0;                 ///< |x_projection - x_slave|
  /// The master vertex with the largest weight (node-to-node pairing on matching meshes).
  LO nearestMasterNode() const;
};

struct ContactSearchResult {
  std::vector<ContactPair> pairs;  ///< ascending slave node
  std::vector<LO> unpaired;        ///< slave nodes with no master face within the search distance,
                                   ///< or whose nearest master face faces away (cannot touch)
  LO facingAway = 0;               ///< of these, the ones facing away
  LO overlapping = 0;              ///< pairs with a negative initial gap
  double largestOverlap = 0.0;     ///< max(-gap) over them (0 if none)
  long long facesTested = 0;       ///< closest-point evaluations in all (the search cost)
};

/// The master surface of a contact pair with its search tree: the closest point of the
/// surface to any point (the contact search and the mortar integration both ask it).
class MasterSurface {
 public:
  MasterSurface(const Mesh& mesh, const std::string& masterSideSet);
  ~MasterSurface();
  MasterSurface(const MasterSurface&) = delete;
  MasterSurface& operator=(const MasterSurface&) = delete;

  struct Projection {
    LO face = -1;                      ///< -1: no face within the radius
    std::array<LO, kMaxMasterFaceNodes> nodes{-1, -1, -1, -1, -1, -1};
    std::array<double, kMaxMasterFaceNodes> weights{};  ///< shape functions at the closest point
    std::array<double, 3> point{};
    double distance = 0.0;
  };
  /// The closest point within `radius` (ties: the lower face index). `facesTested` counts
  /// the closest-point evaluations.
  Projection project(const std::array<double, 3>& x, double radius, long long* facesTested = nullptr) const;
  /// Unit smoothed normal (outward of the master body) interpolated at a projection.
  std::array<double, 3> normalAt(const Projection& p) const;
  const std::string& name() const { return name_; }

 private:
  class Tree;
  std::string name_;
  std::unique_ptr<Tree> tree_;
  /// The tree holds triangles: a 3-node face itself, or a piece of a quadrilateral or of a
  /// 6-node triangle.
  struct SearchTriangle {
    LO face;
    int piece;  ///< which of the face's triangles (ContactSearch.cpp: kFacePieces)
  };
  std::vector<SearchTriangle> searchTriangles_;
  std::vector<FaceNodes> faceNodes_;
  std::vector<std::array<std::array<double, 3>, kMaxMasterFaceNodes>> faceCoords_;  ///< per face, its nodes' coordinates
  /// How far a face may lie from the triangles it is searched as (a warped quadrilateral's
  /// twist, a 6-node triangle's bowed edges), over all faces: the search reaches this much
  /// farther, and a face is then taken on its own distance. 0 on a surface of 3-node triangles.
  double pieceDeviation_ = 0.0;
  std::vector<std::array<double, 3>> nodalNormal_;  ///< unit, per global node (zero off the set)
};

/// Pairs every node of `slaveSideSet` with the master surface `masterSideSet` within
/// `searchDistance` (>= 0, the mesh's units; a slave node farther from every master face
/// cannot touch and is listed in `unpaired`). Throws core::InputError naming the set and
/// node when the surfaces share a node, a surface is folded (zero summed normal at a node),
/// or the master surface faces away from the slave surface at every reachable slave node.
ContactSearchResult searchContactPairs(const Mesh& mesh, const std::string& slaveSideSet,
                                       const std::string& masterSideSet, double searchDistance);

/// Closest point of triangle (a, b, c) to x, as barycentric weights (w_a, w_b, w_c):
/// exact (0 or 1) in the vertex and edge regions. Exposed for tests.
std::array<double, 3> closestPointOnTriangle(const std::array<double, 3>& x, const std::array<double, 3>& a,
                                             const std::array<double, 3>& b, const std::array<double, 3>& c);

/// Vertices of the faces of a side set, ascending, unique.
std::vector<LO> sideSetNodes(const Mesh& mesh, const SideSet& set);

/// Per node: the sum over the faces of `set` that contain it (mid-edge nodes included) of
/// their outward normals (length twice the face area, so the sum is area-weighted); zero off
/// the set.
std::vector<std::array<double, 3>> summedFaceNormals(const Mesh& mesh, const SideSet& set);

}  // namespace tribos::mesh
