#pragma once
/// \file ConstraintRows.hpp
/// What the builders of the rows of B share (private to feti; ConstraintMatrix.cpp builds
/// the gluing and Dirichlet rows and numbers them all, ContactRows.cpp the contact rows):
/// the copies of every node, the prescribed components, a row before numbering and the list
/// that holds the rows' entries.
#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "tribos/core/Format.hpp"
#include "tribos/feti/ConstraintMatrix.hpp"
#include "tribos/mesh/Decomposition.hpp"
#include "tribos/mesh/Mesh.hpp"

namespace tribos::feti::rows {

using Vec3 = std::array<double, 3>;

inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline Vec3 minus(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline double norm(const Vec3& v) { return std::sqrt(dot(v, v)); }
inline Vec3 scaled(const Vec3& v, double s) { return {v[0] * s, v[1] * s, v[2] * s}; }

inline std::string str(double x) { return core::formatNumber(x); }
inline std::string str(const Vec3& x) { return core::formatPoint(x); }

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
  /// (subdomain, local dof) of the components eliminated instead of given rows.
  std::vector<std::pair<int, LO>> eliminated;
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

/// Prescribed displacement components: per (node, component) whether it is prescribed,
/// its value and the condition that prescribed it.
struct Prescribed {
  std::vector<char> fixed;     ///< 3 * numNodes
  std::vector<double> value;   ///< 3 * numNodes
  /// 3 * numNodes: where the condition's rows start from (ConstraintSpec::conditionBase; 0 for
  /// the reference): the row's c is base + value, its part (which factors scale) the value.
  std::vector<double> base;
  /// 3 * numNodes: index into ConstraintSpec::displacementConditions (-1: none, or a
  /// Dirichlet Node Set, whose value 0 no factor scales).
  std::vector<int> condition;
  /// Pairs of displacement conditions that prescribe one component of a node to the same
  /// non-zero value (ConstraintMatrix::overlappingConditions).
  std::set<std::pair<int, int>> overlapping;
  bool any(LO node) const { return fixed[3 * node] || fixed[3 * node + 1] || fixed[3 * node + 2]; }
  bool all(LO node) const { return fixed[3 * node] && fixed[3 * node + 1] && fixed[3 * node + 2]; }
};

/// The copies of every global node, in ascending subdomain order (ALGORITHMS.md 2): a CSR
/// node -> copies built by counting, O(#copies).
struct NodeCopies {
  std::vector<LO> ptr;
  std::vector<Copy> copies;
  LO count(LO node) const { return ptr[node + 1] - ptr[node]; }
  const Copy& of(LO node, LO j) const { return copies[ptr[node] + j]; }
};

NodeCopies nodeCopies(const mesh::Decomposition& decomposition, LO numNodes);

/// What every row builder reads: the copies, the prescribed components and the owner rule.
struct RowContext {
  const NodeCopies& copies;
  const Prescribed& prescribed;
  int numSubdomains, numRanks;
  ZeroComponents zeroComponents;  ///< ConstraintSpec::zeroComponents
  /// Per subdomain, whether its zero components are eliminated (ConstraintSpec::zeroComponents,
  /// where they hold its rigid modes firmly); empty: none.
  std::vector<char> eliminateIn;
  /// A row belongs to the rank that owns the lowest subdomain it touches (header).
  int ownerOf(const Entry* entries, size_t count) const {
    int lowest = numSubdomains;
    for (size_t e = 0; e < count; ++e) lowest = std::min(lowest, entries[e].subdomain);
    return mesh::ownerRank(lowest, numSubdomains, numRanks);
  }
};


/// Per (node, component): prescribed or not, its value and condition; refuses a component
/// prescribed twice with different values (core::InputError naming both conditions).
Prescribed prescribedComponents(const mesh::Mesh& mesh, const ConstraintSpec& spec);

/// (2) The contact rows of every interface of `spec` (ContactRows.cpp), appended to `list`; the
/// contact nodes and per-interface findings to B. Refuses self-contact and contacts modelled
/// twice (core::InputError naming the interfaces).
void addAllContactRows(const mesh::Mesh& mesh, const ConstraintSpec& spec, const RowContext& ctx, RowList& list,
                       ConstraintMatrix& B);

}  // namespace tribos::feti::rows
