/// \file ConstraintMatrix.cpp
/// B = [N; T1; T2; B_e; B_d] and c (paper Sections 3-4, ALGORITHMS.md 2). Every row is
/// built once as a list of (subdomain, local dof, value) entries, given its owner rank and
/// a sort key, then all rows are numbered by (owner, key) and scattered into the
/// per-subdomain blocks. Cost: O(#copies + #rows log #rows) plus the contact search
/// (mesh/ContactSearch.hpp: O(#slave log #master faces)).
#include "tribos/feti/ConstraintMatrix.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <numeric>
#include <set>
#include <sstream>
#include <tuple>

#include "tribos/core/Errors.hpp"
#include "tribos/core/Format.hpp"
#include "tribos/mesh/ContactSearch.hpp"
#include "tribos/mesh/MortarCoupling.hpp"

namespace tribos::feti {

std::vector<std::pair<LO, double>> ContactNode::sides() const {
  std::vector<std::pair<LO, double>> out{{slaveNode, slaveWeight}};
  for (size_t k = 0; k < otherSlaveNodes.size(); ++k) out.push_back({otherSlaveNodes[k], otherSlaveWeights[k]});
  for (size_t v = 0; v < masterNodes.size(); ++v) out.push_back({masterNodes[v], -masterWeights[v]});
  return out;
}

GO ConstraintMatrix::count(RowKind k) const { return std::count(kind.begin(), kind.end(), k); }

GO ConstraintMatrix::unpairedSlaveNodes() const {
  GO n = 0;
  for (const auto& i : interfaces) n += i.unpairedSlaveNodes;
  return n;
}

namespace {
using Vec3 = std::array<double, 3>;

Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3 minus(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double norm(const Vec3& v) { return std::sqrt(dot(v, v)); }
Vec3 scaled(const Vec3& v, double s) { return {v[0] * s, v[1] * s, v[2] * s}; }

std::string str(double x) { return core::formatNumber(x); }
std::string str(const Vec3& x) { return core::formatPoint(x); }

/// One copy of a global node: the subdomain and the node's local index there.
struct Copy {
  int subdomain;
  LO localNode;
};

struct Entry {
  int subdomain;
  LO dof;
  double value;
};

/// A row before numbering. `key` gives the documented order within a rank: contact triples
/// by slave node (group 0), then gluing by (node, component, j) (group 1), then Dirichlet
/// by (node, copy, component) (group 2). Its entries are [firstEntry, firstEntry +
/// numEntries) of one array shared by all rows (RowList): a vector per row cost ~70 bytes of
/// its own per row, 21 MB of every rank's set-up at 4 000 subdomains (doc/measurements/scalability.md).
struct Row {
  RowKind kind = RowKind::Gluing;
  LO numEntries = 0;
  size_t firstEntry = 0;
  double c = 0.0;
  int owner = 0;
  std::tuple<int, LO, int, int> key;
  int contact = -1;  ///< index into the contact nodes (N rows only)
  size_t firstPart = 0;  ///< its parts of c per displacement condition (RowList::parts)
  int numParts = 0;
};

/// The rows and their entries. A row is open from begin() until add() takes it: its entries
/// are the ones appended in between (drop() discards them).
struct RowList {
  std::vector<Row> rows;
  std::vector<Entry> entries;
  /// (displacement condition, its part of c) of the rows (Row::firstPart): ConstraintMatrix::prescribedParts.
  std::vector<std::pair<int, double>> parts;
  Row begin() const {
    Row row;
    row.firstEntry = entries.size();
    row.firstPart = parts.size();
    return row;
  }
  /// The open row's part of c from displacement condition `condition` (none for zero values).
  void addPart(Row& row, int condition, double value) {
    if (condition < 0 || value == 0.0) return;
    parts.push_back({condition, value});
    row.numParts = static_cast<int>(parts.size() - row.firstPart);
  }
  void append(const Entry& e) { entries.push_back(e); }
  Entry* entriesOf(const Row& row) { return entries.data() + row.firstEntry; }
  /// The open row's entries so far (before add).
  size_t openCount(const Row& row) const { return entries.size() - row.firstEntry; }
  void drop(const Row& row) {
    entries.resize(row.firstEntry);
    parts.resize(row.firstPart);
  }
  void add(Row row) {
    row.numEntries = static_cast<LO>(entries.size() - row.firstEntry);
    rows.push_back(row);
  }
};

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

/// Prescribed displacement components: per (node, component) whether it is prescribed,
/// its value and the condition that prescribed it.
struct Prescribed {
  std::vector<char> fixed;     ///< 3 * numNodes
  std::vector<double> value;   ///< 3 * numNodes
  /// 3 * numNodes: index into ConstraintSpec::displacementConditions (-1: none, or a
  /// Dirichlet Node Set, whose value 0 no factor scales).
  std::vector<int> condition;
  /// Pairs of displacement conditions that prescribe one component of a node to the same
  /// non-zero value (ConstraintMatrix::overlappingConditions).
  std::set<std::pair<int, int>> overlapping;
  bool any(LO node) const { return fixed[3 * node] || fixed[3 * node + 1] || fixed[3 * node + 2]; }
  bool all(LO node) const { return fixed[3 * node] && fixed[3 * node + 1] && fixed[3 * node + 2]; }
};

/// The contact normal of a slave node on a symmetry plane: a node held along an axis e_c
/// (but free along another) whose normal is within ~11 degrees of that plane gets the normal's
/// e_c part removed. The smoothed master normal there averages the faces on one side of the
/// plane only, so it leans out of the plane; the whole (mirrored) body's normal lies in it.
/// Then t1, t2 align with the plane and the slave's fixed axis, and friction across the
/// plane is left to the symmetry condition (below).
Vec3 symmetryPlaneNormal(Vec3 normal, const Prescribed& prescribed, LO slaveNode) {
  if (!prescribed.any(slaveNode) || prescribed.all(slaveNode)) return normal;
  for (int c = 0; c < 3; ++c)
    if (prescribed.fixed[3 * static_cast<size_t>(slaveNode) + c] && std::abs(normal[c]) < 0.2) normal[c] = 0.0;
  return scaled(normal, 1.0 / norm(normal));
}

Prescribed prescribedComponents(const mesh::Mesh& mesh, const ConstraintSpec& spec) {
  std::vector<DisplacementCondition> conditions;
  for (const auto& name : spec.dirichletNodeSets)
    conditions.push_back({"Dirichlet Node Sets (" + name + ")", name, {true, true, true}, {0.0, 0.0, 0.0}});
  conditions.insert(conditions.end(), spec.displacementConditions.begin(), spec.displacementConditions.end());
  const size_t n3 = 3 * static_cast<size_t>(mesh.numNodes());
  Prescribed p{std::vector<char>(n3, 0), std::vector<double>(n3, 0.0), std::vector<int>(n3, -1)};
  const int firstCondition = static_cast<int>(spec.dirichletNodeSets.size());
  std::vector<int> by(n3, -1);
  for (size_t k = 0; k < conditions.size(); ++k) {
    const auto& condition = conditions[k];
    for (double v : condition.value)
      core::requireInput(std::isfinite(v), "Boundary/" + condition.name + ": Displacement is not finite");
    for (LO n : mesh.nodeSet(condition.nodeSet).nodes)
      for (int c = 0; c < 3; ++c) {
        if (!condition.components[c]) continue;
        const size_t i = 3 * static_cast<size_t>(n) + c;
        if (by[i] >= 0 && p.value[i] != condition.value[c])
          throw core::InputError("Boundary: node " + std::to_string(n + 1) + " at " + str(mesh.coords[n]) + " gets u_" +
                                 "xyz"[c] + " = " + str(p.value[i]) + " from " + conditions[by[i]].name + " and " +
                                 str(condition.value[c]) + " from " + condition.name);
        const int shared = p.condition[i];
        if (shared >= 0 && condition.value[c] != 0.0 && shared != static_cast<int>(k) - firstCondition)
          p.overlapping.insert({shared, static_cast<int>(k) - firstCondition});
        p.fixed[i] = 1;
        p.value[i] = condition.value[c];
        by[i] = static_cast<int>(k);
        p.condition[i] = static_cast<int>(k) - firstCondition;
      }
  }
  return p;
}
}  // namespace

namespace {
/// The copies of every global node, in ascending subdomain order (ALGORITHMS.md 2): a CSR
/// node -> copies built by counting, O(#copies).
struct NodeCopies {
  std::vector<LO> ptr;
  std::vector<Copy> copies;
  LO count(LO node) const { return ptr[node + 1] - ptr[node]; }
  const Copy& of(LO node, LO j) const { return copies[ptr[node] + j]; }
};

NodeCopies nodeCopies(const mesh::Decomposition& decomposition, LO numNodes) {
  NodeCopies c;
  c.ptr.assign(numNodes + 1, 0);
  for (const auto& s : decomposition.subdomains)
    for (LO n : s.nodes) c.ptr[n + 1]++;
  for (LO n = 0; n < numNodes; ++n) c.ptr[n + 1] += c.ptr[n];
  c.copies.resize(c.ptr[numNodes]);
  std::vector<LO> fill(c.ptr.begin(), c.ptr.end() - 1);
  for (int s = 0; s < decomposition.numSubdomains(); ++s) {
    const auto& nodes = decomposition.subdomains[s].nodes;
    for (LO k = 0; k < static_cast<LO>(nodes.size()); ++k) c.copies[fill[nodes[k]]++] = {s, k};
  }
  return c;
}

/// What every row builder reads: the copies, the prescribed components and the owner rule.
struct RowContext {
  const NodeCopies& copies;
  const Prescribed& prescribed;
  int numSubdomains, numRanks;
  /// A row belongs to the rank that owns the lowest subdomain it touches (header).
  int ownerOf(const Entry* entries, size_t count) const {
    int lowest = numSubdomains;
    for (size_t e = 0; e < count; ++e) lowest = std::min(lowest, entries[e].subdomain);
    return mesh::ownerRank(lowest, numSubdomains, numRanks);
  }
};

/// The contact node of a slave node paired with `masterSide`: its master nodes and weights,
/// gap and frame (nu, t1, t2), right-handed.
ContactNode contactFrame(const mesh::ContactPair& pair, const mesh::MortarRow& masterSide,
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
  node.gap = masterSide.gap;
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

/// The row of contact node `node` along direction d (0: nu, 1: t1, 2: t2) over its nodes
/// `sides` (ContactNode::sides: +1 on the slave, -w_i on master node i), its scale recorded in `node`; or
/// false when it is dropped (the entries it appended are removed): a row (almost) entirely
/// on prescribed components, or a tangential row on a symmetry plane (both sides held along it).
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
          known += weight * dir[c] * prescribed.value[3 * global + c];
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
  // On a symmetry plane with normal t_j (the slave node and its nearest master node both
  // held along t_j, the slave free otherwise) nothing slips along t_j: the friction force
  // along it is the displacement condition's reaction. What would remain of the row (master
  // nodes off the plane, through the mortar weights) is no physical slip; its multiplier,
  // bounded by F g along an almost empty row, makes a needle-thin ellipse on which MPGP
  // crawls (measured on the Hertz half models: 24:1 semi-axes, 20 000 proportioning steps).
  // Where only the slave is held along t_j (a roller on one body at the contact edge) the
  // master can slip past it: the row stays, the slave's prescribed part in c, and Coulomb's
  // law acts on the master's tangential displacement (issue 30).
  // (A slave clamped in every component keeps its rows: the master slides on a fixed
  // point, and the friction acts on the master alone.)
  const bool symmetryPlane = d > 0 && !(slaveFree2 > 1e-12) && !prescribed.all(node.slaveNode) &&
                             !(freeAlong(prescribed, node.masterNode, dir) > 1e-12);
  if (!(free2 > 1e-16 * full2) || symmetryPlane) {
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
  std::sort(knownBy.begin(), knownBy.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (size_t i = 0; i < knownBy.size();) {  // one part per condition
    double sum = 0.0;
    size_t j = i;
    for (; j < knownBy.size() && knownBy[j].first == knownBy[i].first; ++j) sum += knownBy[j].second;
    list.addPart(row, knownBy[i].first, -scale * sum);
    i = j;
  }
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
    slave.push_back(mesh::sideSetNodes(mesh, mesh.sideSet(spec.slaveSideSet)));
    master.push_back(mesh::sideSetNodes(mesh, mesh.sideSet(spec.masterSideSet)));
  }
  for (size_t j = 0; j < interfaces.size(); ++j)
    for (size_t i = 0; i < j; ++i)
      if (aFaceWithin(mesh, interfaces[j].slaveSideSet, master[i]) &&
          aFaceWithin(mesh, interfaces[j].masterSideSet, slave[i]))
        throw core::InputError(interfaces[j].label() + " models the contact of " + interfaces[i].label() +
                               " again with slave and master swapped: give each contact once (a double pass "
                               "would split its forces between the two at random)");
}

/// The master side of every pair of an interface (dual mortar or node-to-surface weights).
std::vector<mesh::MortarRow> masterSidesOf(const mesh::Mesh& mesh, const ContactInterfaceSpec& spec,
                                           const mesh::ContactSearchResult& search) {
  std::vector<mesh::MortarRow> masterSides;
  if (spec.discretization == ContactDiscretization::Mortar) {
    const mesh::MasterSurface master(mesh, spec.masterSideSet);
    return mesh::dualMortarRows(mesh, spec.slaveSideSet, master, search, spec.searchDistance);
  }
  for (const auto& pair : search.pairs) masterSides.push_back(mesh::nodeToSurfaceRow(pair));
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

/// What the search and the mortar integration found on an interface, every pair on every rank.
/// An overlap is counted where it exceeds round-off (1e-12 of the slave surface's size): the
/// weighted gaps of coincident flat surfaces are +-1e-17, not overlaps a user should hear of.
ContactInterfaceRows interfaceRows(const mesh::Mesh& mesh, const ContactInterfaceSpec& spec,
                                   const mesh::ContactSearchResult& search,
                                   const std::vector<mesh::MortarRow>& masterSides) {
  const double roundOff = 1e-12 * diameter(mesh, mesh::sideSetNodes(mesh, mesh.sideSet(spec.slaveSideSet)));
  ContactInterfaceRows found;
  found.label = spec.label();
  found.list = spec.list();
  found.tied = spec.tied;
  found.pairedSlaveNodes = static_cast<GO>(search.pairs.size());
  found.unpairedSlaveNodes = static_cast<GO>(search.unpaired.size());
  constexpr size_t kSample = 5;
  found.unpairedSample.assign(search.unpaired.begin(),
                              search.unpaired.begin() + std::min(kSample, search.unpaired.size()));
  found.searchDistance = spec.searchDistance;
  // The initial overlaps of the rows (weighted where mortar).
  for (const auto& side : masterSides) {
    if (side.gap < -roundOff) {
      ++found.overlappingPairs;
      found.largestOverlap = std::max(found.largestOverlap, -side.gap);
    }
    if (side.gapLimited > 0.0) {
      ++found.limitedMortarGaps;
      found.largestGapLimit = std::max(found.largestGapLimit, side.gapLimited);
    }
  }
  return found;
}

/// The pairs of one interface: its search and the master side of each pair.
struct InterfacePairs {
  mesh::ContactSearchResult search;
  std::vector<mesh::MortarRow> masterSides;
};

InterfacePairs pairsOf(const mesh::Mesh& mesh, const ContactInterfaceSpec& spec) {
  InterfacePairs found;
  try {
    found.search = mesh::searchContactPairs(mesh, spec.slaveSideSet, spec.masterSideSet, spec.searchDistance);
    found.masterSides = masterSidesOf(mesh, spec, found.search);
  } catch (const core::InputError& e) {
    throw core::InputError(spec.label() + ": " + e.what());
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
    masterSides[keep++] = masterSides[p];
  }
  search.pairs.resize(keep);
  masterSides.resize(keep);
  B.interfaces.push_back(interfaceRows(mesh, spec, search, masterSides));
  B.interfaces.back().sharedSlaveNodes = shared;
  const int numDirections = spec.tangentialRows ? 3 : 1;
  list.rows.reserve(numDirections * search.pairs.size());
  for (size_t p = 0; p < search.pairs.size(); ++p) {
    ContactNode node = contactFrame(search.pairs[p], masterSides[p], spec, ctx.prescribed);
    node.interface = index;
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

namespace {
/// (3) Gluing rows (Helmert basis of the differences of the copies) per free component, and
/// displacement rows per prescribed component.
void addGluingAndDirichletRows(LO numNodes, const RowContext& ctx, RowList& list) {
  for (LO n = 0; n < numNodes; ++n) {
    const LO k = ctx.copies.count(n);
    // Copies ascend by subdomain, so copy 1 is the lowest one: every gluing row at this
    // node touches it and has the same owner.
    const int owner = k > 1 ? mesh::ownerRank(ctx.copies.of(n, 0).subdomain, ctx.numSubdomains, ctx.numRanks) : 0;
    for (int c = 0; c < 3; ++c) {
      if (ctx.prescribed.fixed[3 * n + c]) {
        // Every copy prescribed, no gluing rows: the paper's count (k-1 gluing + 1
        // Dirichlet per component) and B stays orthonormal (ALGORITHMS.md 2).
        for (LO j = 0; j < k; ++j) {
          const Copy& cp = ctx.copies.of(n, j);
          Row row = list.begin();
          row.kind = RowKind::Dirichlet;
          list.append({cp.subdomain, 3 * cp.localNode + c, 1.0});
          row.c = ctx.prescribed.value[3 * n + c];
          list.addPart(row, ctx.prescribed.condition[3 * n + c], row.c);
          row.key = {2, n, j, c};
          row.owner = mesh::ownerRank(cp.subdomain, ctx.numSubdomains, ctx.numRanks);
          list.add(row);
        }
        continue;
      }
      for (LO j = 1; j < k; ++j) {
        // Row j: copy j+1 against the mean of copies 1..j, i.e. coefficients -1/j and +1,
        // normalised by 1/sqrt(1 + 1/j); orthonormal and orthogonal to the mean.
        Row row = list.begin();
        row.kind = RowKind::Gluing;
        const double scale = 1.0 / std::sqrt(1.0 + 1.0 / j);
        for (LO i = 0; i < j; ++i) {
          const Copy& cp = ctx.copies.of(n, i);
          list.append({cp.subdomain, 3 * cp.localNode + c, -scale / j});
        }
        const Copy& cp = ctx.copies.of(n, j);
        list.append({cp.subdomain, 3 * cp.localNode + c, scale});
        row.key = {1, n, c, j};
        row.owner = owner;
        list.add(row);
      }
    }
  }
}

/// (4) Numbers the rows by (owner rank, key) (rank p owns a contiguous range), scatters them
/// into the per-subdomain blocks (of `keepForRank`'s subdomains and own rows only when >= 0),
/// and gives every row its id in the numbering by key alone.
void numberRows(RowList& list, int numSubdomains, int numRanks, int keepForRank, ConstraintMatrix& B) {
  std::vector<Row>& rows = list.rows;
  std::vector<size_t> order(rows.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return std::tie(rows[a].owner, rows[a].key) < std::tie(rows[b].owner, rows[b].key);
  });
  B.numRows = static_cast<GO>(rows.size());
  B.kind.resize(rows.size());
  B.c.resize(rows.size());
  B.firstRowOfRank.assign(numRanks + 1, 0);
  B.blocks.assign(numSubdomains, SubdomainBlock{});
  for (auto& blk : B.blocks) blk.rowPtr.push_back(0);
  // keepForRank: a row's entries in a subdomain of another rank are kept only when the row is
  // the rank's own (keepRankRows' rule).
  const bool keepAll = keepForRank < 0;
  const int firstKept = keepAll ? 0 : mesh::firstSubdomain(keepForRank, numSubdomains, numRanks);
  const int endKept = keepAll ? numSubdomains : mesh::firstSubdomain(keepForRank + 1, numSubdomains, numRanks);
  for (size_t r = 0; r < order.size(); ++r) {
    Row& row = rows[order[r]];
    B.kind[r] = row.kind;
    B.c[r] = row.c;
    B.firstRowOfRank[row.owner + 1]++;
    if (row.contact >= 0) B.contact[row.contact].normalRow = static_cast<GO>(r);
    for (int k = 0; k < row.numParts; ++k) {
      const auto& [condition, value] = list.parts[row.firstPart + static_cast<size_t>(k)];
      B.prescribedParts.push_back({static_cast<GO>(r), condition, value});
    }
    // Scatter into the blocks: rows arrive in ascending order, entries of one row sorted
    // by (subdomain, dof).
    Entry* entries = list.entriesOf(row);
    const size_t count = static_cast<size_t>(row.numEntries);
    std::sort(entries, entries + count,
              [](const Entry& a, const Entry& b) { return std::tie(a.subdomain, a.dof) < std::tie(b.subdomain, b.dof); });
    const bool ownRow = keepAll || row.owner == keepForRank;
    for (size_t e = 0; e < count;) {
      const int s = entries[e].subdomain;
      if (!ownRow && (s < firstKept || s >= endKept)) {
        while (e < count && entries[e].subdomain == s) ++e;
        continue;
      }
      SubdomainBlock& blk = B.blocks[s];
      blk.rows.push_back(static_cast<GO>(r));
      for (; e < count && entries[e].subdomain == s; ++e) {
        blk.dof.push_back(entries[e].dof);
        blk.value.push_back(entries[e].value);
      }
      blk.rowPtr.push_back(static_cast<LO>(blk.dof.size()));
    }
  }
  for (int p = 0; p < numRanks; ++p) B.firstRowOfRank[p + 1] += B.firstRowOfRank[p];
  // Row ids: the position in the order by key alone (keys are unique), i.e. the numbering
  // that one rank uses.
  std::vector<size_t> byKey(order);
  std::sort(byKey.begin(), byKey.end(), [&](size_t a, size_t b) { return rows[a].key < rows[b].key; });
  std::vector<GO> numberOf(rows.size());
  for (size_t r = 0; r < order.size(); ++r) numberOf[order[r]] = static_cast<GO>(r);
  B.rowId.resize(rows.size());
  for (size_t k = 0; k < byKey.size(); ++k) B.rowId[numberOf[byKey[k]]] = static_cast<GO>(k);
  // Contact nodes in row order (the header's contract).
  std::sort(B.contact.begin(), B.contact.end(),
            [](const ContactNode& a, const ContactNode& b) { return a.normalRow < b.normalRow; });
}
}  // namespace

ConstraintMatrix buildConstraintMatrix(const mesh::Mesh& mesh, const mesh::Decomposition& decomposition,
                                       const ConstraintSpec& spec, int numRanks, int keepForRank) {
  core::requireInput(numRanks >= 1, "buildConstraintMatrix: numRanks must be >= 1, got " + std::to_string(numRanks));
  core::requireInput(keepForRank < numRanks, "buildConstraintMatrix: keepForRank " + std::to_string(keepForRank) +
                                                 " is not a rank of " + std::to_string(numRanks));
  // (1) Copies of every global node, in ascending subdomain order (ALGORITHMS.md 2).
  const NodeCopies copies = nodeCopies(decomposition, mesh.numNodes());
  const Prescribed prescribed = prescribedComponents(mesh, spec);
  const RowContext ctx{copies, prescribed, decomposition.numSubdomains(), numRanks};
  RowList list;
  ConstraintMatrix B;
  B.overlappingConditions.assign(prescribed.overlapping.begin(), prescribed.overlapping.end());
  refuseContactsModelledTwice(mesh, spec.interfaces);
  std::vector<InterfacePairs> found;
  for (const auto& one : spec.interfaces) found.push_back(pairsOf(mesh, one));
  const std::vector<int> owner = slaveOwners(mesh.numNodes(), found);
  for (size_t i = 0; i < spec.interfaces.size(); ++i)
    addContactRows(mesh, spec, static_cast<int>(i), std::move(found[i]), owner, ctx, list, B);  // (2)
  addGluingAndDirichletRows(mesh.numNodes(), ctx, list);                    // (3)
  numberRows(list, decomposition.numSubdomains(), numRanks, keepForRank, B);  // (4)
  return B;
}

void keepRankRows(ConstraintMatrix& B, int rank, int firstOwned, int endOwned) {
  const GO first = B.firstRowOfRank.at(rank), end = B.firstRowOfRank.at(rank + 1);
  for (int s = 0; s < static_cast<int>(B.blocks.size()); ++s) {
    if (s >= firstOwned && s < endOwned) continue;
    const SubdomainBlock& full = B.blocks[s];
    SubdomainBlock kept;
    kept.rowPtr.push_back(0);
    // Rows ascend: the owned ones are one contiguous run.
    const auto lo = std::lower_bound(full.rows.begin(), full.rows.end(), first);
    const auto hi = std::lower_bound(lo, full.rows.end(), end);
    for (auto it = lo; it != hi; ++it) {
      const size_t i = static_cast<size_t>(it - full.rows.begin());
      kept.rows.push_back(*it);
      kept.dof.insert(kept.dof.end(), full.dof.begin() + full.rowPtr[i], full.dof.begin() + full.rowPtr[i + 1]);
      kept.value.insert(kept.value.end(), full.value.begin() + full.rowPtr[i], full.value.begin() + full.rowPtr[i + 1]);
      kept.rowPtr.push_back(static_cast<LO>(kept.dof.size()));
    }
    kept.rows.shrink_to_fit();
    kept.rowPtr.shrink_to_fit();
    kept.dof.shrink_to_fit();
    kept.value.shrink_to_fit();
    B.blocks[s] = std::move(kept);
  }
}

}  // namespace tribos::feti
