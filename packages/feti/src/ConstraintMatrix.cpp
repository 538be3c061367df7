/// \file ConstraintMatrix.cpp
/// B = [N; T1; T2; B_e; B_d] and c (paper Sections 3-4, ALGORITHMS.md 2). Every row is
/// built once as a list of (subdomain, local dof, value) entries, given its owner rank and
/// a sort key, then all rows are numbered by (owner, key) and scattered into the
/// per-subdomain blocks. Cost: O(#copies + #rows log #rows) plus O(#slave log #master)
/// for the contact pairing (a k-d tree), so Table 1's largest cell (125k rows) takes a few
/// tens of milliseconds.
#include "tribos/feti/ConstraintMatrix.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>
#include <tuple>

#include "tribos/core/Errors.hpp"

namespace tribos::feti {

GO ConstraintMatrix::count(RowKind k) const { return std::count(kind.begin(), kind.end(), k); }

namespace {
using Vec3 = std::array<double, 3>;

Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3 minus(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double norm(const Vec3& v) { return std::sqrt(dot(v, v)); }
Vec3 scaled(const Vec3& v, double s) { return {v[0] * s, v[1] * s, v[2] * s}; }

/// Numbers in error messages: std::to_string prints 1e-7 as "0.000000".
std::string str(double x) {
  std::ostringstream os;
  os.precision(10);
  os << x;
  return os.str();
}
std::string str(const Vec3& x) { return "(" + str(x[0]) + ", " + str(x[1]) + ", " + str(x[2]) + ")"; }

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
/// by (node, copy, component) (group 2).
struct Row {
  RowKind kind = RowKind::Gluing;
  std::vector<Entry> entries;
  double c = 0.0;
  int owner = 0;
  std::tuple<int, LO, int, int> key;
  int contact = -1;  ///< index into the contact nodes (N rows only)
};

/// Vertices of the faces of a side set, ascending, unique.
std::vector<LO> sideSetNodes(const mesh::Mesh& mesh, const mesh::SideSet& set) {
  std::vector<LO> nodes;
  nodes.reserve(3 * set.elements.size());
  for (size_t f = 0; f < set.elements.size(); ++f)
    for (int v : mesh::kTetFaceVertices[set.sides[f]]) nodes.push_back(mesh.tets[set.elements[f]][v]);
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  return nodes;
}

/// Sum over the faces of a side set of their outward normals (length = twice the face
/// area, so the sum is area-weighted), per node; zero off the set.
std::vector<Vec3> outerNormals(const mesh::Mesh& mesh, const mesh::SideSet& set) {
  std::vector<Vec3> normal(mesh.numNodes(), Vec3{0.0, 0.0, 0.0});
  for (size_t f = 0; f < set.elements.size(); ++f) {
    const auto& tet = mesh.tets[set.elements[f]];
    const Vec3 n = mesh.faceNormal(set.elements[f], set.sides[f]);
    for (int v : mesh::kTetFaceVertices[set.sides[f]])
      for (int d = 0; d < 3; ++d) normal[tet[v]][d] += n[d];
  }
  return normal;
}

/// Static k-d tree over the master-surface nodes for the nearest-node search. Unlike a
/// hash grid its cost does not depend on the search distance (which the user sets, from
/// 0 to far more than the mesh spacing): O(log n) per query. Ties in distance go to the
/// lower node id, so the pairing is deterministic.
class NearestNode {
 public:
  NearestNode(const mesh::Mesh& mesh, std::vector<LO> nodes)
      : coords_(mesh.coords), nodes_(std::move(nodes)), axis_(nodes_.size(), 0) {
    build(0, nodes_.size());
  }

  /// The nearest node within `radius` (distance <= radius), or -1; and its distance.
  std::pair<LO, double> nearest(const Vec3& x, double radius) const {
    LO best = -1;
    double best2 = radius * radius;
    search(0, nodes_.size(), x, best, best2);
    return {best, best < 0 ? std::numeric_limits<double>::infinity() : std::sqrt(best2)};
  }

 private:
  void build(size_t lo, size_t hi) {
    if (hi - lo <= 1) return;
    // Split on the widest extent of the range at its median.
    Vec3 low{}, high{};
    for (int d = 0; d < 3; ++d) low[d] = high[d] = coords_[nodes_[lo]][d];
    for (size_t i = lo; i < hi; ++i)
      for (int d = 0; d < 3; ++d) {
        low[d] = std::min(low[d], coords_[nodes_[i]][d]);
        high[d] = std::max(high[d], coords_[nodes_[i]][d]);
      }
    int axis = 0;
    for (int d = 1; d < 3; ++d)
      if (high[d] - low[d] > high[axis] - low[axis]) axis = d;
    const size_t mid = lo + (hi - lo) / 2;
    std::nth_element(nodes_.begin() + lo, nodes_.begin() + mid, nodes_.begin() + hi,
                     [&](LO a, LO b) { return coords_[a][axis] < coords_[b][axis]; });
    axis_[mid] = static_cast<signed char>(axis);
    build(lo, mid);
    build(mid + 1, hi);
  }

  void search(size_t lo, size_t hi, const Vec3& x, LO& best, double& best2) const {
    if (lo >= hi) return;
    const size_t mid = lo + (hi - lo) / 2;
    const LO n = nodes_[mid];
    const Vec3 diff = minus(coords_[n], x);
    const double d2 = dot(diff, diff);
    if (d2 < best2 || (d2 == best2 && (best < 0 || n < best))) {
      best = n;
      best2 = d2;
    }
    if (hi - lo == 1) return;
    const double along = x[axis_[mid]] - coords_[n][axis_[mid]];
    // Nodes left of mid have coordinate <= the split value, right of it >= (nth_element).
    const bool leftFirst = along < 0.0;
    search(leftFirst ? lo : mid + 1, leftFirst ? mid : hi, x, best, best2);
    if (along * along <= best2) search(leftFirst ? mid + 1 : lo, leftFirst ? hi : mid, x, best, best2);
  }

  const std::vector<std::array<double, 3>>& coords_;
  std::vector<LO> nodes_;
  std::vector<signed char> axis_;
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
}  // namespace

ConstraintMatrix buildConstraintMatrix(const mesh::Mesh& mesh, const mesh::Decomposition& decomposition,
                                       const ConstraintSpec& spec, int numRanks) {
  core::requireInput(numRanks >= 1, "buildConstraintMatrix: numRanks must be >= 1, got " + std::to_string(numRanks));
  const int numSubdomains = decomposition.numSubdomains();
  const LO numNodes = mesh.numNodes();

  // (1) Copies of every global node, in ascending subdomain order (ALGORITHMS.md 2): a
  // CSR node -> copies built by counting, O(#copies).
  std::vector<LO> copyPtr(numNodes + 1, 0);
  for (const auto& s : decomposition.subdomains)
    for (LO n : s.nodes) copyPtr[n + 1]++;
  for (LO n = 0; n < numNodes; ++n) copyPtr[n + 1] += copyPtr[n];
  std::vector<Copy> copies(copyPtr[numNodes]);
  {
    std::vector<LO> fill(copyPtr.begin(), copyPtr.end() - 1);
    for (int s = 0; s < numSubdomains; ++s) {
      const auto& nodes = decomposition.subdomains[s].nodes;
      for (LO k = 0; k < static_cast<LO>(nodes.size()); ++k) copies[fill[nodes[k]]++] = {s, k};
    }
  }
  auto numCopies = [&](LO node) { return copyPtr[node + 1] - copyPtr[node]; };

  std::vector<char> clamped(numNodes, 0);
  for (const auto& name : spec.dirichletNodeSets)
    for (LO n : mesh.nodeSet(name).nodes) clamped[n] = 1;

  // A row belongs to the rank that owns the lowest subdomain it touches (header).
  auto ownerOf = [&](const std::vector<Entry>& entries) {
    int lowest = numSubdomains;
    for (const auto& e : entries) lowest = std::min(lowest, e.subdomain);
    return mesh::ownerRank(lowest, numSubdomains, numRanks);
  };

  std::vector<Row> rows;
  ConstraintMatrix B;

  // (2) Contact rows: node-to-node, slave -> master (paper Section 3, ALGORITHMS.md 2,
  // DESIGN.md conventions).
  core::requireInput(spec.slaveSideSet.empty() == spec.masterSideSet.empty(),
                     "contact: give both the slave and the master side set, or neither (slave \"" +
                         spec.slaveSideSet + "\", master \"" + spec.masterSideSet + "\")");
  if (!spec.slaveSideSet.empty()) {
    const auto& slaveSet = mesh.sideSet(spec.slaveSideSet);
    const auto& masterSet = mesh.sideSet(spec.masterSideSet);
    const auto slaves = sideSetNodes(mesh, slaveSet);
    const NearestNode masters(mesh, sideSetNodes(mesh, masterSet));
    const auto slaveNormal = outerNormals(mesh, slaveSet);
    const double radius = std::max(spec.searchDistance, 0.0);
    // Gaps below round-off of the coordinates count as zero (then nu = the outer normal).
    double coordinateScale = 1.0;
    for (const auto& x : mesh.coords)
      coordinateScale = std::max({coordinateScale, std::abs(x[0]), std::abs(x[1]), std::abs(x[2])});
    const double zeroGap = 1e-12 * coordinateScale;
    const int numDirections = spec.tangentialRows ? 3 : 1;
    rows.reserve(numDirections * slaves.size());

    for (LO slave : slaves) {
      const Vec3& xs = mesh.coords[slave];
      const auto [master, distance] = masters.nearest(xs, radius);
      if (master < 0) {
        const double nearest = masters.nearest(xs, std::numeric_limits<double>::infinity()).second;
        throw core::InputError("contact: slave node " + std::to_string(slave + 1) + " at " + str(xs) +
                               " of side set \"" + spec.slaveSideSet + "\" has no node of side set \"" +
                               spec.masterSideSet + "\" within Contact/Search Distance = " + str(radius) +
                               " (the nearest is at distance " + str(nearest) + ")");
      }
      if (master == slave)
        throw core::InputError("contact: node " + std::to_string(slave + 1) + " belongs to both side sets \"" +
                               spec.slaveSideSet + "\" and \"" + spec.masterSideSet +
                               "\": the bodies share their interface nodes; give each body its own nodes "
                               "(gmsh meshes: tribos-msh2exo --split-bodies)");
      ContactNode node;
      node.slaveNode = slave;
      node.masterNode = master;
      const Vec3 outer = slaveNormal[slave];
      const double outerLength = norm(outer);
      core::requireInput(outerLength > 0.0, "contact: the faces of side set \"" + spec.slaveSideSet +
                                                "\" at slave node " + std::to_string(slave + 1) + " at " + str(xs) +
                                                " have a zero summed normal (degenerate or folded surface)");
      const Vec3 toMaster = minus(mesh.coords[master], xs);
      if (distance > zeroGap) {
        // nu from the slave node to its master node, d = their distance (DESIGN.md). A
        // master node behind the slave's surface means the bodies overlap initially: with
        // nu pointing into the slave body the non-penetration row would be meaningless.
        core::requireInput(dot(toMaster, outer) > 0.0,
                           "contact: master node " + std::to_string(master + 1) + " at " + str(mesh.coords[master]) +
                               " lies behind the surface of side set \"" + spec.slaveSideSet + "\" at slave node " +
                               std::to_string(slave + 1) + " at " + str(xs) +
                               " (initial penetration, or nodes meant to coincide that differ by " + str(distance) +
                               ")");
        node.normal = scaled(toMaster, 1.0 / distance);
        node.gap = distance;
      } else {
        node.normal = scaled(outer, 1.0 / outerLength);
        node.gap = 0.0;
      }
      node.t1 = tangent(spec.t1Direction, node.normal);
      node.t2 = cross(node.normal, node.t1);  // right-handed (nu, t1, t2)

      const bool slaveFixed = clamped[slave], masterFixed = clamped[master];
      if (slaveFixed && masterFixed) {
        // Both sides clamped: N, T1, T2 at this node are combinations of Dirichlet rows
        // (DESIGN.md: the paper's Table 1 counts them; we remove and count them).
        B.removedRedundantRows += numDirections;
        continue;
      }
      // Rows act on (mean of the slave copies - mean of the master copies), weights 1/k:
      // then they are orthogonal to every gluing row (which is orthogonal to the mean) and
      // to the Dirichlet rows (a clamped side is dropped, its displacement is zero).
      const LO ks = numCopies(slave), km = numCopies(master);
      const double ws = slaveFixed ? 0.0 : 1.0 / ks, wm = masterFixed ? 0.0 : 1.0 / km;
      node.rowScale = 1.0 / std::sqrt(ws * ws * ks + wm * wm * km);  // raw norm sqrt(1/ks + 1/km)
      const int contactIndex = static_cast<int>(B.contact.size());
      const Vec3* directions[3] = {&node.normal, &node.t1, &node.t2};
      for (int d = 0; d < numDirections; ++d) {
        const Vec3& dir = *directions[d];
        Row row;
        row.kind = static_cast<RowKind>(d);
        row.entries.reserve(3 * (ks + km));
        auto addSide = [&](LO global, double weight) {
          for (LO k = copyPtr[global]; k < copyPtr[global + 1]; ++k)
            for (int c = 0; c < 3; ++c)
              if (dir[c] != 0.0)
                row.entries.push_back({copies[k].subdomain, 3 * copies[k].localNode + c, weight * dir[c] * node.rowScale});
        };
        if (!slaveFixed) addSide(slave, ws);
        if (!masterFixed) addSide(master, -wm);
        // N u <= c: rowScale (u_s - u_m) . nu <= rowScale d.
        row.c = d == 0 ? node.rowScale * node.gap : 0.0;
        row.key = {0, slave, d, 0};
        row.contact = d == 0 ? contactIndex : -1;
        row.owner = ownerOf(row.entries);
        rows.push_back(std::move(row));
      }
      B.contact.push_back(node);
    }
  }

  // (3) Gluing (Helmert basis of the differences of the copies) and Dirichlet rows.
  for (LO n = 0; n < numNodes; ++n) {
    const LO k = numCopies(n);
    if (clamped[n]) {
      // Every copy fixed, no gluing rows: same count as the paper (k-1 gluing + 1
      // Dirichlet per component) and B stays orthonormal (ALGORITHMS.md 2).
      for (LO j = 0; j < k; ++j)
        for (int c = 0; c < 3; ++c) {
          const Copy& cp = copies[copyPtr[n] + j];
          Row row;
          row.kind = RowKind::Dirichlet;
          row.entries.push_back({cp.subdomain, 3 * cp.localNode + c, 1.0});
          row.key = {2, n, j, c};
          row.owner = mesh::ownerRank(cp.subdomain, numSubdomains, numRanks);
          rows.push_back(std::move(row));
        }
      continue;
    }
    // Copies ascend by subdomain, so copy 1 is the lowest one: every row at this node
    // touches it and has the same owner.
    const int owner = k > 1 ? mesh::ownerRank(copies[copyPtr[n]].subdomain, numSubdomains, numRanks) : 0;
    for (int c = 0; c < 3; ++c)
      for (LO j = 1; j < k; ++j) {
        // Row j: copy j+1 against the mean of copies 1..j, i.e. coefficients -1/j and +1,
        // normalised by 1/sqrt(1 + 1/j); orthonormal and orthogonal to the mean.
        Row row;
        row.kind = RowKind::Gluing;
        const double scale = 1.0 / std::sqrt(1.0 + 1.0 / j);
        row.entries.reserve(j + 1);
        for (LO i = 0; i < j; ++i) {
          const Copy& cp = copies[copyPtr[n] + i];
          row.entries.push_back({cp.subdomain, 3 * cp.localNode + c, -scale / j});
        }
        const Copy& cp = copies[copyPtr[n] + j];
        row.entries.push_back({cp.subdomain, 3 * cp.localNode + c, scale});
        row.key = {1, n, c, j};
        row.owner = owner;
        rows.push_back(std::move(row));
      }
  }

  // (4) Number the rows by (owner rank, key): rank p owns a contiguous range.
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
  for (size_t r = 0; r < order.size(); ++r) {
    Row& row = rows[order[r]];
    B.kind[r] = row.kind;
    B.c[r] = row.c;
    B.firstRowOfRank[row.owner + 1]++;
    if (row.contact >= 0) B.contact[row.contact].normalRow = static_cast<GO>(r);
    // Scatter into the blocks: rows arrive in ascending order, entries of one row sorted
    // by (subdomain, dof).
    std::sort(row.entries.begin(), row.entries.end(),
              [](const Entry& a, const Entry& b) { return std::tie(a.subdomain, a.dof) < std::tie(b.subdomain, b.dof); });
    for (size_t e = 0; e < row.entries.size();) {
      const int s = row.entries[e].subdomain;
      SubdomainBlock& blk = B.blocks[s];
      blk.rows.push_back(static_cast<GO>(r));
      for (; e < row.entries.size() && row.entries[e].subdomain == s; ++e) {
        blk.dof.push_back(row.entries[e].dof);
        blk.value.push_back(row.entries[e].value);
      }
      blk.rowPtr.push_back(static_cast<LO>(blk.dof.size()));
    }
  }
  for (int p = 0; p < numRanks; ++p) B.firstRowOfRank[p + 1] += B.firstRowOfRank[p];
  // Contact nodes in row order (the header's contract).
  std::sort(B.contact.begin(), B.contact.end(),
            [](const ContactNode& a, const ContactNode& b) { return a.normalRow < b.normalRow; });
  return B;
}

}  // namespace tribos::feti
