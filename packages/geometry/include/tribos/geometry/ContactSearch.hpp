#pragma once
/// \file ContactSearch.hpp
/// Contact search and pairing (the paper's transfer mapping chi, DESIGN.md conventions):
/// every node of the slave side set is projected on the master *surface* (MasterSurface.hpp:
/// the closest point on the faces of the master side set within the search distance, found
/// with a bounding-volume tree, O(log n) per slave node). The result per slave node: the
/// master face, the weights of the projection (the face's shape functions there; the master
/// displacement there is interpolated with them), the contact normal nu and the signed
/// initial gap d along it.
///
/// nu is the smoothed master normal at the projection (MasterSurface::normalAt), negated so
/// that it points from the slave into the master. d = (x_projection - x_slave) . nu: positive
/// for an open gap, negative for an initial overlap (a small overlap is a negative gap, not an
/// error). On matching meshes every slave node lies on a master vertex: weights (1, 0, 0), the
/// pairing is node-to-node.
#include <array>
#include <string>
#include <vector>

#include "tribos/geometry/MasterSurface.hpp"
#include "tribos/mesh/Mesh.hpp"

namespace tribos::geometry {

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
  /// Projections on curved master faces that did not settle (FaceProjection.hpp), with the
  /// first of them described ("slave node 12 at (...): ..."): their pairs are kept, at the
  /// last point the steps reached.
  LO unsettledProjections = 0;
  std::string firstUnsettled;
};

/// Pairs every node of `slaveSideSet` with the master surface `masterSideSet` within
/// `searchDistance` (>= 0, the mesh's units; a slave node farther from every master face
/// cannot touch and is listed in `unpaired`), and every node inside the master body whatever
/// `searchDistance` says (MasterSurface::pairingProjection: an interference fit is paired at
/// the default distance; its pair's distance exceeds `searchDistance`). Throws core::InputError naming the set and
/// node when the surfaces share a node, a surface is folded (zero summed normal at a node),
/// or the master surface faces away from the slave surface at every reachable slave node.
/// `held`: the nodes on symmetry planes (SurfaceNormals.hpp), whose master normals lie in them.
ContactSearchResult searchContactPairs(const mesh::Mesh& mesh, const std::string& slaveSideSet,
                                       const std::string& masterSideSet, double searchDistance,
                                       const HeldAxes& held = {});

}  // namespace tribos::geometry
