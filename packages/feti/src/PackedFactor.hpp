#pragma once
// Internal: a sparse Cholesky factor L (A = P^T L L^T P) stored for the triangular solves
// only, in as few bytes as a solve must read (doc/measurements/performance.md):
//  - columns grouped into supernodes (consecutive columns whose sub-diagonal row sets nest,
//    so they share one list of row indices);
//  - per supernode, the diagonal triangle packed by columns (reciprocal diagonal apart) and
//    the rows below it as a dense column-major panel, its row indices gathered once per
//    supernode into a contiguous work vector: the forward solve is one axpy per panel
//    column, the backward solve one dot product per panel column, each as long as the
//    panel (where a row-by-row loop would run over the few columns of a small supernode);
//  - 8 bytes per entry plus 4 per panel row (shared by the supernode's columns), instead of
//    CHOLMOD's 12 per entry (simplicial) or its padded square panels (supernodal).
// The solves are plain loops: no BLAS (so concurrent solves on threads are safe and give
// the same bits as a solve alone), no allocation (the caller passes the work vector), and a
// fixed order of every sum (the same bits on every thread, for any number of threads).
//
// A factor solved alone (G G^T, on rank 0) may also split its elimination tree
// into independent subtrees (planSubtrees, PackedFactorSubtrees.cpp) whose substitutions run
// on the threads of core::forEachSubdomain: bandwidth-bound, one thread reads about half of
// what two can (doc/measurements/coarse_problem.md).
#include <algorithm>
#include <memory>
#include <utility>
#include <vector>

#include "tribos/core/Types.hpp"

namespace tribos::feti {

class PackedFactor {
 public:
  /// One supernode as a builder hands it over: columns [firstColumn, firstColumn + numColumns)
  /// of L, `rows` the row indices below the diagonal block (ascending), `value(i, j)` the
  /// entry of L in column firstColumn + j and row (i < numColumns ? firstColumn + i :
  /// rows[i - numColumns]) for i >= j.
  template <class Value>
  void appendSupernode(LO firstColumn, LO numColumns, const std::vector<LO>& rows, Value&& value);
  /// Sizes the storage before the supernodes are appended: `strictLowerValues` entries of L
  /// below the diagonal, `rowIndices` panel rows and `numSupernodes` supernodes in all. A
  /// builder that knows them (CHOLMOD's factor does) avoids the vectors' doubling growth,
  /// which held up to three times the factor's values while one was copied and left up to
  /// twice in the stored factor (doc/measurements/scalability.md, G G^T when it was replicated).
  void reserve(long long strictLowerValues, long long rowIndices, LO numSupernodes, LO numColumns);
  /// For a builder that packs the values in place, in an array of its own: a supernode whose
  /// values it has already laid out (triangle and panel as above, at these offsets into that
  /// array) and the reciprocals of its diagonal; then adoptValues() hands the array over.
  void appendLaidOutSupernode(LO firstColumn, LO numColumns, const std::vector<LO>& rows, long long triangleOffset,
                              long long panelOffset, const double* inverseDiagonal);
  /// Takes `values` (count entries) as the stored values, freed by `release`: no copy of the
  /// factor (CholmodCholesky: CHOLMOD's own array, compacted in place). `resize` (optional,
  /// realloc's contract) lets roundToSingle shrink that array in place instead of copying.
  void adoptValues(double* values, long long count, void (*release)(void*),
                   void* (*resize)(void*, size_t) = nullptr);
  /// Rounds the stored values of L to single precision (4 bytes each instead of 8) and frees
  /// the double ones; the reciprocal diagonal stays double. The solves then apply
  /// (L~ L~^T)^{-1} with L~ = fl32(L), an SPD matrix of its own, exactly as before (double
  /// arithmetic, the same order of every sum: the same bits on every thread and rank). For
  /// G G^T in SMALSE-M's projections, where any SPD approximation leaves the solution exact
  /// (doc/measurements/coarse_problem.md, "The coarse factor in single precision").
  void roundToSingle();
  bool single() const { return single_; }
  /// Sets the fill-reducing permutation: row k of the factor is row perm[k] of A.
  void setPermutation(std::vector<LO> perm) { perm_ = std::move(perm); }

