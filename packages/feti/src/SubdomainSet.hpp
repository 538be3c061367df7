#pragma once
// Internal to feti/: the first component of T-FETI (BlockKernels.hpp lists them): this rank's
// owned subdomains (their systems, generalised inverses, rows of B, work buffers) and the
// dual layout they share: the owned rows of B (dualMap), the rows their blocks touch
// (overlap), and applyBlockwise, which sums the subdomains' contributions into each row in
// ascending subdomain order on any rank and thread layout. Every operator on the dual space
// (F, the preconditioners, B u, d~) is one per-subdomain step given to applyBlockwise.
#include <functional>
#include <memory>
#include <vector>

#include "BlockKernels.hpp"
#include "EliminatedComponents.hpp"

namespace tribos::feti {

/// One owned subdomain: its system, generalised inverse, rows of B and scratch buffers
/// (allocated before any threaded loop: TOOLCHAIN.md rule 1).
struct OwnedSubdomain {
  int subdomain = 0;
  const SubdomainBlock* block = nullptr;
  std::vector<LO> overlapIndex;  ///< local index in the overlap map of each block row
  std::vector<BlockTerm> factorTerms;  ///< B_s with the dofs in the factor's order (blockTerms)
  std::vector<LO> rowOrder;      ///< the block's rows by ascending global id (B.rowId)
  fem::SubdomainSystem system;
  SubdomainSolver solver;
  std::vector<double> denseF;    ///< explicit F_s when requested (packLowerInRowOrder)
  EliminatedRows eliminated;     ///< the components eliminated from K_s (block->eliminated)
  int liveModes = 6;             ///< R's columns that are rigid modes (the rest are 0: eliminated)
  std::vector<double> in, out, x, y;
  LO m() const { return static_cast<LO>(block->rows.size()); }
  LO n() const { return system.K.n; }
};

class SubdomainSet {
 public:
  /// (1) The dual and overlap maps of this rank's subdomains (`numOwned` of them: checked
  /// against the decomposition's split over the ranks, and B against the communicator).
  SubdomainSet(const ConstraintMatrix& B, const Teuchos::RCP<const Teuchos::Comm<int>>& comm, int numSubdomains,
               int numOwned);

  /// (2) Rigid body modes and (3) the structures of the owned subdomains (their systems,
  /// consumed; components eliminated from K_s; overlap indices; row orders; buffers).
  void setUp(const mesh::Mesh& mesh, const mesh::Decomposition& decomposition, std::vector<fem::SubdomainSystem> owned);
  /// (3) K_reg of every owned subdomain factorised on threads and B_s in the factor's order;
  /// `alsoEach(L, i)` then runs on subdomain i in the same threaded loop (preconditioner
  /// blocks, explicit F_s). Stops between subdomains once settings.deadline has passed (every
  /// rank agrees). Returns the slowest rank's seconds.
  double factorize(const mesh::Mesh& mesh, const mesh::Decomposition& decomposition, const TotalFetiSettings& settings,
                   const std::function<void(OwnedSubdomain&, int)>& alsoEach);
  /// Several ranks: each entry (row, owned subdomain) travels to the row's owner by `import`
  /// (source: the owned subdomains' rows, from `firstSource[i]`; target: the owned rows'
  /// entries, those of row r from rowStart[r]), where applyBlockwise sums it (CoarseSpace
  /// builds this import for G and hands it over).
  void sumEntriesAtRowOwners(Teuchos::RCP<const Tpetra::Import<LO, GO>> import, Teuchos::RCP<DualVector> source,
                             Teuchos::RCP<DualVector> target, std::vector<LO> firstSource, const std::vector<LO>* rowStart);

  /// x (owned) -> overlap values -> op(L, true) on each owned subdomain (its `in` gathered, its
  /// `out` filled) -> each row's entries summed into y (owned).
  template <class LocalOp>
  void applyBlockwise(const DualVector& x, DualVector& y, LocalOp op) const;
  /// x on the overlap rows (x itself on one rank).
  const double* overlapValues(const DualVector& x) const;

  /// Per coarse column (6 per subdomain): 1 where R's column is 0 (components eliminated), on
  /// every rank. Collective.
  std::vector<char> pinnedModes() const;

  Teuchos::RCP<const DualMap> dualMap() const { return dualMap_; }
  bool overlapIsOwned() const { return overlapIsOwned_; }
  const ConstraintMatrix& constraints() const { return B_; }
  const Teuchos::RCP<const Teuchos::Comm<int>>& comm() const { return comm_; }
  int numSubdomains() const { return numSubdomains_; }
  int firstOwned() const { return firstOwned_; }
  int numOwned() const { return static_cast<int>(local_.size()); }
  OwnedSubdomain& owned(int i) const { return *local_[i]; }
  const std::vector<std::unique_ptr<OwnedSubdomain>>& all() const { return local_; }
  long long primalDofs() const { return primalDofs_; }
  GO rowId(GO r) const { return B_.rowId.empty() ? r : B_.rowId[r]; }

