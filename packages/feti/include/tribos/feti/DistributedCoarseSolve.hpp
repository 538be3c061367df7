#pragma once
/// \file DistributedCoarseSolve.hpp
/// The coarse problem's triangular solves spread over the ranks (issue 11,
/// doc/coarse_problem.md, "The coarse solve over the ranks").
///
/// G G^T is factorised on rank 0. Its elimination tree (nested dissection, postorder) splits
/// into independent subtrees and a top (the separators above them). Each rank receives the
/// values of the subtrees it is given, once; a solve then runs
///   - forward: every rank its subtrees, keeping their updates of top rows;
///   - MPI_Gatherv of those updates to rank 0, which subtracts them in the serial order and
///     solves the top (forward and backward);
///   - MPI_Bcast of the top's solution; every rank its subtrees backward;
///   - MPI_Allgatherv of the subtrees' solutions: every rank has the whole solution.
/// Every entry sees the operations of the serial solve in its order: the bits of the
/// serial solve, on any number of ranks and threads (a rank runs its subtrees on its threads).
///
/// Replicating the solve on every rank streamed R copies of the factor at once (16 ranks at
/// 4 000 subdomains: 43 ms a solve, doc/scalability.md); solving on rank 0 alone left the
/// other ranks idle. Here each rank reads its share once, and rank 0 holds the top.
#include <mpi.h>

#include <memory>
#include <utility>
#include <vector>

#include "tribos/core/Types.hpp"

namespace tribos::feti {

class SparseCholesky;
class PackedFactor;

class DistributedCoarseSolve {
 public:
  /// Collective. `whole`: the factor, on rank 0 (ignored on the other ranks). Returns null on
  /// every rank when the split would not pay: one rank, a factor without a packed form
  /// ("Tacho"), fewer than `fromValues` stored values, or no split that takes at least a
  /// quarter of the serial solve's reads off the busiest rank.
  static std::unique_ptr<DistributedCoarseSolve> create(MPI_Comm comm, const SparseCholesky* whole,
                                                        long long fromValues);
  ~DistributedCoarseSolve();

  /// Collective: x = A^{-1} b on every rank, b the same on every rank (x may be b).
  void solve(const double* b, double* x) const;
  /// Subtrees of the split (over all ranks).
  int numSubtrees() const { return static_cast<int>(subtrees_.size()); }
  /// Stored values of the factor this rank reads in a solve (its subtrees; rank 0 the top too).
  long long valuesOnThisRank() const { return valuesOnThisRank_; }

 private:
  struct Subtree {
    LO first = 0, last = 0;            ///< supernodes [first, last) of the whole factor
    LO columnBegin = 0, columnEnd = 0;  ///< its columns
    long long updates = 0;             ///< its updates of top rows in a forward solve
    int owner = 0;                     ///< the rank that solves it
  };
  /// A subtree of this rank: supernodes [first, last) of the factor it reads (rank 0: the
  /// whole; else its part), offsets into the work arrays.
  struct Mine {
    int subtree = 0;
    LO first = 0, last = 0;
    size_t panelWork = 0, updateOffset = 0;
  };
  DistributedCoarseSolve() = default;
  void distributeParts(const PackedFactor* whole);
  void planBuffers();

  MPI_Comm comm_ = MPI_COMM_NULL;
  int rank_ = 0, size_ = 1;
  LO n_ = 0;
  std::vector<Subtree> subtrees_;
  const PackedFactor* whole_ = nullptr;  ///< rank 0: the factor (owned by the SparseCholesky)
  std::unique_ptr<PackedFactor> part_;   ///< ranks > 0: the supernodes of their subtrees
  const PackedFactor* factor_ = nullptr;  ///< what this rank reads: whole_ or part_
  std::vector<Mine> mine_;
  std::vector<std::pair<LO, LO>> topColumns_;  ///< column ranges outside every subtree
  long long topCount_ = 0, valuesOnThisRank_ = 0;
  /// Gatherv of the top updates and allgatherv of the subtrees' columns: counts and
  /// displacements per rank; where each subtree's updates start in the gathered array.
  std::vector<int> updateCounts_, updateDispls_, columnCounts_, columnDispls_;
  std::vector<size_t> gatheredOffset_;
  std::vector<size_t> gatheredColumns_;  ///< where each subtree's columns start in allColumns_
  /// Rank 0: subtrees (index) and top runs (-1) with their supernodes, in supernode order.
  std::vector<std::pair<int, std::pair<LO, LO>>> segments_;
  mutable std::vector<double> v_, work_, updates_, gathered_, top_, columns_, allColumns_;
  size_t topPanelWork_ = 0;
};

}  // namespace tribos::feti
