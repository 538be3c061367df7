// The owned subdomains and the dual layout (SubdomainSet.hpp).
#include "SubdomainSet.hpp"

namespace tribos::feti {

SubdomainSet::SubdomainSet(const ConstraintMatrix& B, const Teuchos::RCP<const Teuchos::Comm<int>>& comm,
                           int numSubdomains, int numOwned)
    : B_(B), comm_(comm), numSubdomains_(numSubdomains) {
  const int rank = comm->getRank(), size = comm->getSize();
  firstOwned_ = mesh::firstSubdomain(rank, numSubdomains_, size);
  const int expected = mesh::firstSubdomain(rank + 1, numSubdomains_, size) - firstOwned_;
  TEUCHOS_TEST_FOR_EXCEPTION(numOwned != expected, std::invalid_argument,
                             "tribos::feti::TotalFeti: got " << numOwned << " subdomain systems, rank owns "
                                                             << expected);
  TEUCHOS_TEST_FOR_EXCEPTION(static_cast<int>(B.firstRowOfRank.size()) != size + 1, std::invalid_argument,
                             "tribos::feti::TotalFeti: B was built for " << B.firstRowOfRank.size() - 1
                                                                         << " ranks, the communicator has " << size);
  // (1) Maps: owned rows (contiguous per rank by construction of B) and the overlap = the
  // rows that touch this rank's subdomains, both in B's row order. Their global ids are
  // B.rowId, the numbering of one rank: the same id for the same row on any number of ranks.
  const GO myFirst = B_.firstRowOfRank[rank], myEnd = B_.firstRowOfRank[rank + 1];
  std::vector<GO> ids;
  for (GO r = myFirst; r < myEnd; ++r) ids.push_back(rowId(r));
  dualMap_ = Teuchos::rcp(new DualMap(B_.numRows, Teuchos::ArrayView<const GO>(ids.data(), ids.size()), 0, comm_));
  std::vector<GO> overlapRows;
  for (int i = 0; i < numOwned; ++i) {
    const auto& rows = B_.blocks[firstOwned_ + i].rows;
    overlapRows.insert(overlapRows.end(), rows.begin(), rows.end());
  }
  std::sort(overlapRows.begin(), overlapRows.end());
  overlapRows.erase(std::unique(overlapRows.begin(), overlapRows.end()), overlapRows.end());
  ids.clear();
  for (GO r : overlapRows) ids.push_back(rowId(r));
  overlapMap_ = Teuchos::rcp(new DualMap(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                                         Teuchos::ArrayView<const GO>(ids.data(), ids.size()), 0, comm_));
  importer_ = Teuchos::rcp(new Tpetra::Import<LO, GO>(dualMap_, overlapMap_));
  overlapIsOwned_ = overlapMap_->isSameAs(*dualMap_);
  xOverlap_ = Teuchos::rcp(new DualVector(overlapMap_));
}

void SubdomainSet::setUp(const mesh::Mesh& mesh, const mesh::Decomposition& decomposition,
                         std::vector<fem::SubdomainSystem> owned) {
  const int numOwned = static_cast<int>(owned.size());
  // (2) Rigid body modes of the owned subdomains (a rank needs no other R_s: the g_{s,r}
  // of foreign subdomains come from their owners, CoarseSpace).
  std::vector<std::vector<double>> R(numOwned);
  core::forEachSubdomain(numOwned, [&](int i) {
    const auto& nodes = decomposition.subdomains[firstOwned_ + i].nodes;
    std::vector<std::array<double, 3>> coords;
    coords.reserve(nodes.size());
    for (LO node : nodes) coords.push_back(mesh.coords[node]);
    R[i] = fem::rigidBodyModes(coords);
  });
  // (3) Owned subdomains: their systems, rows of B and work buffers.
  local_.resize(numOwned);
  for (int i = 0; i < numOwned; ++i) {
    auto L = std::make_unique<OwnedSubdomain>();
    L->subdomain = firstOwned_ + i;
    L->block = &B_.blocks[L->subdomain];
    L->system = std::move(owned[i]);
    L->system.R = std::move(R[i]);
    if (!L->block->eliminated.empty())
      L->eliminated = eliminateComponents(L->system, L->block->eliminated, L->liveModes);
    for (GO row : L->block->rows) L->overlapIndex.push_back(overlapMap_->getLocalElement(rowId(row)));
    L->rowOrder.resize(L->m());
    std::iota(L->rowOrder.begin(), L->rowOrder.end(), 0);
    std::sort(L->rowOrder.begin(), L->rowOrder.end(),
              [&](LO a, LO b) { return rowId(L->block->rows[a]) < rowId(L->block->rows[b]); });
    L->in.assign(L->m(), 0.0);
    L->out.assign(L->m(), 0.0);
    // n for the solves, m for the explicit F's gathered input and sums (applyPackedLower)
    L->x.assign(std::max(L->n(), L->m()), 0.0);
    L->y.assign(std::max(L->n(), L->m()), 0.0);
    local_[i] = std::move(L);
  }
  gatherOverlapContributions();
  long long mine = 0;
  for (const auto& L : local_) mine += L->n();
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_SUM, 1, &mine, &primalDofs_);
}

