#pragma once
/// \file SameMeshOnEveryRank.hpp
/// Every rank reads the mesh file itself. A file replaced while a job starts (a preprocessor
/// writing it anew) can give ranks different meshes, and then the job would compute nonsense
/// or wait forever in a collective whose sizes disagree. So before any other work the ranks
/// compare what they read: counts and a checksum of every value the file gave.
#include <mpi.h>

#include <cstdint>
#include <string>

#include "tribos/mesh/Mesh.hpp"

namespace tribos::stack {

/// FNV-1a (64 bits) over the coordinates, connectivity, blocks, node and side sets and element
/// numbers: equal meshes give equal sums on every machine (same bytes; IEEE doubles).
std::uint64_t meshChecksum(const mesh::Mesh& mesh);

/// Collective over `comm`: throws core::InputError on every rank, naming `file` and what each
/// rank read, unless every rank's `mesh` has the same checksum.
void requireSameMeshOnEveryRank(const mesh::Mesh& mesh, const std::string& file, MPI_Comm comm);

/// The Exodus mesh `file`, read by every rank of `comm` or none (a rank that cannot read it
/// stops them all, core::onEveryRankOrNone), then compared (requireSameMeshOnEveryRank).
/// Collective.
mesh::Mesh readMeshOnEveryRank(const std::string& file, MPI_Comm comm);

}  // namespace tribos::stack
