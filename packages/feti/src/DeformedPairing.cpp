// Contact pairing that follows the deformed bodies (issue 41; ConstraintSpec::pairingDisplacement):
// each slave node keeps the pairing of the solved state unless the bodies at x + u show it
// wrong, node by node, so that a scene whose pairing holds gets the same rows bit for bit.
#include <algorithm>
#include <map>
#include <set>

#include "ConstraintRows.hpp"
#include "ContactPairs.hpp"
#include "tribos/core/Errors.hpp"
#include "tribos/geometry/MasterSurface.hpp"

namespace tribos::feti::rows {

namespace {
/// The gap of a row found on the deformed bodies measured from the reference: d_ref = d + sum
/// over its nodes of w nu . u (the slave node and the other slave nodes with their weights, the
/// master nodes with -w); exact for gaps linear in the coordinates through the row's weights
/// (projections, and the mortar integrals).
double referenceGap(const geometry::ContactPair& pair, const geometry::MortarRow& side,
                    const std::vector<std::array<double, 3>>& u) {
  auto along = [&](LO node) { return dot(pair.normal, u[node]); };
  double shift = side.slaveWeight * along(pair.slaveNode);
  for (size_t k = 0; k < side.slaveNodes.size(); ++k) shift += side.slaveWeights[k] * along(side.slaveNodes[k]);
  for (size_t k = 0; k < side.masterNodes.size(); ++k) shift -= side.weights[k] * along(side.masterNodes[k]);
  return side.gap + shift;
}

/// The largest distance between two nodes of a pair's master face (at the mesh's coordinates).
double faceSize(const mesh::Mesh& mesh, const geometry::ContactPair& pair) {
  double size = 0.0;
  for (LO a : pair.masterNodes)
    for (LO b : pair.masterNodes)
      if (a >= 0 && b > a) size = std::max(size, norm(minus(mesh.coords[a], mesh.coords[b])));
  return size;
}

/// Index of each slave node's pair.
std::map<LO, size_t> bySlaveNode(const InterfacePairs& found) {
  std::map<LO, size_t> at;
  for (size_t p = 0; p < found.search.pairs.size(); ++p) at[found.search.pairs[p].slaveNode] = p;
  return at;
}

enum class Source { None, Reference, Deformed };

/// How far a contact node has slid along its master since its rows were built: the tangential
/// part (to its normal) of its row's weighted displacement now less then (ContactNode::pairedAt).
double slidSincePairing(const ContactNode& node, const std::vector<std::array<double, 3>>& u) {
  Vec3 shift{-node.pairedAt[0], -node.pairedAt[1], -node.pairedAt[2]};
  for (const auto& [n, w] : node.sides())
    for (int c = 0; c < 3; ++c) shift[c] += w * u[n][c];
  const double along = dot(shift, node.normal);
  return norm(minus(shift, scaled(node.normal, along)));
}

/// Where slave node n takes its pair from (ConstraintSpec::pairingDisplacement's rules).
/// `solved`: its contact node in the solved state's pairing (null: no rows there);
/// `deformed`: its pair at x + u (null: none) with `inside` whether that lies inside the master
/// and `slid` whether the node slid by more than half that pair's face since it was paired.
Source sourceOf(const ContactNode* solved, bool reference, const geometry::ContactPair* deformed, bool inside,
                bool slid, InterfacePairs& out) {
  if (solved) {
    if (deformed) {
      const auto& masters = solved->masterNodes;
      if (slid || !std::binary_search(masters.begin(), masters.end(), deformed->nearestMasterNode())) {
        ++out.movedOn;
        return Source::Deformed;
      }
      if (solved->pairedDeformed) return Source::Deformed;
    }
    return reference ? Source::Reference : Source::None;
  }
  if (deformed && inside) {
    ++out.newlyInside;
    return Source::Deformed;
  }
  return reference ? Source::Reference : Source::None;
}
/// The interface searched at x + u: its search reaches at least a master face's size, so that a
/// node the solve left touching, or slightly open, beyond a small Search Distance keeps a pair to
/// compare and re-pair.
ContactInterfaceSpec widened(const mesh::Mesh& deformed, const ContactInterfaceSpec& one) {
  ContactInterfaceSpec wide = one;
  wide.searchDistance = std::max(one.searchDistance, geometry::MasterSurface(deformed, one.masterSideSet).largestFaceSize());
  return wide;
}

/// The contact nodes of interface `index` in the solved state's pairing, by slave node.
std::map<LO, const ContactNode*> solvedNodes(const ConstraintSpec& spec, int index) {
  std::map<LO, const ContactNode*> solved;
  if (spec.solvedPairing)
    for (const auto& node : spec.solvedPairing->contact)
      if (node.interface == index) solved[node.slaveNode] = &node;
  return solved;
}

/// Where slave node n takes its pair from, given its pair at x + u (null: none).
Source decide(LO n, const std::map<LO, const ContactNode*>& solved, bool reference, const geometry::ContactPair* pair,
              const mesh::Mesh& deformed, const std::vector<std::array<double, 3>>& u, InterfacePairs& out) {
  const auto s = solved.find(n);
  const double size = pair ? faceSize(deformed, *pair) : 0.0;
  const bool inside = pair && pair->gap < -1e-3 * size;
  const bool slid = pair && s != solved.end() && slidSincePairing(*s->second, u) > 0.5 * size;
  return sourceOf(s == solved.end() ? nullptr : s->second, reference, pair, inside, slid, out);
}
}  // namespace

mesh::Mesh deformedMesh(const mesh::Mesh& mesh, const std::vector<std::array<double, 3>>& u) {
  mesh::Mesh deformed = mesh;
  for (size_t n = 0; n < deformed.coords.size(); ++n)
    for (int c = 0; c < 3; ++c) deformed.coords[n][c] += u[n][c];
  return deformed;
}

InterfacePairs pairsOnTheDeformedBodies(const mesh::Mesh& mesh, const mesh::Mesh& deformed, const ConstraintSpec& spec,
                                        int index, const geometry::HeldAxes& held) {
  const ContactInterfaceSpec& one = spec.interfaces[index];
  const auto& u = *spec.pairingDisplacement;
  const InterfacePairs reference = pairsOf(mesh, one, held);
  ContactInterfaceSpec atDeformed = widened(deformed, one);
  // Surface Geometry = Automatic decides on the reference mesh, where the fit is; the rows
  // found at x + u measure their gaps on the same surfaces.
  atDeformed.surfaceGeometry = reference.smoothed ? SurfaceGeometry::Smoothed : SurfaceGeometry::Faceted;
  const InterfacePairs moved = pairsOf(deformed, atDeformed, held);
  const auto solved = solvedNodes(spec, index);
  const auto atReference = bySlaveNode(reference), atMoved = bySlaveNode(moved);
  std::set<LO> slaveNodes(reference.search.unpaired.begin(), reference.search.unpaired.end());
  for (const auto& [n, p] : atReference) slaveNodes.insert(n);
  InterfacePairs out;
  out.search.unsettledProjections = reference.search.unsettledProjections + moved.search.unsettledProjections;
  out.search.firstUnsettled = reference.search.firstUnsettled + moved.search.firstUnsettled;
  out.unsettledQuadraturePoints = reference.unsettledQuadraturePoints + moved.unsettledQuadraturePoints;
  out.searchDistance = reference.searchDistance;
  out.smoothed = reference.smoothed;
  out.smoothedByChoice = reference.smoothedByChoice;
  for (LO n : slaveNodes) {
    const auto r = atReference.find(n), d = atMoved.find(n);
    const geometry::ContactPair* pair = d == atMoved.end() ? nullptr : &moved.search.pairs[d->second];
    switch (decide(n, solved, r != atReference.end(), pair, deformed, u, out)) {
      case Source::None: out.search.unpaired.push_back(n); break;
      case Source::Reference:
        out.search.pairs.push_back(reference.search.pairs[r->second]);
        out.masterSides.push_back(reference.masterSides[r->second]);
        out.deformed.push_back(0);
        break;
      case Source::Deformed:
        out.search.pairs.push_back(*pair);
        out.masterSides.push_back(moved.masterSides[d->second]);
        out.masterSides.back().gap = referenceGap(*pair, out.masterSides.back(), u);
        out.deformed.push_back(1);
        break;
    }
  }
  return out;
}

}  // namespace tribos::feti::rows

namespace tribos::feti {

std::array<GO, 2> pairingChanges(const mesh::Mesh& mesh, const ConstraintSpec& spec) {
  using namespace rows;
  const mesh::Mesh deformed = deformedMesh(mesh, *spec.pairingDisplacement);
  InterfacePairs counts;
  const geometry::HeldAxes held = heldAxes(prescribedComponents(mesh, spec));
  for (size_t i = 0; i < spec.interfaces.size(); ++i) {
    const auto& one = widened(deformed, spec.interfaces[i]);
    geometry::ContactSearchResult moved;
    try {
      moved = geometry::searchContactPairs(deformed, one.slaveSideSet, one.masterSideSet, one.searchDistance, held);
    } catch (const core::InputError& e) {
      throw core::InputError(one.label() + ": " + e.what());
    }
    const auto solved = solvedNodes(spec, static_cast<int>(i));
    for (const auto& pair : moved.pairs)
      decide(pair.slaveNode, solved, true, &pair, deformed, *spec.pairingDisplacement, counts);
  }
  return {counts.newlyInside, counts.movedOn};
}

}  // namespace tribos::feti
