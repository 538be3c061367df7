#pragma once
/// \file DistributedCoarseSolve.hpp
/// The coarse problem's triangular solves spread over the ranks (issue 11,
/// doc/measurements/coarse_problem.md, "The coarse solve over the ranks").
///
/// G G^T is factorised on rank 0. Its elimination tree (nested dissection, postorder) is cut
/// into a tree of tasks: the whole factor is split over all ranks into independent subtrees
/// and a top (the separators above them); a subtree given several ranks is split again over
/// them, one given one rank is a leaf. Each rank receives, once per factorisation, the values
/// of its leaves and of the tops of the splits it leads (the first rank of their group).
/// A solve runs
///   - forward: every rank its leaves, keeping their updates of rows above them; then, from
///     the deepest split up, the leader of each split gathers its parts' updates
///     (MPI_Gatherv over the split's ranks), subtracts those of rows inside it in the serial
///     order, solves its top and keeps the updates of rows above it for the next split up;
///   - backward: from the whole factor down, each leader solves its top and broadcasts it
///     over its split's ranks (MPI_Bcast); every rank then solves its leaves;
///   - MPI_Allgatherv of every rank's solved columns: every rank has the whole solution.
/// Every entry sees the operations of the serial solve in its order: the bits of the
/// serial solve, on any number of ranks and threads.
///
/// Replicating the solve on every rank streamed R copies of the factor at once (16 ranks at
/// 4 000 subdomains: 43 ms a solve, doc/measurements/scalability.md); solving on rank 0 alone left the
/// other ranks idle and read the whole factor with one core.
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
  /// ("Tacho"), fewer than `fromValues` stored values, or no split whose estimated critical
  /// path reads at most three quarters of what the serial solve reads.
  static std::unique_ptr<DistributedCoarseSolve> create(MPI_Comm comm, const SparseCholesky* whole,
                                                        long long fromValues);
  ~DistributedCoarseSolve();
  DistributedCoarseSolve(const DistributedCoarseSolve&) = delete;
  DistributedCoarseSolve& operator=(const DistributedCoarseSolve&) = delete;

  /// Collective: x = A^{-1} b on every rank, b the same on every rank (x may be b).
  void solve(const double* b, double* x) const;
  /// Leaves of the task tree (subtrees solved by one rank each), over all ranks.
  int numLeaves() const;
  /// Splits of the task tree on the longest chain from the whole factor to a leaf.
  int depth() const;
  /// Stored values of the factor this rank reads in a solve (its leaves and the tops it leads).
  long long valuesOnThisRank() const { return valuesOnThisRank_; }

  /// A task: supernodes [first, last) of the whole factor (a subtree, or the whole factor),
  /// solved by ranks [rankBegin, rankEnd): split over them (parts and a top) or, as a leaf,
  /// by rankBegin alone. As broadcast from rank 0.
  struct Task {
    LO first = 0, last = 0, columnBegin = 0, columnEnd = 0;
    int rankBegin = 0, rankEnd = 0, parent = -1;
    bool split = false;
    long long updates = 0;  ///< its forward updates of rows >= columnEnd (rows above it)
  };

 private:
  /// A split this rank takes part in, and what it needs of it.
  struct Split {
    int task = 0;
    MPI_Comm comm = MPI_COMM_NULL;
    bool leader = false;
    std::vector<int> parts;            ///< its part tasks, in supernode order
    /// Its segments in supernode order: a part (index into parts) or a top run of supernodes.
    struct Segment {
      int part;  ///< -1: a top run
      LO first, last;
      long long updates;  ///< top run: its updates of rows above the split
    };
    std::vector<Segment> segments;
    std::vector<int> counts, displs;   ///< gather: update entries per rank of comm
    std::vector<size_t> partOffset;    ///< leader: where each part's updates start in gathered
    std::vector<std::vector<LO>> partRows;  ///< leader: the rows of each part's updates
    std::vector<std::pair<LO, LO>> topColumns;
    long long topCount = 0;
    mutable std::vector<double> gathered, send, top;
  };
  DistributedCoarseSolve() = default;
  void buildSplits();
  void receiveParts(const PackedFactor* whole);
  void planBuffers();
  // The steps of solve() on the permuted vector v: the forward substitution of this rank's
  // leaves, then of the splits it is in (deepest first), the backward substitution (splits
  // from the whole factor down, then the leaves), and the solved columns to every rank.
  void forwardLeaves(double* v) const;
  void forwardSplits(double* v) const;
  void backward(double* v) const;
  void shareColumns(double* v) const;
  /// The supernode index in factor_ of supernode k of the whole factor.
  LO local(LO k) const;
  /// The update entries a task hands to its parent's leader: a leaf's or a split's.
  std::vector<double>& outputOf(int task) const { return output_[static_cast<size_t>(task)]; }

  MPI_Comm comm_ = MPI_COMM_NULL;
  int rank_ = 0, size_ = 1;
  LO n_ = 0;
  std::vector<Task> tasks_;
  std::vector<int> leaves_;                 ///< this rank's leaf tasks, ascending
  std::vector<Split> splits_;               ///< the splits this rank is in, whole factor first
  const PackedFactor* whole_ = nullptr;     ///< rank 0: the factor (owned by the SparseCholesky)
  std::unique_ptr<PackedFactor> part_;      ///< ranks > 0: its supernodes
  const PackedFactor* factor_ = nullptr;    ///< what this rank reads: whole_ or part_
  std::vector<std::pair<LO, LO>> partRanges_;  ///< ranks > 0: whole-factor ranges held, ascending
  std::vector<LO> partStart_;                  ///< their first index in part_
  /// The final all-gather: columns per rank (ranges in each rank's order) and counts.
  std::vector<std::vector<std::pair<LO, LO>>> ownedColumns_;
  std::vector<int> columnCounts_, columnDispls_;
  long long valuesOnThisRank_ = 0;
  mutable std::vector<std::vector<double>> output_;  ///< per task (this rank's leaves and led splits)
  mutable std::vector<double> v_, work_, columns_, allColumns_;
};

}  // namespace tribos::feti