  LO size() const { return static_cast<LO>(perm_.size()); }
  /// Entries of the work vector of solve().
  LO workSize() const { return size() + maxPanelRows_; }
  /// x = A^{-1} b for one vector (b and x may alias); work has workSize() entries.
  void solve(const double* b, double* x, double* work) const;
  /// In the factor's own (permuted) numbering: v := L^{-T} L^{-1} v; work has
  /// workSize() - size() entries.
  void solvePermuted(double* v, double* work) const;
  const std::vector<LO>& permutation() const { return perm_; }
  /// Supernode ranges [first, last), ascending.
  using Ranges = std::vector<std::pair<LO, LO>>;
  /// The supernodes a solve must visit when the right-hand side vanishes outside `columns`
  /// (in the factor's numbering) and the solution is read at `columns` only: those holding
  /// one of them and their ancestors in the elimination tree. The forward substitution of any
  /// other supernode divides and subtracts zeros only (its subtree has no nonzero right-hand
  /// side), and no visited supernode reads its values in the backward one (it is nobody's
  /// ancestor among them). F = B_s K^+ B_s^T at H/h 5 leaves out ~10 % of the factor, ~20 % at
  /// H/h 10.
  Ranges reach(const std::vector<LO>& columns) const;
  /// solvePermuted with the backward substitution over the supernodes of `reach` only (the
  /// forward one whole: why in the .cpp): at `columns`, the bits of solvePermuted for such a
  /// right-hand side; elsewhere v holds the forward substitution's values.
  void solvePermutedOnReach(double* v, double* work, const Ranges& reach) const;

  /// Stored values of L (diagonal included): what each triangular solve reads once.
  long long storedValues() const { return valueCount() + static_cast<long long>(inverseDiagonal_.size()); }
  /// Bytes that one solve with one right-hand side reads from the factor: values, row
  /// indices and supernode descriptors, twice (forward and backward substitution).
  long long solveBytes() const;
  /// The same for solvePermutedOnReach.
  long long solveBytes(const Ranges& reach) const;
  /// Bytes one substitution (forward or backward) reads over supernodes [first, last).
  long long substitutionBytes(LO first, LO last) const;
  LO numSupernodes() const { return static_cast<LO>(supernodes_.size()); }

  /// Splits the elimination tree into independent subtrees for solve() and solvePermuted()
  /// when the factor has at least `fromValues` stored values (and the supernodes are in
  /// postorder, as CHOLMOD's are): the subtrees' substitutions then run on the threads of
  /// core::forEachSubdomain, the rest (the top separators) on the calling thread. Every
  /// entry of x sees the operations of the serial solve in the same order, so the bits are
  /// those of the serial solve for any number of threads. Returns whether it split.
  /// Such a factor must not be solved from inside forEachSubdomain.
  bool planSubtrees(long long fromValues);
  /// Number of subtrees of the split (0: solved serially).
  int numSubtrees() const;
  /// Share of the stored values in the serial top part of the split (0 without a split).
  double topShare() const;

