#pragma once
/// \file Decomposition.hpp
/// Subdomains of a mesh (T-FETI: every subdomain is a floating body with its own copy of
/// each of its nodes) and their distribution over MPI ranks.
#include <array>
#include <vector>

#include "tribos/mesh/Mesh.hpp"

namespace tribos::mesh {

struct Subdomain {
  int body = 0;                          ///< index of the element block it lies in
  std::vector<LO> elements;              ///< global element ids, ascending
  std::vector<LO> nodes;                 ///< global node ids, ascending: local node i <-> nodes[i]
  Connectivity localElements;            ///< the elements in local node numbering
  LO numNodes() const { return static_cast<LO>(nodes.size()); }
  LO numDofs() const { return 3 * numNodes(); }
};

struct Decomposition {
  std::vector<Subdomain> subdomains;  ///< all subdomains; index = global subdomain id
  std::vector<int> elementPart;       ///< subdomain of every element
  int numSubdomains() const { return static_cast<int>(subdomains.size()); }
  /// n = sum of subdomain dofs (the paper's n, Table 1).
  long long numPrimalDofs() const;
};

/// Builds the subdomains from an element -> part map (parts 0..P-1, all non-empty).
/// Throws core::InputError if a part is empty or spans two element blocks (bodies).
Decomposition buildDecomposition(const Mesh& mesh, const std::vector<int>& elementPart);

/// METIS partition of a general mesh into `numParts` parts, face-adjacent (ncommon = 3) and
/// contiguous. Each body (element block) is partitioned on its own, so no part spans two
/// bodies; body b gets a share of the parts proportional to its element count (at least
/// one). Throws core::InputError naming "Mesh/Subdomains" if numParts is smaller than the
/// number of bodies or larger than a body's element count allows, and naming the block and
/// its islands if a body is several face-connected pieces (MeshFaces.hpp).
std::vector<int> metisPartition(const Mesh& mesh, int numParts);

/// Contiguous block distribution of subdomains over ranks: the subdomains of `rank`
/// are [firstSubdomain(rank), firstSubdomain(rank + 1)).
int firstSubdomain(int rank, int numSubdomains, int numRanks);
/// Rank that owns subdomain `s`.
int ownerRank(int s, int numSubdomains, int numRanks);

}  // namespace tribos::mesh
