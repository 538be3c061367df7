/// \file ContactSearch.cpp
/// Pairing of the slave nodes with the master surface (header).
#include "tribos/geometry/ContactSearch.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "VectorMath.hpp"
#include "tribos/core/Errors.hpp"
#include "tribos/core/Format.hpp"
#include "tribos/geometry/SurfaceNormals.hpp"

namespace tribos::geometry {

namespace {
std::string str(double x) { return core::formatNumber(x); }
std::string str(const Vec3& x) { return core::formatPoint(x); }
std::string nodeAt(LO node, const Vec3& x) { return "slave node " + std::to_string(node + 1) + " at " + str(x); }
}  // namespace

LO ContactPair::nearestMasterNode() const {
  return masterNodes[std::max_element(weights.begin(), weights.end()) - weights.begin()];
}

ContactSearchResult searchContactPairs(const mesh::Mesh& mesh, const std::string& slaveSideSet,
                                       const std::string& masterSideSet, double searchDistance,
                                       const HeldAxes& held) {
  core::requireInput(std::isfinite(searchDistance) && searchDistance >= 0.0,
                     "Contact/Search Distance must be finite and >= 0, got " + str(searchDistance));
  const mesh::SideSet& slaveSet = mesh.sideSet(slaveSideSet);
  const auto slaves = sideSetNodes(mesh, slaveSet);
  const auto masterNodes = sideSetNodes(mesh, mesh.sideSet(masterSideSet));
  const MasterSurface master(mesh, masterSideSet, held);
  const auto slaveNormal = unitNodalNormals(mesh, slaveSet);
  const double zeroGap = 1e-12 * coordinateScale(mesh);

  ContactSearchResult result;
  std::string firstFacingAway;
  for (LO slave : slaves) {
    const Vec3& xs = mesh.coords[slave];
    if (std::binary_search(masterNodes.begin(), masterNodes.end(), slave))
      throw core::InputError("contact: node " + std::to_string(slave + 1) + " belongs to both side sets \"" +
                             slaveSideSet + "\" and \"" + masterSideSet +
                             "\": the bodies share their interface nodes; give each body its own nodes "
                             "(gmsh meshes: tribos-msh2exo --split-bodies)");
    core::requireInput(norm(slaveNormal[slave]) > 0.0,
                       "contact: the faces of side set \"" + slaveSideSet + "\" at slave node " +
                           std::to_string(slave + 1) + " at " + str(xs) +
                           " have a zero summed normal (degenerate or folded surface)");
    // Nearest face within the search distance; ties go to the lower face index.
    const auto projection = master.pairingProjection(xs, searchDistance, &result.facesTested);
    if (!projection.outcome.settled() && result.unsettledProjections++ == 0)
      result.firstUnsettled = nodeAt(slave, xs) + ": " + describe(projection.outcome);
    if (projection.face < 0) {
      result.unpaired.push_back(slave);
      continue;
    }
    ContactPair pair;
    pair.slaveNode = slave;
    pair.masterFace = projection.face;
    pair.masterNodes = projection.nodes;
    pair.weights = projection.weights;
    // nu = -(interpolated master normal) (header: the smoothed normal).
    Vec3 n = master.normalAt(projection);
    core::requireInput(norm(n) > 0.0, "contact: the master surface \"" + masterSideSet + "\" is folded at " +
                                          str(projection.point) + " (its nodal normals cancel), the projection of slave node " +
                                          std::to_string(slave + 1));
    for (double& c : n) c = -c;
    // Where the master surface faces away from the slave surface the node cannot touch it
    // (it found the back or the side of the master body): no rows, like a node out of reach.
    if (!(dot(n, slaveNormal[slave]) > 0.0)) {
      result.unpaired.push_back(slave);
      ++result.facingAway;
      if (result.facingAway == 1) firstFacingAway = nodeAt(slave, xs) + " projects on face " + std::to_string(projection.face + 1) +
                                                    " at " + str(projection.point);
      continue;
    }
    pair.normal = n;
    pair.distance = projection.distance;
    pair.gap = dot(minus(projection.point, xs), n);
    if (std::abs(pair.gap) <= zeroGap) pair.gap = 0.0;
    if (pair.gap < 0.0) {
      ++result.overlapping;
      result.largestOverlap = std::max(result.largestOverlap, -pair.gap);
    }
    result.pairs.push_back(pair);
  }
  // Every reachable node facing away: the sets are swapped or name the wrong surfaces.
  core::requireInput(!result.pairs.empty() || result.facingAway == 0,
                     "contact: the master surface \"" + masterSideSet + "\" faces away from the slave surface \"" +
                         slaveSideSet + "\" wherever it is within the Search Distance (e.g. " + firstFacingAway +
                         "); check the side sets (outer faces of the two bodies, facing each other)");
  return result;
}

}  // namespace tribos::geometry