  /// The supernodes as an elimination tree (they are in postorder, as CHOLMOD's are): the
  /// parent of each (-1: a root), the first supernode of its subtree ([firstDescendant[k], k]
  /// is the subtree), its stored values and its subtree's, its children; the roots. Empty when
  /// the supernodes are not a postordered elimination tree.
  struct SupernodeTree {
    std::vector<LO> parent, firstDescendant, roots;
    std::vector<long long> values, subtreeValues;
    std::vector<std::vector<LO>> children;
    bool empty() const { return parent.empty(); }
  };
  SupernodeTree supernodeTree() const;
  /// The greedy splits of the subtrees rooted at `start` into independent subtrees: each step
  /// replaces the largest subtree that has children by its children (its root joins the
  /// top). The roots of each state (ascending), the start first, then one per step while
  /// fewer than maxCount subtrees and at most maxSteps steps.
  static std::vector<std::vector<LO>> greedyStates(const SupernodeTree& tree, std::vector<LO> start, int maxCount,
                                                   int maxSteps);
  /// The states of greedyStates from the tree's roots as supernode ranges; planSubtrees takes
  /// the first with at least four subtrees. Empty when the supernodes are not a tree.
  struct TreeSplit {
    std::vector<LO> first, last;      ///< supernode range [first, last) of each subtree, ascending
    std::vector<long long> values;    ///< stored values of each subtree
    long long totalValues = 0;        ///< of the whole factor
  };
  std::vector<TreeSplit> greedySplits(int maxCount) const;
  /// One past the last column of the subtree that ends at supernode last - 1.
  LO columnEndOf(LO last) const { return supernodes_[last - 1].firstColumn + supernodes_[last - 1].numColumns; }
  /// First column of supernode k.
  LO firstColumnOf(LO k) const { return supernodes_[k].firstColumn; }
  /// Entries of forward()'s topUpdates for supernodes [first, last) with that columnEnd.
  long long topUpdateCount(LO first, LO last, LO columnEnd) const;
  /// The rows those entries update, in their order.
  std::vector<LO> topUpdateRows(LO first, LO last, LO columnEnd) const;

  /// The supernodes of `ranges` (each [first, last), ascending) as bytes for a rank that
  /// solves only those subtrees (DistributedCoarseSolve), written straight from this factor
  /// (rank 0 sends one part per rank while it holds the whole factor); deserialize reads them
  /// as a factor of their own: their values and row indices (still in the whole factor's
  /// column numbering), the whole permutation and reciprocal diagonal (n entries each: small
  /// against the values); supernode k of the ranges becomes supernode (its position among them).
  std::vector<char> serialize(const std::vector<std::pair<LO, LO>>& ranges) const;
  static PackedFactor deserialize(const std::vector<char>& bytes);

  PackedFactor();
  ~PackedFactor();
  PackedFactor(PackedFactor&&) noexcept;
  PackedFactor& operator=(PackedFactor&&) noexcept;

 private:
  struct Supernode {
    LO firstColumn, numColumns, numPanelRows;
    LO rowOffset;    ///< into rows_
    long long triangleOffset;  ///< into values_: packed strict lower triangle, by columns
    long long panelOffset;     ///< into values_: numPanelRows x numColumns, column-major
  };
  /// Forward substitution over supernodes [first, last). Panel rows below `columnEnd` are
  /// updated in x; for those at or above it (the top rows of a subtree) the update t_r is
  /// stored in topUpdates instead, in order, for applyTopUpdates.
  void forward(LO first, LO last, double* x, double* panelWork, LO columnEnd, double* topUpdates) const;
  /// x_row -= the stored updates of forward(first, last, ..., columnEnd, topUpdates).
  void applyTopUpdates(LO first, LO last, double* x, LO columnEnd, const double* topUpdates) const;
  /// Backward substitution over supernodes [first, last), from the last.
  void backward(LO first, LO last, double* x, double* panelWork) const;
  friend class DistributedCoarseSolve;  ///< runs forward, applyTopUpdates and backward by ranges
  struct Subtrees;  ///< the split of planSubtrees (PackedFactorSubtrees.cpp)
  void solveSubtrees(double* v) const;

