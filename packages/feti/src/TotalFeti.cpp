// TotalFeti: the set-up (maps, factorisations, G, the coarse problem, d~, lambda_Im) and F.
#include "CoarseProblem.hpp"
#include "TotalFetiParts.hpp"

namespace tribos::feti {

TotalFeti::~TotalFeti() = default;

TotalFeti::TotalFeti(const mesh::Mesh& mesh, const mesh::Decomposition& decomposition,
                     std::vector<fem::SubdomainSystem> owned, const ConstraintMatrix& B,
                     const Teuchos::RCP<const Teuchos::Comm<int>>& comm, const TotalFetiSettings& settings)
    : B_(B), comm_(comm), settings_(settings) {
  const int rank = comm->getRank(), size = comm->getSize();
  numSubdomains_ = decomposition.numSubdomains();
  firstOwned_ = mesh::firstSubdomain(rank, numSubdomains_, size);
  const int numOwned = mesh::firstSubdomain(rank + 1, numSubdomains_, size) - firstOwned_;
  TEUCHOS_TEST_FOR_EXCEPTION(static_cast<int>(owned.size()) != numOwned, std::invalid_argument,
                             "tribos::feti::TotalFeti: got " << owned.size() << " subdomain systems, rank owns "
                                                             << numOwned);
  TEUCHOS_TEST_FOR_EXCEPTION(static_cast<int>(B.firstRowOfRank.size()) != size + 1, std::invalid_argument,
                             "tribos::feti::TotalFeti: B was built for " << B.firstRowOfRank.size() - 1
                                                                         << " ranks, the communicator has " << size);
  {
    core::ScopedPhase phase("T-FETI: subdomain factors");
    buildMaps(numOwned);                                     // (1)
    setUpSubdomains(mesh, decomposition, std::move(owned));  // (2) and (3)'s structures
    factorizeSubdomains(mesh, decomposition);                // (3)
  }
  {
    // (4) G on the owned rows; G G^T assembled and factorised once, on rank 0.
    core::ScopedPhase phase("T-FETI: coarse space and problem");
    buildCoarseRows(mesh, decomposition);
    measureTraffic();  // before the coarse factor: "Auto" compares the coarse solve with it
    coarse_ = std::make_unique<CoarseProblem>(*G_, numSubdomains_, B_.numRows, gMax_, subdomainBytesPerF_, comm_,
                                              settings_, profile_, pinnedModes());
    coarse_->factorize();
  }
  if (settings_.deadline) settings_.deadline->check("the coarse problem", rawComm(*comm));
  settings_.deadline = nullptr;  // the caller's: not kept beyond the set-up
  core::ScopedPhase phase("T-FETI: d~ and lambda_Im");
  {
    const int rank = comm_->getRank();
    c_.assign(B_.c.begin() + B_.firstRowOfRank[rank], B_.c.begin() + B_.firstRowOfRank[rank + 1]);
  }
  buildDualData();  // (5)
}

void TotalFeti::setRightHandSide(const std::vector<std::vector<double>>& fOwned, const std::vector<double>& cOwned) {
  TEUCHOS_TEST_FOR_EXCEPTION(fOwned.size() != local_.size() || cOwned.size() != c_.size(), std::invalid_argument,
                             "tribos::feti::TotalFeti::setRightHandSide: " << fOwned.size() << " load vectors and "
                                 << cOwned.size() << " values of c for " << local_.size() << " owned subdomains and "
                                 << c_.size() << " owned rows");
  for (size_t i = 0; i < local_.size(); ++i) {
    TEUCHOS_TEST_FOR_EXCEPTION(fOwned[i].size() != local_[i]->system.f.size(), std::invalid_argument,
                               "tribos::feti::TotalFeti::setRightHandSide: subdomain " << local_[i]->subdomain
                                   << " has " << local_[i]->system.f.size() << " dofs, its load "
                                   << fOwned[i].size());
    local_[i]->system.f = fOwned[i];
    if (!local_[i]->eliminated.dof.empty()) eliminateLoads(local_[i]->system.f, local_[i]->eliminated);
  }
  c_ = cOwned;
  buildDualData();
}

void TotalFeti::buildMaps(int numOwned) {
  // (1) Maps: owned rows (contiguous per rank by construction of B) and the overlap = the
  // rows that touch this rank's subdomains, both in B's row order. Their global ids are
  // B.rowId, the numbering of one rank: the same id for the same row on any number of ranks.
  const int rank = comm_->getRank();
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

std::vector<char> TotalFeti::pinnedModes() const {
  // The columns of R that eliminated components left 0, of every subdomain (owners know theirs).
  std::vector<int> mine(6 * static_cast<size_t>(numSubdomains_), 0), all(mine.size(), 0);
  for (const auto& L : local_)
    for (int j = L->liveModes; j < 6; ++j) mine[6 * static_cast<size_t>(L->subdomain) + j] = 1;
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MAX, static_cast<int>(mine.size()), mine.data(), all.data());
  return std::vector<char>(all.begin(), all.end());
}

std::vector<EliminatedReaction> TotalFeti::eliminatedReactions(const std::vector<std::vector<double>>& u) const {
  std::vector<EliminatedReaction> out;
  for (size_t i = 0; i < local_.size(); ++i) {
    const Local& L = *local_[i];
    const std::vector<double> force = feti::eliminatedReactions(L.eliminated, u[i]);
    for (size_t k = 0; k < force.size(); ++k) out.push_back({L.subdomain, L.eliminated.dof[k], force[k]});
  }
  return out;
}

void TotalFeti::setUpSubdomains(const mesh::Mesh& mesh, const mesh::Decomposition& decomposition,
                                std::vector<fem::SubdomainSystem> owned) {
  const int numOwned = static_cast<int>(owned.size());
  // (2) Rigid body modes of the owned subdomains (a rank needs no other R_s: the g_{s,r}
  // of foreign subdomains come from their owners, buildCoarseRows).
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
    auto L = std::make_unique<Local>();
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

namespace {
// F_s = B_s K^dagger B_s^T, column by column of B_s^T (ALGORITHMS.md 3, explicit F).
void assembleExplicitF(TotalFeti::Local& L) {
  const LO m = L.m(), n = L.n();
  std::vector<double> Bt(static_cast<size_t>(n) * m, 0.0), Y(static_cast<size_t>(n) * m);
  for (LO r = 0; r < m; ++r)
    for (LO k = L.block->rowPtr[r]; k < L.block->rowPtr[r + 1]; ++k)
      Bt[static_cast<size_t>(r) * n + L.block->dof[k]] = L.block->value[k];
  L.solver.applyPseudoInverse(Bt.data(), Y.data(), m);
  std::vector<double> full(static_cast<size_t>(m) * m);
  for (LO c = 0; c < m; ++c) applyBlock(*L.block, &Y[static_cast<size_t>(c) * n], &full[static_cast<size_t>(c) * m]);
  L.denseF = packLowerInRowOrder(full, L.rowOrder);
}
}  // namespace

void TotalFeti::factorizeSubdomains(const mesh::Mesh& mesh, const mesh::Decomposition& decomposition) {
  // (3) K_reg of every owned subdomain factorised on threads, B_s in the factor's order, the
  // preconditioners' blocks and the explicit F_s when asked for.
  core::Stopwatch watch;
  std::atomic<bool> stopped{false};  // Solver/Max Seconds passed on this rank: the rest skipped
  core::forEachSubdomain(numOwnedSubdomains(), [&](int i) {
    if (stopped || (settings_.deadline && settings_.deadline->passed())) {
      stopped = true;
      return;
    }
    Local& L = *local_[i];
    std::vector<std::array<double, 3>> coords;
    for (LO node : decomposition.subdomains[L.subdomain].nodes) coords.push_back(mesh.coords[node]);
    L.solver.compute(L.system, coords, settings_.factorization, settings_.factorOptions);
    std::vector<LO> position(L.n());
    const std::vector<LO>& perm = L.solver.permutation();
    for (LO k = 0; k < L.n(); ++k) position[perm[k]] = k;
    std::vector<LO> factorDof(L.block->dof.size());  // per entry of the block: its dof in the factor's order
    for (size_t k = 0; k < factorDof.size(); ++k) factorDof[k] = position[L.block->dof[k]];
    L.solver.setSparseDofs(factorDof);
    L.factorTerms = blockTerms(*L.block, L.rowOrder, factorDof);
    if (settings_.dirichletPreconditioner || settings_.lumpedPreconditioner)
      buildPreconditionerBlocks(L, settings_.dirichletPreconditioner, settings_.factorization, settings_.factorOptions);
    if (settings_.explicitF) assembleExplicitF(L);
  });
  if (settings_.deadline) settings_.deadline->agree(stopped, "the factorisation", rawComm(*comm_));
  double seconds = watch.seconds();
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MAX, 1, &seconds, &factorizationSeconds_);
}

void TotalFeti::buildDualData() {
  // (5) e = R^T f, d~ = B K^dagger f - c, lambda_Im = G^T (G G^T)^{-1} e.
  e_.assign(numCoarse(), 0.0);
  std::vector<double> eLocal(numCoarse(), 0.0);
  for (const auto& L : local_)
    for (int j = 0; j < 6; ++j) {
      double s = 0.0;
      for (LO k = 0; k < L->n(); ++k) s += L->system.R[static_cast<size_t>(j) * L->n() + k] * L->system.f[k];
      eLocal[6 * L->subdomain + j] = s;
    }
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_SUM, numCoarse(), eLocal.data(), e_.data());

