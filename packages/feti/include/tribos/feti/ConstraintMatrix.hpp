#pragma once
/// \file ConstraintMatrix.hpp
/// The T-FETI constraint matrix B = [N; T1; T2; B_e; B_d] and the gap vector c (paper
/// Sections 3-4, ALGORITHMS.md 2), with every row of unit norm and B B^T = I:
///  - gluing: a node shared by k subdomain copies gets k-1 rows per component, an
///    orthonormal (Helmert) basis of the differences: row j couples copy j+1 against the
///    mean of copies 1..j;
///  - Dirichlet: at a clamped node every copy gets a unit row per component (no gluing
///    rows there) — the paper's count, and B stays orthonormal;
///  - contact (node-to-node, slave side -> master side): rows N_r, T1_r, T2_r acting on
///    (mean of the slave copies - mean of the master copies) projected on nu, t1, t2 and
///    scaled to unit norm; orthogonal to the gluing rows by construction. A side that is
///    clamped is dropped from the row (its displacement is zero anyway); a contact node
///    whose two sides are both clamped gives redundant rows: they are removed and counted.
/// B is built on every rank (it is small next to the subdomain factors); each row is owned
/// by one rank — the owner of the lowest subdomain it touches — and rows are numbered so
/// that the rows of rank p are the contiguous range [firstRowOfRank[p], firstRowOfRank[p+1]).
/// Within a rank: contact triples (N, T1, T2 consecutive per contact node), then gluing,
/// then Dirichlet rows.
#include <array>
#include <string>
#include <vector>

#include "tribos/mesh/Decomposition.hpp"

namespace tribos::feti {

enum class RowKind : int { ContactNormal = 0, ContactT1 = 1, ContactT2 = 2, Gluing = 3, Dirichlet = 4 };

struct ConstraintSpec {
  std::vector<std::string> dirichletNodeSets;  ///< node sets with u = 0
  std::string slaveSideSet, masterSideSet;     ///< contact surfaces; both empty = no contact
  bool tangentialRows = true;                  ///< T1, T2 rows (friction or bonded); false: N only
  std::array<double, 3> t1Direction{1.0, 0.0, 0.0};  ///< t1 = this projected on the tangent plane
  /// A slave node pairs with the nearest master-surface node within this distance (the
  /// mesh's units); farther means no partner (InputError naming the node).
  double searchDistance = 1e-6;
};

/// One slave contact node r with its partner and frame (DESIGN.md conventions).
struct ContactNode {
  LO slaveNode = -1, masterNode = -1;      ///< global mesh node ids
  std::array<double, 3> normal{}, t1{}, t2{};  ///< orthonormal frame, normal from slave to master
  double gap = 0.0;                        ///< d_r: distance from slave to master along normal (>= 0)
  GO normalRow = -1;                       ///< row of N_r (T1_r = normalRow + 1, T2_r = + 2)
  double rowScale = 1.0;                   ///< the factor that made the contact rows unit norm
};

/// B_s: the rows of B that touch subdomain s, as a sparse (rows x local dofs) matrix.
struct SubdomainBlock {
  std::vector<GO> rows;      ///< global row ids, ascending
  std::vector<LO> rowPtr;    ///< rows.size() + 1
  std::vector<LO> dof;       ///< local dof (3 * local node + component)
  std::vector<double> value;
};

struct ConstraintMatrix {
  GO numRows = 0;                    ///< n_d after removing redundant rows
  GO removedRedundantRows = 0;       ///< rows removed as redundant (n_d + this = paper's n_d)
  std::vector<RowKind> kind;         ///< per row
  std::vector<double> c;             ///< per row: scaled gap for N rows, 0 otherwise
  std::vector<GO> firstRowOfRank;    ///< numRanks + 1 entries
  std::vector<ContactNode> contact;  ///< contact nodes, in row order
  std::vector<SubdomainBlock> blocks;  ///< index = global subdomain
  GO count(RowKind k) const;
};

/// Builds B and c. Throws core::InputError naming the set / node on bad input (unknown
/// set, a slave node without a master partner within searchDistance).
ConstraintMatrix buildConstraintMatrix(const mesh::Mesh& mesh, const mesh::Decomposition& decomposition,
                                       const ConstraintSpec& spec, int numRanks);

}  // namespace tribos::feti