  const double* valueData() const { return adopted_ ? adopted_.get() : values_.data(); }
  long long valueCount() const {
    if (single_) return singleCount_;
    return adopted_ ? adoptedCount_ : static_cast<long long>(values_.size());
  }
  /// Bytes of one stored value of L (the reciprocal diagonal is always double).
  long long valueBytes() const { return single_ ? 4 : 8; }
  template <class V>
  void forwardWith(const V* values, LO first, LO last, double* x, double* panelWork, LO columnEnd,
                   double* topUpdates) const;
  template <class V>
  void backwardWith(const V* values, LO first, LO last, double* x, double* panelWork) const;

  std::vector<Supernode> supernodes_;
  std::vector<LO> rows_;
  std::vector<double> values_;  ///< appendSupernode's; empty once values are adopted
  std::unique_ptr<double, void (*)(void*)> adopted_{nullptr, nullptr};  ///< adoptValues'
  long long adoptedCount_ = 0;
  void* (*resize_)(void*, size_t) = nullptr;  ///< adoptValues': realloc for adopted_
  /// roundToSingle's values: in singleValues_, or in place in the adopted array (resized to
  /// them, then held by singleAdopted_); singleData_ points at them.
  std::vector<float> singleValues_;
  std::unique_ptr<float, void (*)(void*)> singleAdopted_{nullptr, nullptr};
  const float* singleData_ = nullptr;
  long long singleCount_ = 0;
  bool single_ = false;
  std::vector<double> inverseDiagonal_;  ///< 1 / L_jj, by column
  std::vector<LO> perm_;
  LO maxPanelRows_ = 0;
  std::unique_ptr<Subtrees> subtrees_;
};

inline void PackedFactor::appendLaidOutSupernode(LO firstColumn, LO numColumns, const std::vector<LO>& rows,
                                                  long long triangleOffset, long long panelOffset,
                                                  const double* inverseDiagonal) {
  supernodes_.push_back({firstColumn, numColumns, static_cast<LO>(rows.size()), static_cast<LO>(rows_.size()),
                         triangleOffset, panelOffset});
  rows_.insert(rows_.end(), rows.begin(), rows.end());
  inverseDiagonal_.insert(inverseDiagonal_.end(), inverseDiagonal, inverseDiagonal + numColumns);
  maxPanelRows_ = std::max(maxPanelRows_, static_cast<LO>(rows.size()));
}

inline void PackedFactor::adoptValues(double* values, long long count, void (*release)(void*),
                                      void* (*resize)(void*, size_t)) {
  adopted_ = std::unique_ptr<double, void (*)(void*)>(values, release);
  adoptedCount_ = count;
  resize_ = resize;
  std::vector<double>().swap(values_);
}

inline void PackedFactor::reserve(long long strictLowerValues, long long rowIndices, LO numSupernodes, LO numColumns) {
  values_.reserve(static_cast<size_t>(strictLowerValues));
  rows_.reserve(static_cast<size_t>(rowIndices));
  supernodes_.reserve(static_cast<size_t>(numSupernodes));
  inverseDiagonal_.reserve(static_cast<size_t>(numColumns));
}

template <class Value>
void PackedFactor::appendSupernode(LO firstColumn, LO numColumns, const std::vector<LO>& rows, Value&& value) {
  Supernode s{firstColumn, numColumns, static_cast<LO>(rows.size()), static_cast<LO>(rows_.size()), 0, 0};
  rows_.insert(rows_.end(), rows.begin(), rows.end());
  s.triangleOffset = static_cast<long long>(values_.size());
  for (LO j = 0; j < numColumns; ++j) {
    inverseDiagonal_.push_back(1.0 / value(j, j));
    for (LO i = j + 1; i < numColumns; ++i) values_.push_back(value(i, j));
  }
  s.panelOffset = static_cast<long long>(values_.size());
  for (LO j = 0; j < numColumns; ++j)
    for (LO r = 0; r < s.numPanelRows; ++r) values_.push_back(value(numColumns + r, j));
  maxPanelRows_ = std::max(maxPanelRows_, s.numPanelRows);
  supernodes_.push_back(s);
}

}  // namespace tribos::feti