  dTilde_ = createDualVector();
  applyBlockwise(*dTilde_, *dTilde_, [](Local& L, bool) {
    L.solver.applyPseudoInverse(L.system.f.data(), L.y.data());
    applyBlock(*L.block, L.y.data(), L.out.data());
  });
  {
    const int rank = comm_->getRank();
    const GO myFirst = B_.firstRowOfRank[rank], myEnd = B_.firstRowOfRank[rank + 1];
    double* d = readWrite(*dTilde_);
    for (GO r = myFirst; r < myEnd; ++r) d[r - myFirst] -= c_[r - myFirst];
  }
  lambdaIm_ = createDualVector();
  std::vector<double> a = e_;
  solveCoarseExactly(a);  // G lambda_Im = e to double precision
  applyGt(a, *lambdaIm_);
}

void TotalFeti::measureTraffic() {
  // The least each product with P F P must move between memory and the cores: every array
  // below is read (or written) once per use, the n_s-sized work vectors of a subdomain
  // staying in cache. doc/measurements/performance.md divides it by the triad bandwidth.
  constexpr double kDouble = sizeof(double), kIndex = sizeof(LO);
  double f = 0.0, factorEntries = 0.0;
  for (const auto& L : local_) {
    const double entries = static_cast<double>(L->block->value.size()), rows = L->m();
    if (settings_.explicitF) {
      f += kDouble * rows * (rows + 1) / 2;  // F_s's lower triangle (packLowerInRowOrder)
    } else {
      // the factor (forward whole, backward the part B_s's dofs reach; P F P applies K^+, not
      // K^dagger, so R is not read); B_s^T and B_s (its terms, twice)
      f += static_cast<double>(L->solver.generalizedInverseBytesOnDofs()) + 2 * entries * sizeof(BlockTerm);
    }
    f += rows * (2 * kIndex + 3 * kDouble);  // overlap indices in and out; x gathered, y added
    factorEntries += static_cast<double>(L->solver.factor().factorNonzeros());
  }
  const double subdomainF = f;
  // The preconditioner: K_bb's upper triangle (lumped), with the Dirichlet one K_ib twice (K_ib
  // and K_bi = K_ib^T) and the K_ii factor (both substitutions); B_s^T and B_s (its terms,
  // twice), the dual entries.
  const bool preconditioner = settings_.dirichletPreconditioner || settings_.lumpedPreconditioner;
  double dirichlet = 0.0;
  for (const auto& L : local_) {
    if (!preconditioner) break;
    const DirichletBlocks& D = L->dirichlet;
    const double entries = static_cast<double>(L->block->value.size()), rows = L->m();
    dirichlet += D.Kbb.bytes() + 2 * entries * sizeof(BlockTerm) + rows * (2 * kIndex + 3 * kDouble);
    if (!settings_.dirichletPreconditioner) continue;
    dirichlet += 2 * D.Kib.bytes();
    if (D.interiorFactor) dirichlet += static_cast<double>(D.interiorFactor->solveBytes());
  }
  const double owned = static_cast<double>(G_->numRows), gEntries = static_cast<double>(G_->rowSubdomain.size());
  f += owned * kDouble;  // y cleared before the sum
  // One projection: G x and G^T a, each one pass over its terms (16 bytes each: G x's of
  // the owned subdomains, G^T a's of the owned rows) and the coordinate and full slots (the
  // run table and M_s are small); x read twice, y written. The memo's copies of x and P x
  // are not counted.
  const double gxTerms = static_cast<double>(G_->ownedTerm.size());
  const double slots = static_cast<double>(G_->coords.size() + G_->full.size());
  const double projection = (gxTerms + gEntries) * sizeof(CoarseTerm) + 2 * slots * kDouble + owned * (kIndex + 3 * kDouble);
  if (preconditioner) dirichlet += owned * kDouble;
  // The subdomains' part alone (each counted once, by its owner: the same sum on every
  // layout, unlike the projection's slots, which ranks sharing a subdomain both hold).
  double local[5] = {f + 2 * projection, factorEntries, projection, dirichlet, subdomainF},
         global[5] = {0.0, 0.0, 0.0, 0.0, 0.0};
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_SUM, 5, local, global);
  bytesPerFApplication_ = global[0];
  subdomainBytesPerF_ = global[4];
  factorNonzeros_ = static_cast<long long>(global[1]);
  profile_.projectionBytes = global[2];
  profile_.preconditionerBytes = global[3];
}