 private:
  void gatherOverlapContributions();

  const ConstraintMatrix& B_;
  Teuchos::RCP<const Teuchos::Comm<int>> comm_;
  int numSubdomains_ = 0, firstOwned_ = 0;
  std::vector<std::unique_ptr<OwnedSubdomain>> local_;
  Teuchos::RCP<const DualMap> dualMap_, overlapMap_;
  Teuchos::RCP<const Tpetra::Import<LO, GO>> importer_;
  bool overlapIsOwned_ = false;        ///< one rank: the overlap map is the owned map
  Teuchos::RCP<DualVector> xOverlap_;  ///< applyBlockwise's, allocated once
  std::vector<LO> contributionStart_;
  std::vector<const double*> contribution_;
  Teuchos::RCP<DualVector> entrySource_, entryTarget_;
  Teuchos::RCP<const Tpetra::Import<LO, GO>> entryImport_;
  std::vector<LO> entrySourceFirst_;
  const std::vector<LO>* entryRowStart_ = nullptr;  ///< per owned row + 1: its entries in entryTarget_
  long long primalDofs_ = 0;  ///< sum of n_s over all subdomains
};

template <class LocalOp>
void SubdomainSet::applyBlockwise(const DualVector& x, DualVector& y, LocalOp op) const {
  // Import (main thread), per-subdomain work on threads with raw pointers only, then each
  // row's sum over its subdomains in ascending subdomain order, on any layout: with several
  // ranks the entries travel to the row's owner one by one (a per-rank pre-sum, then an
  // export-add, would group three or more terms differently on different layouts). The
  // work vectors live as long as this object (no allocation per application); when the
  // overlap is the owned rows themselves (one rank), x serves as its own overlap vector.
  const double* xo = overlapValues(x);
  if (!overlapIsOwned_) {
    // Several ranks: each entry to the owner of its row, summed there in subdomain order.
    double* source = entrySource_->getLocalViewHost(Tpetra::Access::OverwriteAll).data();
    core::forEachSubdomain(numOwned(), [&](int i) {
      OwnedSubdomain& L = *local_[i];
      for (LO r = 0; r < L.m(); ++r) L.in[r] = xo[L.overlapIndex[r]];
      op(L, true);
      std::copy(L.out.begin(), L.out.end(), source + entrySourceFirst_[i]);
    });
    entryTarget_->doImport(*entrySource_, *entryImport_, Tpetra::INSERT);
    const double* entry = readOnly(*entryTarget_);
    double* yo = y.getLocalViewHost(Tpetra::Access::OverwriteAll).data();
    const std::vector<LO>& rowStart = *entryRowStart_;
    const LO numRows = static_cast<LO>(rowStart.size()) - 1;
    core::forEachSubdomain((numRows + kRowChunk - 1) / kRowChunk, [&](int chunk) {
      const LO end = std::min<LO>(numRows, (chunk + 1) * kRowChunk);
      for (LO r = chunk * kRowChunk; r < end; ++r) {
        double total = 0.0;
        for (LO e = rowStart[r]; e < rowStart[r + 1]; ++e) total += entry[e];
        yo[r] = total;
      }
    });
    return;
  }
  core::forEachSubdomain(numOwned(), [&](int i) {
    OwnedSubdomain& L = *local_[i];
    for (LO r = 0; r < L.m(); ++r) L.in[r] = xo[L.overlapIndex[r]];
    op(L, true);
  });
  // One rank (or no shared rows): the overlap is the owned rows; every one has a
  // contribution (that is what puts it in the overlap), so the gather overwrites y.
  double* yo = y.getLocalViewHost(Tpetra::Access::OverwriteAll).data();
  const LO numOverlap = static_cast<LO>(contributionStart_.size()) - 1;
  core::forEachSubdomain((numOverlap + kRowChunk - 1) / kRowChunk, [&](int chunk) {
    const LO end = std::min<LO>(numOverlap, (chunk + 1) * kRowChunk);
    for (LO o = chunk * kRowChunk; o < end; ++o) {
      double total = 0.0;
      for (LO k = contributionStart_[o]; k < contributionStart_[o + 1]; ++k) total += *contribution_[k];
      yo[o] = total;
    }
  });
}

}  // namespace tribos::feti
