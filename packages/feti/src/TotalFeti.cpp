// TotalFeti, the orchestrator of the T-FETI components (BlockKernels.hpp lists them): their
// set-up in order, F and P F, e, d~ and lambda_Im, and the public operations, each handed to the
// component that owns it.
#include "tribos/feti/TotalFeti.hpp"

#include "CoarseProblem.hpp"
#include "CoarseSpace.hpp"
#include "Preconditioners.hpp"
#include "PrimalRecovery.hpp"
#include "SubdomainSet.hpp"

namespace tribos::feti {

TotalFeti::~TotalFeti() = default;

namespace {
// F_s = B_s K^dagger B_s^T, column by column of B_s^T (ALGORITHMS.md 3, explicit F).
void assembleExplicitF(OwnedSubdomain& L) {
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

TotalFeti::TotalFeti(const mesh::Mesh& mesh, const mesh::Decomposition& decomposition,
                     std::vector<fem::SubdomainSystem> owned, const ConstraintMatrix& B,
                     const Teuchos::RCP<const Teuchos::Comm<int>>& comm, const TotalFetiSettings& settings)
    : B_(B), comm_(comm), settings_(settings), numSubdomains_(decomposition.numSubdomains()) {
  {
    core::ScopedPhase phase("T-FETI: subdomain factors");
    const int numOwned = static_cast<int>(owned.size());
    subdomains_ = std::make_unique<SubdomainSet>(B_, comm_, numSubdomains_, numOwned);  // (1)
    subdomains_->setUp(mesh, decomposition, std::move(owned));                          // (2) and (3)'s structures
    const bool preconditioned = settings_.dirichletPreconditioner || settings_.lumpedPreconditioner;
    preconditioners_ = std::make_unique<Preconditioners>(numOwned, settings_.dirichletPreconditioner,
                                                         settings_.factorization, settings_.factorOptions);
    // (3) the factors, and with each the preconditioner's blocks and the explicit F_s asked for
    factorizationSeconds_ = subdomains_->factorize(mesh, decomposition, settings_, [&](OwnedSubdomain& L, int i) {
      if (preconditioned) preconditioners_->build(L, i);
      if (settings_.explicitF) assembleExplicitF(L);
    });
  }
  {
    // (4) G on the owned rows; G G^T assembled and factorised once, on rank 0.
    core::ScopedPhase phase("T-FETI: coarse space and problem");
    coarse_ = std::make_unique<CoarseSpace>(*subdomains_, mesh, decomposition, profile_);
    measureTraffic();  // before the coarse factor: "Auto" compares the coarse solve with it
    coarse_->setUpProblem(subdomainBytesPerF_, settings_, subdomains_->pinnedModes());
  }
  if (settings_.deadline) settings_.deadline->check("the coarse problem", rawComm(*comm));
  settings_.deadline = nullptr;  // the caller's: not kept beyond the set-up
  recovery_ = std::make_unique<PrimalRecovery>(*subdomains_, *coarse_, settings_);
  core::ScopedPhase phase("T-FETI: d~ and lambda_Im");
  {
    const int rank = comm_->getRank();
    c_.assign(B_.c.begin() + B_.firstRowOfRank[rank], B_.c.begin() + B_.firstRowOfRank[rank + 1]);
  }
  buildDualData();  // (5)
}

void TotalFeti::setRightHandSide(const std::vector<std::vector<double>>& fOwned, const std::vector<double>& cOwned) {
  const int numOwned = subdomains_->numOwned();
  TEUCHOS_TEST_FOR_EXCEPTION(fOwned.size() != static_cast<size_t>(numOwned) || cOwned.size() != c_.size(),
                             std::invalid_argument,
                             "tribos::feti::TotalFeti::setRightHandSide: " << fOwned.size() << " load vectors and "
                                 << cOwned.size() << " values of c for " << numOwned << " owned subdomains and "
                                 << c_.size() << " owned rows");
  for (int i = 0; i < numOwned; ++i) {
    OwnedSubdomain& L = subdomains_->owned(i);
    TEUCHOS_TEST_FOR_EXCEPTION(fOwned[i].size() != L.system.f.size(), std::invalid_argument,
                               "tribos::feti::TotalFeti::setRightHandSide: subdomain " << L.subdomain << " has "
                                   << L.system.f.size() << " dofs, its load " << fOwned[i].size());
    L.system.f = fOwned[i];
    if (!L.eliminated.dof.empty()) eliminateLoads(L.system.f, L.eliminated);
  }
  c_ = cOwned;
  buildDualData();
}

void TotalFeti::buildDualData() {
  // (5) e = R^T f, d~ = B K^dagger f - c, lambda_Im = G^T (G G^T)^{-1} e.
  e_.assign(numCoarse(), 0.0);
  std::vector<double> eLocal(numCoarse(), 0.0);
  for (const auto& L : subdomains_->all())
    for (int j = 0; j < 6; ++j) {
      double s = 0.0;
      for (LO k = 0; k < L->n(); ++k) s += L->system.R[static_cast<size_t>(j) * L->n() + k] * L->system.f[k];
      eLocal[6 * L->subdomain + j] = s;
    }
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_SUM, numCoarse(), eLocal.data(), e_.data());

  dTilde_ = createDualVector();
  subdomains_->applyBlockwise(*dTilde_, *dTilde_, [](OwnedSubdomain& L, bool) {
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

// --- F and P F --------------------------------------------------------------------------

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
  subdomains_->applyBlockwise(x, y, [this, removeKernel](OwnedSubdomain& L, bool) {
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

// --- The preconditioners ------------------------------------------------------------------

namespace {
/// One preconditioner application, counted and timed in the profile.
template <class Apply>
void countedApplication(OperatorProfile& profile, Apply apply) {
  core::Stopwatch watch;
  apply();
  ++profile.preconditionerApplications;
  profile.preconditionerSeconds += watch.seconds();
}
}  // namespace

void TotalFeti::applyLumped(const DualVector& x, DualVector& y) const {
  TEUCHOS_TEST_FOR_EXCEPTION(!settings_.lumpedPreconditioner && !settings_.dirichletPreconditioner, std::logic_error,
                             "tribos::feti::TotalFeti::applyLumped: construct with "
                             "settings.lumpedPreconditioner = true");
  countedApplication(profile_, [&] { preconditioners_->applyLumped(*subdomains_, x, y); });
}

void TotalFeti::applyDirichlet(const DualVector& x, DualVector& y) const {
  TEUCHOS_TEST_FOR_EXCEPTION(!settings_.dirichletPreconditioner, std::logic_error,
                             "tribos::feti::TotalFeti::applyDirichlet: construct with "
                             "settings.dirichletPreconditioner = true");
  countedApplication(profile_, [&] { preconditioners_->applyDirichlet(*subdomains_, x, y); });
}

// --- The coarse space and the projector ---------------------------------------------------

void TotalFeti::applyG(const DualVector& x, std::vector<double>& gx) const { coarse_->applyG(x, gx); }
void TotalFeti::applyGt(const std::vector<double>& a, DualVector& y) const { coarse_->applyGt(a, y); }
void TotalFeti::solveCoarse(std::vector<double>& a) const { coarse_->solve(a); }
void TotalFeti::solveCoarseExactly(std::vector<double>& a) const { coarse_->solveExactly(a); }
void TotalFeti::releaseCoarseFactor() const { coarse_->release(); }
void TotalFeti::keepCoarseFactor(bool keep) { coarse_->keepFactor(keep); }
void TotalFeti::project(const DualVector& x, DualVector& y, CoarseCoordinates* ofX) const { coarse_->project(x, y, ofX); }
void TotalFeti::projectExactly(const DualVector& x, DualVector& y) const { coarse_->projectExactly(x, y); }
void TotalFeti::coarseCoordinates(const DualVector& x, std::vector<double>& gx, std::vector<double>& a) const {
  coarse_->coordinates(x, gx, a);
}

// --- The primal recovery ------------------------------------------------------------------

std::vector<double> TotalFeti::rigidBodyCoefficients(const DualVector& lambda) const {
  const core::ScopedSeconds timed(profile_.rigidCoefficientsSeconds);
  DualVector residual(dualMap());
  applyF(lambda, residual);
  residual.update(-1.0, *dTilde_, 1.0);
  std::vector<double> alpha;
  applyG(residual, alpha);
  solveCoarseExactly(alpha);
  return alpha;
}

std::vector<double> TotalFeti::rigidBodyCoefficients(const DualVector& lambda,
                                                     const std::vector<char>& ownedRowMask) const {
  return rigidBodyCoefficients(lambda, ownedRowMask, {});
}

std::vector<double> TotalFeti::rigidBodyCoefficients(const DualVector& lambda, const std::vector<char>& ownedRowMask,
                                                     const std::vector<RowCombination>& combinations) const {
  const core::ScopedSeconds timed(profile_.rigidCoefficientsSeconds);
  DualVector residual(dualMap());
  applyF(lambda, residual);
  residual.update(-1.0, *dTilde_, 1.0);
  return recovery_->rigidBodyCoefficients(residual, ownedRowMask, combinations);
}

void TotalFeti::applyB(const std::vector<std::vector<double>>& u, DualVector& y) const { recovery_->applyB(u, y); }

double TotalFeti::equilibriumResidual(const DualVector& lambda, const std::vector<std::vector<double>>& u,
                                      double* forceScale) const {
  return recovery_->equilibriumResidual(lambda, u, forceScale);
}

std::vector<std::vector<double>> TotalFeti::recoverDisplacements(const DualVector& lambda,
                                                                 const std::vector<double>& alpha) const {
  return recovery_->recoverDisplacements(lambda, alpha);
}

std::vector<EliminatedReaction> TotalFeti::eliminatedReactions(const std::vector<std::vector<double>>& u) const {
  return recovery_->eliminatedReactions(u);
}

double TotalFeti::energy(const std::vector<std::vector<double>>& u) const { return recovery_->energy(u); }
double TotalFeti::loadNormInf() const { return recovery_->loadNormInf(); }

// --- Layout and counts ----------------------------------------------------------------------

Teuchos::RCP<const DualMap> TotalFeti::dualMap() const { return subdomains_->dualMap(); }
Teuchos::RCP<DualVector> TotalFeti::createDualVector() const { return Teuchos::rcp(new DualVector(dualMap())); }
const SubdomainSolver& TotalFeti::subdomainSolver(int i) const { return subdomains_->all().at(i)->solver; }
int TotalFeti::firstOwnedSubdomain() const { return subdomains_->firstOwned(); }
int TotalFeti::numOwnedSubdomains() const { return subdomains_->numOwned(); }
long long TotalFeti::primalDofs() const { return subdomains_->primalDofs(); }

}  // namespace tribos::feti