Teuchos::RCP<DualVector> TotalFeti::createDualVector() const { return Teuchos::rcp(new DualVector(dualMap_)); }

const SubdomainSolver& TotalFeti::subdomainSolver(int i) const { return local_.at(i)->solver; }

const double* TotalFeti::overlapValues(const DualVector& x) const {
  if (overlapIsOwned_) return readOnly(x);
  xOverlap_->doImport(x, *importer_, Tpetra::INSERT);
  return readOnly(*xOverlap_);
}

void TotalFeti::gatherOverlapContributions() {
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


void TotalFeti::applyF(const DualVector& x, DualVector& y) const { applyF(x, y, true); }

void TotalFeti::applyPF(const DualVector& x, DualVector& y) const {
  // For x in Ker G, B_s^T x is orthogonal to R_s (G x = 0 block by block), and P removes
  // what B_s R_s R_s^T adds on the way out (P G^T = 0): P F x = P B K^+ B^T x, without the
  // two kernel projections of K^dagger.
  applyF(x, y, settings_.explicitF);
  project(y, y);
}

void TotalFeti::applyF(const DualVector& x, DualVector& y, bool removeKernel) const {
  ++fApplications_;
  ++profile_.fApplications;
  core::Stopwatch watch;
  applyBlockwise(x, y, [this, removeKernel](Local& L, bool) {
    if (settings_.explicitF) {
      applyPackedLower(L.denseF, L.rowOrder, L.in.data(), L.x.data(), L.y.data(), L.out.data());
      return;
    }
    // Two triangular solves in the factor's order: B_s^T scatters into it, B_s gathers from it
    // (K^+ alone: the backward one over the part of the factor that B_s's dofs reach).
    scatterTerms(L.factorTerms, L.in.data(), L.x.data(), L.n());
    if (removeKernel)
      L.solver.applyPseudoInversePermuted(L.x.data());
    else
      L.solver.applyGeneralizedInverseOnDofs(L.x.data());
    gatherTerms(L.factorTerms, L.x.data(), L.out.data(), L.m());
  });
  profile_.fSeconds += watch.seconds();
}


}  // namespace tribos::feti
