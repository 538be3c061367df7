#pragma once
/// \file SceneSize.hpp
/// Sizes that cannot work, refused before any allocation: a generated mesh whose elements,
/// nodes and subdomain matrices cannot fit in the machines' memory (or in 32-bit local
/// indices) is an input error with the numbers, not a std::bad_alloc after minutes.
#include <mpi.h>

#include <string>

#include "tribos/core/Types.hpp"

namespace Teuchos {
class ParameterList;
}

namespace tribos::stack {

/// Lower bounds of what a Two Bricks scene allocates (zero for meshes read from a file,
/// whose size the file bounds).
struct SceneSize {
  double tetrahedra = 0.0, nodes = 0.0;  ///< of the global mesh, which every rank holds
  double primalUnknowns = 0.0;           ///< 3 per node at least (subdomain copies add more)
  double factorNonzeros = 0.0;           ///< of all subdomain factors (a solve, not a dry run)
  /// Bytes on one machine running `ranksHere` of `ranks` ranks: each rank its own copy of
  /// the mesh and its share of the subdomain matrices (and of their factors when `solving`).
  double bytesPerMachine(int ranksHere, int ranks, bool solving) const;
};

/// The estimate for a validated "Tribos" list.
SceneSize estimateSceneSize(const Teuchos::ParameterList& tribos);

/// Throws core::InputError (naming `source`, Mesh/H Over h and Mesh/Subdomains Per Brick and
/// the numbers) when the scene needs more memory than the machine with the least memory has
/// (physical memory or its cgroup's limit), more than one rank may still map (its address-space
/// limit, `ulimit -v`), or more elements or nodes than 32-bit local indices count. `solving`
/// false (a dry run): the factors are not counted. Collective over `comm`: every rank reaches
/// the same verdict.
void requireSceneFitsInMemory(const Teuchos::ParameterList& tribos, const std::string& source, MPI_Comm comm,
                              bool solving = true);

/// Bytes rank 0 keeps per load step until the end of a history: the step's record and summary
/// entry (its nodal fields are written into the result file as the step converges and released:
/// drivers/HistoryResults.hpp). Measured: 15.4 KB per step on the bricks (one interface), 1 000
/// against 200 steps of input/two_bricks.xml, the peak resident memory of rank 0.
inline constexpr double kHeldBytesPerStep = 16e3;

/// Throws core::InputError (naming Load Steps/Number Of Steps and the numbers) when what rank 0
/// keeps of a load history's steps would take more than half the memory it has (physical memory,
/// its cgroup's limit, its address-space limit): issue 44, 100 000 steps under a 2 GB limit ran
/// out of memory after 45 s. Collective over `comm`.
void requireHistoryFitsInMemory(int loadSteps, MPI_Comm comm);

}  // namespace tribos::stack
