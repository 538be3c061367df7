#include "tribos/feti/ConstraintMatrix.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <unordered_map>

#include "tribos/core/Errors.hpp"

namespace tribos::feti {

GO ConstraintMatrix::count(RowKind k) const { return std::count(kind.begin(), kind.end(), k); }

namespace {
using Vec3 = std::array<double, 3>;

Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3 normalized(Vec3 v) {
  const double n = std::sqrt(dot(v, v));
  return {v[0] / n, v[1] / n, v[2] / n};
}

struct Copy {
  int subdomain;
  LO localNode;
};

struct Entry {
  int subdomain;
  LO dof;
  double value;
};

/// A row before numbering: its entries, gap, kind, owner and a sort key that gives the
/// documented order (contact triples by slave node, then gluing, then Dirichlet).
struct Row {
  RowKind kind;
  std::vector<Entry> entries;
  double c = 0.0;
  int owner = 0;
  std::tuple<int, LO, int, int> key;  // (group, node, component / direction, j)
  int contact = -1;                   // index into contact nodes (N rows only)
};

/// Nodes of the faces of a side set, ascending.
std::vector<LO> sideSetNodes(const mesh::Mesh& mesh, const mesh::SideSet& set) {
  std::vector<LO> nodes;
  for (size_t f = 0; f < set.elements.size(); ++f)
    for (int v : mesh::kTetFaceVertices[set.sides[f]]) nodes.push_back(mesh.tets[set.elements[f]][v]);
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  return nodes;
}

/// Area-weighted outer normals of a side set, summed per node.
std::unordered_map<LO, Vec3> outerNormals(const mesh::Mesh& mesh, const mesh::SideSet& set) {
  std::unordered_map<LO, Vec3> normal;
  for (size_t f = 0; f < set.elements.size(); ++f) {
    const auto& tet = mesh.tets[set.elements[f]];
    const Vec3 n = mesh.faceNormal(set.elements[f], set.sides[f]);
    for (int v : mesh::kTetFaceVertices[set.sides[f]]) {
      auto& acc = normal[tet[v]];
      for (int d = 0; d < 3; ++d) acc[d] += n[d];
    }
  }
  return normal;
}

/// Uniform hash grid over the master nodes for the nearest-node search.
class NodeGrid {
 public:
  NodeGrid(const mesh::Mesh& mesh, const std::vector<LO>& nodes, double cell) : mesh_(mesh), cell_(cell) {
    for (LO n : nodes) cells_[key(cellOf(mesh.coords[n]))].push_back(n);
  }
  /// Nearest node within `radius` (<= cell), or -1; also returns the distance.
  std::pair<LO, double> nearest(const Vec3& x, double radius) const {
    const auto c = cellOf(x);
    LO best = -1;
    double bestDistance = radius;
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy)
        for (long long dz = -1; dz <= 1; ++dz) {
          const auto it = cells_.find(key({c[0] + dx, c[1] + dy, c[2] + dz}));
          if (it == cells_.end()) continue;
          for (LO n : it->second) {
            const auto& y = mesh_.coords[n];
            const double d = std::sqrt(dot({y[0] - x[0], y[1] - x[1], y[2] - x[2]}, {y[0] - x[0], y[1] - x[1], y[2] - x[2]}));
            if (d <= bestDistance && (best < 0 || d < bestDistance || n < best)) {
              best = n;
              bestDistance = d;
            }
          }
        }
    return {best, bestDistance};
  }
  /// Distance to the nearest node anywhere (for error messages): brute force.
  double nearestAnywhere(const Vec3& x) const {
    double best = INFINITY;
    for (const auto& [k, nodes] : cells_)
      for (LO n : nodes) {
        const auto& y = mesh_.coords[n];
        best = std::min(best, std::sqrt(dot({y[0] - x[0], y[1] - x[1], y[2] - x[2]}, {y[0] - x[0], y[1] - x[1], y[2] - x[2]})));
      }
    return best;
  }

 private:
  std::array<long long, 3> cellOf(const Vec3& x) const {
    return {static_cast<long long>(std::floor(x[0] / cell_)), static_cast<long long>(std::floor(x[1] / cell_)),
            static_cast<long long>(std::floor(x[2] / cell_))};
  }
  static long long key(const std::array<long long, 3>& c) {
    return (c[0] * 73856093LL) ^ (c[1] * 19349663LL) ^ (c[2] * 83492791LL);
  }
  const mesh::Mesh& mesh_;
  double cell_;
  std::unordered_map<long long, std::vector<LO>> cells_;
};
}  // namespace

