/// \file ContactRows.cpp
/// The contact rows of B: N, T1, T2 per contact node (paper Section 3, the transfer mapping
/// chi; ALGORITHMS.md 2), from the pairs and master sides the contact geometry finds
/// (geometry/ContactSearch.hpp, geometry/MortarCoupling.hpp), with the known part of
/// prescribed components in c.
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "ConstraintRows.hpp"
#include "ContactPairs.hpp"
#include "tribos/core/Errors.hpp"
#include "tribos/geometry/ContactSearch.hpp"
#include "tribos/geometry/MortarCoupling.hpp"
#include "tribos/geometry/SurfaceNormals.hpp"
#include "tribos/mesh/BoundaryFaces.hpp"

namespace tribos::feti::rows {

namespace {
/// t1 = `direction` projected on the plane orthogonal to `normal`, normalised; when the
/// direction is (nearly) parallel to the normal, the first of x, y, z that is not.
Vec3 tangent(const Vec3& direction, const Vec3& normal) {
  for (const Vec3& candidate : {direction, Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}}) {
    const double length = norm(candidate);
    if (!(length > 0.0)) continue;
    Vec3 t = minus(candidate, scaled(normal, dot(candidate, normal)));
    const double tl = norm(t);
    if (tl > 1e-6 * length) return scaled(t, 1.0 / tl);
  }
  return {1.0, 0.0, 0.0};  // unreachable for a unit normal: one axis is at most 55 degrees off the plane
}

/// The axes a node is held along while free along another (geometry::HeldAxes: symmetry planes).
std::uint8_t heldAxesOf(const Prescribed& prescribed, LO node) {
  if (!prescribed.any(node) || prescribed.all(node)) return 0;
  std::uint8_t axes = 0;
  for (int c = 0; c < 3; ++c)
    if (prescribed.fixed[3 * static_cast<size_t>(node) + c]) axes |= static_cast<std::uint8_t>(1 << c);
  return axes;
}

/// The contact normal of a slave node on a symmetry plane lies in it (geometry::inSymmetryPlanes;
/// the master's nodal normals there already do). Then t1, t2 align with the plane and the
/// slave's fixed axis, and friction across the plane is left to the symmetry condition (below).
Vec3 symmetryPlaneNormal(const Vec3& normal, const Prescribed& prescribed, LO slaveNode) {
  return geometry::inSymmetryPlanes(normal, heldAxesOf(prescribed, slaveNode));
}

/// The contact node of a slave node paired with `masterSide`: its master nodes and weights,
/// gap and frame (nu, t1, t2), right-handed.
ContactNode contactFrame(const geometry::ContactPair& pair, const geometry::MortarRow& masterSide,
                         const ContactInterfaceSpec& spec, const Prescribed& prescribed) {
  ContactNode node;
  node.slaveNode = pair.slaveNode;
  node.masterNode = pair.nearestMasterNode();
  node.masterNodes = masterSide.masterNodes;
  node.masterWeights = masterSide.weights;
  node.slaveWeight = masterSide.slaveWeight;
  node.otherSlaveNodes = masterSide.slaveNodes;
  node.otherSlaveWeights = masterSide.slaveWeights;
  node.mortar = !masterSide.nodeToSurface;
  node.normal = symmetryPlaneNormal(pair.normal, prescribed, pair.slaveNode);
  node.interference = spec.tied ? 0.0 : spec.interference;
  node.gap = masterSide.gap - node.interference;
  node.t1 = tangent(spec.t1Direction, node.normal);
  node.t2 = cross(node.normal, node.t1);  // right-handed (nu, t1, t2)
  return node;
}

/// |dir|^2 over the components of `node` that no condition prescribes (1: none prescribed).
double freeAlong(const Prescribed& prescribed, LO node, const Vec3& dir) {
  if (!prescribed.any(node)) return 1.0;
  double free = 0.0;
  for (int c = 0; c < 3; ++c)
    if (!prescribed.fixed[3 * static_cast<size_t>(node) + c]) free += dir[c] * dir[c];
  return free;
}

/// Whether nodes a and b are held along `dir` at the same value in every step: their
/// prescribed displacements along dir, condition by condition (each its own factor in a
/// history), cancel. Both must be held along dir (freeAlong zero).
bool heldAlike(const Prescribed& prescribed, LO a, LO b, const Vec3& dir) {
  std::vector<std::pair<int, double>> parts;  // (condition, part of (u_a - u_b) . dir)
  double size = 0.0;
  for (const auto& [node, sign] : {std::pair<LO, double>{a, 1.0}, std::pair<LO, double>{b, -1.0}})
    for (int c = 0; c < 3; ++c) {
      const size_t i = 3 * static_cast<size_t>(node) + c;
      if (!prescribed.fixed[i] || dir[c] == 0.0) continue;
      parts.push_back({prescribed.condition[i], sign * dir[c] * prescribed.value[i]});
      size += std::abs(dir[c] * prescribed.value[i]);
    }
  std::sort(parts.begin(), parts.end());
  for (size_t i = 0; i < parts.size();) {
    double sum = 0.0;
    size_t j = i;
    for (; j < parts.size() && parts[j].first == parts[i].first; ++j) sum += parts[j].second;
    if (std::abs(sum) > 1e-12 * size) return false;
    i = j;
  }
  return true;
}

/// Whether a tangential row along `dir` of `node` has both sides held along it, to be
/// dropped: the slave node and its nearest master node both held along t_j, the slave free
/// otherwise (`slaveFree2`: |dir|^2 over the slave's free components). What would remain of
/// the row (master nodes off the held plane, through the mortar weights) is no physical slip;
/// its multiplier, bounded by F g along an almost empty row, makes a needle-thin ellipse on
/// which MPGP crawls (measured on the Hertz half models: 24:1 semi-axes, 20 000 proportioning
/// steps; on a tet10 push-out the slip bound stalled at a change of 1e-7 for 400 outer
/// iterations). Held at the same value (a symmetry plane) nothing slips along t_j: the friction
/// there is the displacement condition's reaction. Held at different values (a shaft pushed
/// out of its hub by its end faces) the slip is prescribed: ContactNode::slipPrescribed.
/// Where only the slave is held along t_j (a roller on one body at the contact edge) the
/// master can slip past it: the row stays, the slave's prescribed part in c, and Coulomb's
/// law acts on the master's tangential displacement (issue 30).
/// (A slave clamped in every component keeps its rows: the master slides on a fixed
/// point, and the friction acts on the master alone.)
bool bothSidesHeld(const ContactNode& node, const Vec3& dir, double slaveFree2, const Prescribed& prescribed) {
  return !(slaveFree2 > 1e-12) && !prescribed.all(node.slaveNode) &&
         !(freeAlong(prescribed, node.masterNode, dir) > 1e-12);
}

/// The known parts of a contact row's c (scaled by -scale), one per displacement condition:
/// `knownBy` holds (condition, part) per prescribed component of the row's nodes.
void addKnownParts(std::vector<std::pair<int, double>> knownBy, double scale, RowList& list, Row& row) {
  std::sort(knownBy.begin(), knownBy.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (size_t i = 0; i < knownBy.size();) {  // one part per condition
    double sum = 0.0;
    size_t j = i;
    for (; j < knownBy.size() && knownBy[j].first == knownBy[i].first; ++j) sum += knownBy[j].second;
    list.addPart(row, knownBy[i].first, -scale * sum);
    i = j;
  }
}

/// The row of contact node `node` along direction d (0: nu, 1: t1, 2: t2) over its nodes
/// `sides` (ContactNode::sides: +1 on the slave, -w_i on master node i), its scale recorded in `node`; or
/// false when it is dropped (the entries it appended are removed): a row (almost) entirely
/// on prescribed components (a tangential one marked ContactNode::slipPrescribed), or a
/// tangential row on a symmetry plane (both sides held along it at the same value).
bool contactRow(int d, bool tied, ContactNode& node, const std::vector<std::pair<LO, double>>& sides,
                const RowContext& ctx, RowList& list, Row& row) {
  const Vec3* directions[3] = {&node.normal, &node.t1, &node.t2};
  const Vec3& dir = *directions[d];
  const Prescribed& prescribed = ctx.prescribed;
  row = list.begin();
  row.kind = static_cast<RowKind>(d);
  // Prescribed components leave the row; their known part moves to the right side.
  // (The arithmetic repeats the node-to-node rows' exactly when nothing is prescribed.)
  // Each node's weight is spread evenly over its copies (1/k each): the row is then
  // orthogonal to every gluing row, which is orthogonal to the mean of the copies.
  double known = 0.0, free2 = 0.0, full2 = 0.0, slaveFree2 = 1.0;
  std::vector<std::pair<int, double>> knownBy;  // the known part per displacement condition
  for (const auto& [global, weight] : sides) {
    const LO k = ctx.copies.count(global);
    const double perCopy = weight / k;
    double freeDirection2 = 1.0;  // |dir|^2 over the free components (dir is a unit vector)
    if (prescribed.any(global)) {
      freeDirection2 = 0.0;
      for (int c = 0; c < 3; ++c)
        if (prescribed.fixed[3 * global + c]) {
          known += weight * dir[c] * (prescribed.base[3 * global + c] + prescribed.value[3 * global + c]);
          knownBy.push_back({prescribed.condition[3 * global + c], weight * dir[c] * prescribed.value[3 * global + c]});
        }
        else freeDirection2 += dir[c] * dir[c];
    }
    if (global == node.slaveNode) slaveFree2 = freeDirection2;
    full2 += perCopy * perCopy * k;
    free2 += perCopy * perCopy * k * freeDirection2;
    for (int c = 0; c < 3; ++c) {
      if (dir[c] == 0.0 || prescribed.fixed[3 * global + c]) continue;
      for (LO j = 0; j < k; ++j) {
        const Copy& copy = ctx.copies.of(global, j);
        list.append({copy.subdomain, 3 * copy.localNode + c, perCopy * dir[c]});
      }
    }
  }
  // A row (almost) entirely on prescribed components is redundant: removed, counted.
  const bool held = d > 0 && bothSidesHeld(node, dir, slaveFree2, prescribed);
  if (!(free2 > 1e-16 * full2) || held) {
    // A tangential row whose slave and nearest master are held at different values: its
    // slip is prescribed, and its friction, which acts on held components, is added after
    // the solve (stack/ContactFields.hpp, issue 42).
    if (d > 0 && !(slaveFree2 > 1e-12) && !(freeAlong(prescribed, node.masterNode, dir) > 1e-12) &&
        !heldAlike(prescribed, node.slaveNode, node.masterNode, dir))
      node.slipPrescribed[d - 1] = true;
    list.drop(row);
    return false;
  }
  const double scale = 1.0 / std::sqrt(free2);
  Entry* entries = list.entriesOf(row);
  const size_t count = list.openCount(row);
  for (size_t e = 0; e < count; ++e) entries[e].value *= scale;
  // N u <= d: scale ((u_s - chi u_m) . nu) <= scale (d - known part); tied: = -known part (the
  // initial gap is kept, not closed).
  row.c = scale * ((d == 0 && !tied ? node.gap : 0.0) - known);
  addKnownParts(std::move(knownBy), scale, list, row);
  row.key = {0, node.slaveNode, d, 0};
  row.owner = ctx.ownerOf(entries, count);
  row.numEntries = static_cast<LO>(count);
  if (d == 0) {
    node.rowScale = scale;
  } else {
    node.hasTangential[d - 1] = true;
    node.tangentialScale[d - 1] = scale;
  }
  return true;
}

/// The element blocks (bodies) that hold the faces of a side set, ascending.
std::vector<int> bodiesOf(const mesh::Mesh& mesh, const std::string& sideSet) {
  std::vector<int> bodies;
  for (LO e : mesh.sideSet(sideSet).elements) bodies.push_back(mesh.blockOf(e));
  std::sort(bodies.begin(), bodies.end());
  bodies.erase(std::unique(bodies.begin(), bodies.end()), bodies.end());
  return bodies;
}

/// Self-contact (a surface against another of the same body) is not modelled: its rows would
/// tie a body to itself, which the search's normals and the rigid-body analysis do not expect.
void refuseSelfContact(const mesh::Mesh& mesh, const ContactInterfaceSpec& spec) {
  const auto slave = bodiesOf(mesh, spec.slaveSideSet), master = bodiesOf(mesh, spec.masterSideSet);
  for (int b : slave)
    if (std::binary_search(master.begin(), master.end(), b))
      throw core::InputError(spec.label() + ": both surfaces have faces on element block \"" + mesh.blocks[b].name +
                             "\": self-contact (a body against itself) is not supported; the slave and master "
                             "surfaces of an interface must lie on different bodies");
}

/// Whether a face of side set `faces` has all its nodes in `nodes` (ascending).
bool aFaceWithin(const mesh::Mesh& mesh, const std::string& faces, const std::vector<LO>& nodes) {
  const auto& set = mesh.sideSet(faces);
  for (size_t f = 0; f < set.elements.size(); ++f) {
    bool within = true;
    for (LO n : mesh.faceNodes(set.elements[f], set.sides[f]))
      within = within && std::binary_search(nodes.begin(), nodes.end(), n);
    if (within) return true;
  }
  return false;
}

/// Every interface names two surfaces on different bodies, and no contact is modelled twice:
/// an interface whose slave surface has a face on an earlier one's master surface and whose
/// master surface has a face on that one's slave surface (the same contact with the roles
/// swapped, a "double pass") would split its forces between the two at random. Surfaces that
/// only share an edge (an L-shaped seat) are not that.
void refuseContactsModelledTwice(const mesh::Mesh& mesh, const std::vector<ContactInterfaceSpec>& interfaces) {
  std::vector<std::vector<LO>> slave, master;
  for (const auto& spec : interfaces) {
    core::requireInput(!spec.slaveSideSet.empty() && !spec.masterSideSet.empty(),
                       spec.label() + ": give both the slave and the master side set");
    refuseSelfContact(mesh, spec);
    slave.push_back(geometry::sideSetNodes(mesh, mesh.sideSet(spec.slaveSideSet)));
    master.push_back(geometry::sideSetNodes(mesh, mesh.sideSet(spec.masterSideSet)));
  }
  for (size_t j = 0; j < interfaces.size(); ++j)
    for (size_t i = 0; i < j; ++i) {
      if (aFaceWithin(mesh, interfaces[j].slaveSideSet, master[i]) &&
          aFaceWithin(mesh, interfaces[j].masterSideSet, slave[i]))
        throw core::InputError(interfaces[j].label() + " models the contact of " + interfaces[i].label() +
                               " again with slave and master swapped: give each contact once (a double pass "
                               "would split its forces between the two at random)");
      // The same faces on both sides again (the same pair, another law on it, or the same
      // faces under other set names): the later interface would get no rows (issue 44).
      if (aFaceWithin(mesh, interfaces[j].slaveSideSet, slave[i]) &&
          aFaceWithin(mesh, interfaces[j].masterSideSet, master[i]))
        throw core::InputError(interfaces[j].label() + " models the contact of " + interfaces[i].label() +
                               " again (faces of both its surfaces are that interface's): give each contact once, "
                               "with one law");
    }
}

/// Every face of every contact surface lies on the mesh's boundary (issue 44: a side set of
/// interior faces was accepted and ended as exit 3 with a friction-capacity message). Also what
/// bodies that share their interface nodes make of their contact faces.
void refuseInteriorContactFaces(const mesh::Mesh& mesh, const std::vector<ContactInterfaceSpec>& interfaces) {
  if (interfaces.empty()) return;
  const mesh::SideSet boundary = mesh::boundaryFaces(mesh);
  std::vector<std::pair<LO, int>> onBoundary;
  for (size_t f = 0; f < boundary.elements.size(); ++f) onBoundary.push_back({boundary.elements[f], boundary.sides[f]});
  for (const auto& spec : interfaces)
    for (const std::string* name : {&spec.slaveSideSet, &spec.masterSideSet}) {
      const mesh::SideSet& set = mesh.sideSet(*name);
      for (size_t f = 0; f < set.elements.size(); ++f)
        core::requireInput(std::binary_search(onBoundary.begin(), onBoundary.end(),
                                              std::make_pair(set.elements[f], set.sides[f])),
                           spec.label() + ": side " + std::to_string(set.sides[f] + 1) + " of element " +
                               std::to_string(set.elements[f] + 1) + " in side set \"" + *name +
                               "\" is interior to the mesh (another element shares it): a contact surface lies on "
                               "a body's boundary (bodies meshed with shared interface nodes: give each its own, "
                               "tribos-msh2exo --split-bodies)");
    }
}

/// The master side of every pair of an interface (dual mortar or node-to-surface weights).
/// `unsettledProjections` counts the mortar quadrature points whose projection did not settle.
/// `smoothed`: the gaps measured between the smoothed surfaces (mortar only).
std::vector<geometry::MortarRow> masterSidesOf(const mesh::Mesh& mesh, const ContactInterfaceSpec& spec,
                                               const geometry::ContactSearchResult& search,
                                               const geometry::HeldAxes& held, bool smoothed,
                                               long long& unsettledProjections) {
  std::vector<geometry::MortarRow> masterSides;
  if (spec.discretization == ContactDiscretization::Mortar) {
    const geometry::MasterSurface master(mesh, spec.masterSideSet, held);
    return geometry::dualMortarRows(mesh, spec.slaveSideSet, master, search, spec.searchDistance,
                                    &unsettledProjections, smoothed, held);
  }
  for (const auto& pair : search.pairs) masterSides.push_back(geometry::nodeToSurfaceRow(pair));
  return masterSides;
}

/// The diameter of the bounding box of some nodes.
double diameter(const mesh::Mesh& mesh, const std::vector<LO>& nodes) {
  Vec3 low{0.0, 0.0, 0.0}, high{0.0, 0.0, 0.0};
  for (size_t k = 0; k < nodes.size(); ++k)
    for (int c = 0; c < 3; ++c) {
      const double x = mesh.coords[nodes[k]][c];
      low[c] = k == 0 ? x : std::min(low[c], x);
      high[c] = k == 0 ? x : std::max(high[c], x);
    }
  return norm(minus(high, low));
}

/// An initial overlap counts where it exceeds round-off (1e-12 of the slave surface's size): the
/// weighted gaps of coincident flat surfaces are +-1e-17, not overlaps a user should hear of.
double overlapRoundOff(const mesh::Mesh& mesh, const ContactInterfaceSpec& spec) {
  return 1e-12 * diameter(mesh, geometry::sideSetNodes(mesh, mesh.sideSet(spec.slaveSideSet)));
}

/// What the search and the mortar integration found on an interface, every pair on every rank.
ContactInterfaceRows interfaceRows(const mesh::Mesh& mesh, const ContactInterfaceSpec& spec,
                                   const InterfacePairs& pairs) {
  const auto& search = pairs.search;
  const auto& masterSides = pairs.masterSides;
  const double roundOff = overlapRoundOff(mesh, spec);
  ContactInterfaceRows found;
  found.label = spec.label();
  found.list = spec.list();
  found.tied = spec.tied;
  found.pairedSlaveNodes = static_cast<GO>(search.pairs.size());
  found.unpairedSlaveNodes = static_cast<GO>(search.unpaired.size());
  constexpr size_t kSample = 5;
  found.unpairedSample.assign(search.unpaired.begin(),
                              search.unpaired.begin() + std::min(kSample, search.unpaired.size()));
  found.searchDistance = pairs.searchDistance;
  found.interference = spec.interference;
  found.smoothedSurfaces = pairs.smoothed;
  found.smoothedByChoice = pairs.smoothedByChoice;
  for (const auto& pair : search.pairs) found.pairedInside += pair.distance > pairs.searchDistance;
  // The initial overlaps of the rows (weighted where mortar).
  for (const auto& side : masterSides) {
    if (side.gap < -roundOff) {
      ++found.overlappingPairs;
      found.largestOverlap = std::max(found.largestOverlap, -side.gap);
    }
    found.largestFacetSag = std::max(found.largestFacetSag, side.facetSag);
    if (side.gapLimited > 0.0) {
      ++found.limitedMortarGaps;
      found.largestGapLimit = std::max(found.largestGapLimit, side.gapLimited);
    }
  }
  return found;
}

/// Per mesh node, the interface whose rows a slave node gets (-1: none pairs it): where several
/// pair it (a corner of a body on a floor and against a wall), the one with the smallest gap,
/// the surface it touches or is nearest to (ties: the earlier interface).
std::vector<int> slaveOwners(LO numNodes, const std::vector<InterfacePairs>& found) {
  std::vector<int> owner(numNodes, -1);
  std::vector<double> gap(numNodes, std::numeric_limits<double>::infinity());
  for (size_t i = 0; i < found.size(); ++i)
    for (size_t p = 0; p < found[i].search.pairs.size(); ++p) {
      const LO n = found[i].search.pairs[p].slaveNode;
      if (found[i].masterSides[p].gap < gap[n]) {
        gap[n] = found[i].masterSides[p].gap;
        owner[n] = static_cast<int>(i);
      }
    }
  return owner;
}

/// (2) Contact rows of interface `index`: slave node minus the master displacement weighted by
/// the dual mortar or node-to-surface weights (paper Section 3, the transfer mapping chi;
/// DESIGN.md), for the pairs whose slave node `owner` gives to this interface (slaveOwners).
void addContactRows(const mesh::Mesh& mesh, const ConstraintSpec& all, int index, InterfacePairs found,
                    const std::vector<int>& owner, const RowContext& ctx, RowList& list, ConstraintMatrix& B) {
  const ContactInterfaceSpec& spec = all.interfaces[index];
  auto& search = found.search;
  auto& masterSides = found.masterSides;
  GO shared = 0;
  size_t keep = 0;
  for (size_t p = 0; p < search.pairs.size(); ++p) {
    if (owner[search.pairs[p].slaveNode] != index) {
      ++shared;
      continue;
    }
    search.pairs[keep] = search.pairs[p];
    if (!found.deformed.empty()) found.deformed[keep] = found.deformed[p];
    masterSides[keep++] = masterSides[p];
  }
  search.pairs.resize(keep);
  masterSides.resize(keep);
  B.interfaces.push_back(interfaceRows(mesh, spec, found));
  B.interfaces.back().unsettledProjections = search.unsettledProjections + found.unsettledQuadraturePoints;
  B.interfaces.back().firstUnsettled = search.firstUnsettled;
  B.interfaces.back().sharedSlaveNodes = shared;
  B.interfaces.back().newlyInside = found.newlyInside;
  B.interfaces.back().movedOn = found.movedOn;
  const int numDirections = spec.tangentialRows ? 3 : 1;
  list.rows.reserve(numDirections * search.pairs.size());
  for (size_t p = 0; p < search.pairs.size(); ++p) {
    ContactNode node = contactFrame(search.pairs[p], masterSides[p], spec, ctx.prescribed);
    node.interface = index;
    node.pairedDeformed = !found.deformed.empty() && found.deformed[p];
    if (node.pairedDeformed)
      for (const auto& [n, w] : node.sides())
        for (int c = 0; c < 3; ++c) node.pairedAt[c] += w * (*all.pairingDisplacement)[n][c];
    const std::vector<std::pair<LO, double>> sides = node.sides();
    // The node's rows are added together, their entries consecutive in the list.
    std::vector<Row> nodeRows;
    for (int d = 0; d < numDirections; ++d) {
      Row row;
      if (!contactRow(d, spec.tied, node, sides, ctx, list, row)) {
        if (d == 0) break;  // no normal row: the node cannot press, its tangential rows go too
        continue;
      }
      row.contact = d == 0 ? static_cast<int>(B.contact.size()) : -1;
      nodeRows.push_back(row);
    }
    B.removedRedundantRows += numDirections - static_cast<GO>(nodeRows.size());
    if (nodeRows.empty()) continue;
    // All rows of a node go to the owner of its normal row (they are consecutive there).
    for (auto& row : nodeRows) {
      row.owner = nodeRows.front().owner;
      list.rows.push_back(row);
    }
    B.contact.push_back(node);
  }
}
}  // namespace

geometry::HeldAxes heldAxes(const Prescribed& prescribed) {
  geometry::HeldAxes held(prescribed.fixed.size() / 3, 0);
  for (size_t n = 0; n < held.size(); ++n) held[n] = heldAxesOf(prescribed, static_cast<LO>(n));
  return held;
}

namespace {
/// The fit the rows of an interface close: over the pairs whose initial gap less the
/// Interference is an overlap beyond round-off, the largest and the smallest overlap.
struct Fit {
  double largest = 0.0, smallest = std::numeric_limits<double>::infinity();
  double range() const { return largest > 0.0 ? largest - smallest : 0.0; }
};

Fit fitOf(const std::vector<geometry::MortarRow>& rows, const ContactInterfaceSpec& spec, double roundOff) {
  Fit fit;
  for (const auto& side : rows) {
    const double overlap = spec.interference - side.gap;
    if (overlap <= roundOff) continue;
    fit.largest = std::max(fit.largest, overlap);
    fit.smallest = std::min(fit.smallest, overlap);
  }
  return fit;
}
}  // namespace

bool facetsDominate(const mesh::Mesh& mesh, const ContactInterfaceSpec& spec,
                    const std::vector<geometry::MortarRow>& faceted) {
  if (spec.tied || spec.discretization != ContactDiscretization::Mortar) return false;
  double sag = 0.0;
  for (const auto& side : faceted) sag = std::max(sag, side.facetSag);
  const Fit fit = fitOf(faceted, spec, overlapRoundOff(mesh, spec));
  return fit.largest > 0.0 && sag >= 0.1 * fit.largest;
}

bool smoothedFitsBetter(const mesh::Mesh& mesh, const ContactInterfaceSpec& spec,
                        const std::vector<geometry::MortarRow>& faceted,
                        const std::vector<geometry::MortarRow>& smoothed) {
  const double roundOff = overlapRoundOff(mesh, spec);
  return fitOf(smoothed, spec, roundOff).range() < fitOf(faceted, spec, roundOff).range();
}

double searchReach(const mesh::Mesh& mesh, const ContactInterfaceSpec& spec) {
  if (spec.searchDistance > 0.0) return spec.searchDistance;
  const mesh::SideSet& set = mesh.sideSet(spec.slaveSideSet);
  double largest = 0.0;
  for (size_t f = 0; f < set.elements.size(); ++f) {
    const mesh::FaceNodes face = mesh.faceNodes(set.elements[f], set.sides[f]);
    for (int a = 0; a < face.numVertices; ++a)
      for (int b = 0; b < a; ++b)
        largest = std::max(largest, norm(minus(mesh.coords[face.node[a]], mesh.coords[face.node[b]])));
  }
  return largest;
}

InterfacePairs pairsOf(const mesh::Mesh& mesh, const ContactInterfaceSpec& given, const geometry::HeldAxes& held) {
  InterfacePairs found;
  ContactInterfaceSpec spec = given;
  try {
    spec.searchDistance = found.searchDistance = searchReach(mesh, given);
    found.search =
        geometry::searchContactPairs(mesh, spec.slaveSideSet, spec.masterSideSet, spec.searchDistance, held);
    found.smoothed = spec.surfaceGeometry == SurfaceGeometry::Smoothed;
    found.masterSides = masterSidesOf(mesh, spec, found.search, held, found.smoothed, found.unsettledQuadraturePoints);
    if (spec.surfaceGeometry == SurfaceGeometry::Automatic && facetsDominate(mesh, spec, found.masterSides)) {
      long long unsettled = 0;
      auto smoothed = masterSidesOf(mesh, spec, found.search, held, true, unsettled);
      if (smoothedFitsBetter(mesh, spec, found.masterSides, smoothed)) {
        found.smoothed = found.smoothedByChoice = true;
        found.unsettledQuadraturePoints = unsettled;
        found.masterSides = std::move(smoothed);
      }
    }
  } catch (const core::InputError& e) {
    throw core::InputError(spec.label() + ": " + e.what());
  }
  return found;
}

void addAllContactRows(const mesh::Mesh& mesh, const ConstraintSpec& spec, const RowContext& ctx, RowList& list,
                       ConstraintMatrix& B) {
  refuseContactsModelledTwice(mesh, spec.interfaces);
  refuseInteriorContactFaces(mesh, spec.interfaces);
  std::vector<InterfacePairs> found;
  const geometry::HeldAxes held = heldAxes(ctx.prescribed);
  B.heldAxes = held;
  if (spec.pairingDisplacement) {
    const mesh::Mesh deformed = deformedMesh(mesh, *spec.pairingDisplacement);
    for (size_t i = 0; i < spec.interfaces.size(); ++i)
      found.push_back(pairsOnTheDeformedBodies(mesh, deformed, spec, static_cast<int>(i), held));
  } else {
    for (const auto& one : spec.interfaces) found.push_back(pairsOf(mesh, one, held));
  }
  const std::vector<int> owner = slaveOwners(mesh.numNodes(), found);
  for (size_t i = 0; i < spec.interfaces.size(); ++i)
    addContactRows(mesh, spec, static_cast<int>(i), std::move(found[i]), owner, ctx, list, B);
}

}  // namespace tribos::feti::rows