double SubdomainSet::factorize(const mesh::Mesh& mesh, const mesh::Decomposition& decomposition,
                               const TotalFetiSettings& settings,
                               const std::function<void(OwnedSubdomain&, int)>& alsoEach) {
  core::Stopwatch watch;
  std::atomic<bool> stopped{false};  // Solver/Max Seconds passed on this rank: the rest skipped
  core::forEachSubdomain(numOwned(), [&](int i) {
    if (stopped || (settings.deadline && settings.deadline->passed())) {
      stopped = true;
      return;
    }
    OwnedSubdomain& L = *local_[i];
    std::vector<std::array<double, 3>> coords;
    for (LO node : decomposition.subdomains[L.subdomain].nodes) coords.push_back(mesh.coords[node]);
    L.solver.compute(L.system, coords, settings.factorization, settings.factorOptions);
    std::vector<LO> position(L.n());
    const std::vector<LO>& perm = L.solver.permutation();
    for (LO k = 0; k < L.n(); ++k) position[perm[k]] = k;
    std::vector<LO> factorDof(L.block->dof.size());  // per entry of the block: its dof in the factor's order
    for (size_t k = 0; k < factorDof.size(); ++k) factorDof[k] = position[L.block->dof[k]];
    L.solver.setSparseDofs(factorDof);
    L.factorTerms = blockTerms(*L.block, L.rowOrder, factorDof);
    alsoEach(L, i);
  });
  if (settings.deadline) settings.deadline->agree(stopped, "the factorisation", rawComm(*comm_));
  double seconds = watch.seconds(), slowest = 0.0;
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MAX, 1, &seconds, &slowest);
  return slowest;
}

void SubdomainSet::sumEntriesAtRowOwners(Teuchos::RCP<const Tpetra::Import<LO, GO>> import,
                                         Teuchos::RCP<DualVector> source, Teuchos::RCP<DualVector> target,
                                         std::vector<LO> firstSource, const std::vector<LO>* rowStart) {
  entryImport_ = std::move(import);
  entrySource_ = std::move(source);
  entryTarget_ = std::move(target);
  entrySourceFirst_ = std::move(firstSource);
  entryRowStart_ = rowStart;
}

const double* SubdomainSet::overlapValues(const DualVector& x) const {
  if (overlapIsOwned_) return readOnly(x);
  xOverlap_->doImport(x, *importer_, Tpetra::INSERT);
  return readOnly(*xOverlap_);
}

void SubdomainSet::gatherOverlapContributions() {
  // For each overlap row, the entries of the subdomains' `out` that add into it, in
  // ascending subdomain order (the order the sequential sum used): a row's sum is then one
  // thread's business, and the same bits for any number of threads.
  const LO numOverlap = static_cast<LO>(overlapMap_->getNodeNumElements());
  contributionStart_.assign(numOverlap + 1, 0);
  for (const auto& L : local_)
    for (LO index : L->overlapIndex) ++contributionStart_[index + 1];
  for (LO o = 0; o < numOverlap; ++o) contributionStart_[o + 1] += contributionStart_[o];
  contribution_.resize(contributionStart_.back());
  std::vector<LO> fill(contributionStart_.begin(), contributionStart_.end() - 1);
  for (const auto& L : local_)
    for (LO r = 0; r < L->m(); ++r) contribution_[fill[L->overlapIndex[r]]++] = &L->out[r];
}

std::vector<char> SubdomainSet::pinnedModes() const {
  // The columns of R that eliminated components left 0, of every subdomain (owners know theirs).
  std::vector<int> mine(6 * static_cast<size_t>(numSubdomains_), 0), all(mine.size(), 0);
  for (const auto& L : local_)
    for (int j = L->liveModes; j < 6; ++j) mine[6 * static_cast<size_t>(L->subdomain) + j] = 1;
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MAX, static_cast<int>(mine.size()), mine.data(), all.data());
  return std::vector<char>(all.begin(), all.end());
}

}  // namespace tribos::feti