ConstraintMatrix buildConstraintMatrix(const mesh::Mesh& mesh, const mesh::Decomposition& decomposition,
                                       const ConstraintSpec& spec, int numRanks) {
  const int numSubdomains = decomposition.numSubdomains();
  const LO numNodes = mesh.numNodes();

  // (1) Copies of every global node, in ascending subdomain order.
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
  std::vector<char> clamped(numNodes, 0);
  for (const auto& name : spec.dirichletNodeSets)
    for (LO n : mesh.nodeSet(name).nodes) clamped[n] = 1;

  std::vector<Row> rows;
  ConstraintMatrix B;
  auto ownerOf = [&](const std::vector<Entry>& entries) {
    int lowest = numSubdomains;
    for (const auto& e : entries) lowest = std::min(lowest, e.subdomain);
    return mesh::ownerRank(lowest, numSubdomains, numRanks);
  };

  // (2) Contact rows (node-to-node, slave -> master; ALGORITHMS.md 2, DESIGN.md conventions).
  if (!spec.slaveSideSet.empty()) {
    const auto& slaveSet = mesh.sideSet(spec.slaveSideSet);
    const auto& masterSet = mesh.sideSet(spec.masterSideSet);
    const auto slaves = sideSetNodes(mesh, slaveSet);
    const auto masters = sideSetNodes(mesh, masterSet);
    const auto slaveNormal = outerNormals(mesh, slaveSet);
    const double radius = spec.searchDistance;
    const NodeGrid grid(mesh, masters, std::max(radius, 1e-300));
    double meshScale = 0.0;
    for (const auto& x : mesh.coords) meshScale = std::max({meshScale, std::abs(x[0]), std::abs(x[1]), std::abs(x[2])});
    for (LO slave : slaves) {
      const auto& xs = mesh.coords[slave];
      const auto [master, distance] = grid.nearest(xs, radius);
      if (master < 0)
        throw core::InputError("contact: slave node " + std::to_string(slave + 1) + " at (" + std::to_string(xs[0]) +
                               ", " + std::to_string(xs[1]) + ", " + std::to_string(xs[2]) + ") of side set \"" +
                               spec.slaveSideSet + "\" has no node of \"" + spec.masterSideSet + "\" within " +
                               "Contact/Search Distance = " + std::to_string(radius) + " (nearest: " +
                               std::to_string(grid.nearestAnywhere(xs)) + ")");
      if (master == slave)
        throw core::InputError("contact: node " + std::to_string(slave + 1) + " belongs to both \"" + spec.slaveSideSet +
                               "\" and \"" + spec.masterSideSet +
                               "\": the bodies share their interface nodes; give each body its own nodes "
                               "(gmsh meshes: tribos-msh2exo --split-bodies)");
      ContactNode node;
      node.slaveNode = slave;
      node.masterNode = master;
      const auto& xm = mesh.coords[master];
      if (distance > 1e-12 * std::max(meshScale, 1.0)) {
        node.normal = normalized({xm[0] - xs[0], xm[1] - xs[1], xm[2] - xs[2]});
        node.gap = distance;
      } else {
        node.normal = normalized(slaveNormal.at(slave));
        node.gap = 0.0;
      }
      // t1: the user's direction projected on the tangent plane; t2 = nu x t1.
      Vec3 t1 = spec.t1Direction;
      for (const Vec3& fallback : {spec.t1Direction, Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}}) {
        t1 = fallback;
        const double along = dot(t1, node.normal);
        for (int d = 0; d < 3; ++d) t1[d] -= along * node.normal[d];
        if (std::sqrt(dot(t1, t1)) > 1e-6 * std::sqrt(dot(fallback, fallback))) break;
      }
      node.t1 = normalized(t1);
      node.t2 = cross(node.normal, node.t1);

      const bool slaveFixed = clamped[slave], masterFixed = clamped[master];
      const int numDirections = spec.tangentialRows ? 3 : 1;
      if (slaveFixed && masterFixed) {  // both sides clamped: the rows are redundant
        B.removedRedundantRows += numDirections;
        continue;
      }
      // Mean of the slave copies minus mean of the master copies; a clamped side is dropped.
      const LO ks = copyPtr[slave + 1] - copyPtr[slave], km = copyPtr[master + 1] - copyPtr[master];
      const double norm2 = (slaveFixed ? 0.0 : 1.0 / ks) + (masterFixed ? 0.0 : 1.0 / km);
      node.rowScale = 1.0 / std::sqrt(norm2);
      const int contactIndex = static_cast<int>(B.contact.size());
      const Vec3* directions[3] = {&node.normal, &node.t1, &node.t2};
      for (int d = 0; d < numDirections; ++d) {
        Row row;
        row.kind = static_cast<RowKind>(d);
        auto addSide = [&](LO global, double weight) {
          for (LO k = copyPtr[global]; k < copyPtr[global + 1]; ++k)
            for (int c = 0; c < 3; ++c)
              if ((*directions[d])[c] != 0.0)
                row.entries.push_back({copies[k].subdomain, 3 * copies[k].localNode + c,
                                       weight * (*directions[d])[c] * node.rowScale});
        };
        if (!slaveFixed) addSide(slave, 1.0 / ks);
        if (!masterFixed) addSide(master, -1.0 / km);
        row.c = d == 0 ? node.rowScale * node.gap : 0.0;
        row.key = {0, slave, d, 0};
        row.contact = d == 0 ? contactIndex : -1;
        rows.push_back(std::move(row));
      }
      B.contact.push_back(node);
    }
    // All rows of one contact node touch the same subdomains: one owner for the triple.
    for (auto& row : rows) row.owner = ownerOf(row.entries);
  }

  // (3) Gluing (Helmert basis of the differences of the copies) and Dirichlet rows.
  for (LO n = 0; n < numNodes; ++n) {
    const LO k = copyPtr[n + 1] - copyPtr[n];
    if (clamped[n]) {
      for (LO j = 0; j < k; ++j)
        for (int c = 0; c < 3; ++c) {
          Row row;
          row.kind = RowKind::Dirichlet;
          const Copy& cp = copies[copyPtr[n] + j];
          row.entries.push_back({cp.subdomain, 3 * cp.localNode + c, 1.0});
          row.key = {2, n, j, c};
          row.owner = ownerOf(row.entries);
          rows.push_back(std::move(row));
        }
      continue;
    }
    for (int c = 0; c < 3; ++c)
      for (LO j = 1; j < k; ++j) {
        // Copy j+1 against the mean of copies 1..j: coefficients -1/j and +1, normalised.
        Row row;
        row.kind = RowKind::Gluing;
        const double scale = 1.0 / std::sqrt(1.0 + 1.0 / j);
        for (LO i = 0; i < j; ++i) {
          const Copy& cp = copies[copyPtr[n] + i];
          row.entries.push_back({cp.subdomain, 3 * cp.localNode + c, -scale / j});
        }
        const Copy& cp = copies[copyPtr[n] + j];
        row.entries.push_back({cp.subdomain, 3 * cp.localNode + c, scale});
        row.key = {1, n, c, j};
        row.owner = ownerOf(row.entries);
        rows.push_back(std::move(row));
      }
  }

  // (4) Number the rows: by owner rank, then group and key.
  std::vector<size_t> order(rows.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return std::tie(rows[a].owner, rows[a].key) < std::tie(rows[b].owner, rows[b].key);
  });
  B.numRows = static_cast<GO>(rows.size());
  B.kind.resize(rows.size());
  B.c.resize(rows.size());
  B.firstRowOfRank.assign(numRanks + 1, 0);
  B.blocks.assign(numSubdomains, SubdomainBlock{});
  std::vector<std::vector<std::pair<LO, double>>> rowEntries;  // per subdomain, scratch
  for (size_t r = 0; r < order.size(); ++r) {
    Row& row = rows[order[r]];
    B.kind[r] = row.kind;
    B.c[r] = row.c;
    B.firstRowOfRank[row.owner + 1]++;
    if (row.contact >= 0) B.contact[row.contact].normalRow = static_cast<GO>(r);
    std::sort(row.entries.begin(), row.entries.end(),
              [](const Entry& a, const Entry& b) { return std::tie(a.subdomain, a.dof) < std::tie(b.subdomain, b.dof); });
    for (size_t e = 0; e < row.entries.size();) {
      SubdomainBlock& blk = B.blocks[row.entries[e].subdomain];
      if (blk.rowPtr.empty()) blk.rowPtr.push_back(0);
      blk.rows.push_back(static_cast<GO>(r));
      const int s = row.entries[e].subdomain;
      for (; e < row.entries.size() && row.entries[e].subdomain == s; ++e) {
        blk.dof.push_back(row.entries[e].dof);
        blk.value.push_back(row.entries[e].value);
      }
      blk.rowPtr.push_back(static_cast<LO>(blk.dof.size()));
    }
  }
  for (int p = 0; p < numRanks; ++p) B.firstRowOfRank[p + 1] += B.firstRowOfRank[p];
  for (auto& blk : B.blocks)
    if (blk.rowPtr.empty()) blk.rowPtr.push_back(0);
  // Contact nodes in row order.
  std::sort(B.contact.begin(), B.contact.end(),
            [](const ContactNode& a, const ContactNode& b) { return a.normalRow < b.normalRow; });
  return B;
}

}  // namespace tribos::feti
