#pragma once
// Internal to feti/: the coarse problem of T-FETI, G G^T (ALGORITHMS.md 3; doc/design.md,
// "T-FETI operators"): its block pattern, its assembly on rank 0 from every rank's owned rows
// of G (whole, or over a mask's rows: G_I G_I^T), its factor (double, or rounded to single
// behind a gate: TotalFetiSettings::coarsePrecision), and its solves, on rank 0 and broadcast
// or over the ranks (DistributedCoarseSolve). TotalFeti owns one and projects with it.
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "tribos/core/ReproducibleSum.hpp"
#include "tribos/feti/TotalFeti.hpp"

namespace tribos::feti {

struct CoarseRows;  // CoarseSpace.hpp

class CoarseProblem {
 public:
  /// y = G G^T x (replicated vectors of length l): the products of iterative refinement.
  using Product = std::function<void(const std::vector<double>& x, std::vector<double>& y)>;

  /// G: the owned rows of G (CoarseRows); gMax = max |g_{s,r,j}| over all ranks
  /// (the scale of the reproducible sums); subdomainBytesPerF: the bytes of the subdomain
  /// solves of one F application (what "Auto" precision compares the coarse solves with).
  /// Builds the block pattern (collective); factorize() assembles and factorises.
  CoarseProblem(const CoarseRows& G, int numSubdomains, GO numRowsOfB, double gMax,
                double subdomainBytesPerF, Teuchos::RCP<const Teuchos::Comm<int>> comm,
                const TotalFetiSettings& settings, OperatorProfile& profile, std::vector<char> pinnedModes = {});
  ~CoarseProblem();

  /// Assembles G G^T (collective) and factorises it on rank 0, rounded to single where the
  /// settings ask and the gate passes.
  void factorize();
  /// a := (G G^T)^{-1} a with the factor as it is (single or double); factorises again after
  /// release(). Collective.
  void solve(std::vector<double>& a);
  /// a := (G G^T)^{-1} a to double precision: with a single factor, solve() refined by
  /// iterative refinement with `product`. Collective.
  void solveExactly(std::vector<double>& a, const Product& product);
  /// Frees the factor (a later solve factorises G G^T again: the same bits).
  void release();
  /// Whether solves use a single-precision factor (factorises first if released).
  bool single() {
    if (!factored_) factorize();
    return single_;
  }
  /// G_I G_I^T over the owned rows with mask != 0, summed over the ranks (no mask: G G^T), on
  /// the pattern of G G^T, on rank 0 (the other ranks get an empty matrix). Collective.
  fem::CsrMatrix assemble(const std::vector<char>* ownedRowMask,
                          const std::vector<TotalFeti::RowCombination>* combinations = nullptr) const;
  /// Whether the two owned rows touch the same subdomains (a combination may then be assembled).
  bool sameSubdomains(LO a, LO b) const;

 private:
  /// The block pattern of G G^T from the owned rows of G and one all-gather of their
  /// subdomain pairs (no rank reads the blocks of B of subdomains it does not own).
  void buildPattern();
  /// The index of block (s, t) in the pattern.
  LO blockOf(int s, int t) const;
  /// The upper blocks (s <= t) that the counted owned rows touch, ascending; slotOf: block ->
  /// its index among them (-1: untouched).
  std::vector<LO> touchedBlocks(const std::vector<char>* ownedRowMask, std::vector<LO>& slotOf) const;
  /// The exact slot sums (core::SumBins) of the counted owned rows' products in those blocks,
  /// and of the combinations'.
  std::vector<double> sumOwnedRows(const std::vector<char>* ownedRowMask,
                                   const std::vector<TotalFeti::RowCombination>* combinations,
                                   const std::vector<LO>& slotOf, size_t numTouched) const;
  /// Deposits g g^T of one row's (or combination's) g_{s}, 6 per entry of `subdomains`.
  void depositOuterProduct(const std::vector<double>& g, const int* subdomains, LO entries, const core::SumBins& bins,
                           const std::vector<LO>& slotOf, std::vector<double>& local) const;
  /// Rank 0: the diagonal of the pinned rows (pinned_) set.
  void pinRows(fem::CsrMatrix& GGt) const;
  /// Rank 0: G G^T (or G_I G_I^T) in CSR from the whole pattern's slots.
  fem::CsrMatrix matrixFromSlots(const std::vector<double>& slots) const;
  /// Rank 0: sum = the whole pattern's slots, every rank's `values` (their `blocks`, kSlots x 36
  /// each) added in; rank 0's own values are released. Collective.
  void addBlocksOnRoot(const std::vector<LO>& blocks, std::vector<double>& values, std::vector<double>& sum) const;
  /// Rank 0, factorised: whether coarsePrecision asks for the single factor, given two coarse
  /// solves' bytes over those of F's subdomain solves.
  bool singlePays(double coarseToFBytes) const;
  /// Rank 0: rounds factor_ to single precision where its implementation can; returns
  /// whether it did and the relative difference of one solve (a fixed right-hand side)
  /// before and after.
  std::pair<bool, double> roundToSingle();

  const CoarseRows& G_;
  int numSubdomains_;
  /// Per coarse row, 1 where G's row is 0 (a rigid mode that eliminated components removed):
  /// its diagonal is set to the largest other one, so that G G^T stays regular and the row's
  /// coordinate stays 0 (TotalFeti::pinnedModes). Empty: none.
  std::vector<char> pinned_;
  GO numRowsOfB_;
  double gMax_, subdomainBytesPerF_;
  Teuchos::RCP<const Teuchos::Comm<int>> comm_;
  const TotalFetiSettings& settings_;
  OperatorProfile& profile_;
  /// Block row s has the blocks k in [blockStart_[s], blockStart_[s + 1]), block column
  /// neighbours_[k] (ascending within a row).
  std::vector<LO> blockStart_;
  std::vector<int> neighbours_;
  /// The factor, on rank 0 only; null after release() until the next solve.
  std::unique_ptr<SparseCholesky> factor_;
  /// The solves spread over the ranks (several ranks and a factor large enough to pay,
  /// DistributedCoarseSolve.hpp); null: solved on rank 0 and broadcast. Reset before factor_.
  std::unique_ptr<DistributedCoarseSolve> distributed_;
  /// Whether G G^T is factorised (on rank 0): the same on every rank.
  bool factored_ = false;
  /// Whether the factor is in single precision (the same on every rank), and whether the
  /// single one was found too inaccurate for this G G^T (then it stays double).
  bool single_ = false, singleRejected_ = false;
  std::vector<double> rhs_;  ///< solve()'s copy of its right-hand side
};

/// Runs `work` on rank 0 alone, then broadcasts v (of the same length on every rank) from it;
/// if `work` throws there, every rank calls fail(rank 0's message), which throws. One rank:
/// work() alone. Collective.
void onRootThenBroadcast(const Teuchos::Comm<int>& comm, std::vector<double>& v, const std::function<void()>& work,
                         const std::function<void(const std::string&)>& fail);

}  // namespace tribos::feti
