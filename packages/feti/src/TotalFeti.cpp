#include "tribos/feti/TotalFeti.hpp"

#include <Tpetra_Core.hpp>
#include <Tpetra_Import.hpp>
#include <Tpetra_Map.hpp>
#include <Tpetra_Vector.hpp>

#include <algorithm>
#include <cmath>
#include <map>

#include "tribos/core/Errors.hpp"
#include "tribos/core/Parallel.hpp"
#include "tribos/core/Timer.hpp"
#include "tribos/fem/SubdomainSystem.hpp"

namespace tribos::feti {

namespace {
// x = B_s^T lambda_s (x has n entries, zeroed here).
void applyBlockTranspose(const SubdomainBlock& b, const double* lambda, double* x, LO n) {
  std::fill(x, x + n, 0.0);
  for (size_t i = 0; i + 1 < b.rowPtr.size(); ++i)
    for (LO k = b.rowPtr[i]; k < b.rowPtr[i + 1]; ++k) x[b.dof[k]] += b.value[k] * lambda[i];
}

// out = B_s y.
void applyBlock(const SubdomainBlock& b, const double* y, double* out) {
  for (size_t i = 0; i + 1 < b.rowPtr.size(); ++i) {
    double s = 0.0;
    for (LO k = b.rowPtr[i]; k < b.rowPtr[i + 1]; ++k) s += b.value[k] * y[b.dof[k]];
    out[i] = s;
  }
}

// Extracts K_ii (rows and columns `interior`, ascending) from K.
fem::CsrMatrix principalSubmatrix(const fem::CsrMatrix& K, const std::vector<LO>& keep) {
  std::vector<LO> position(K.n, -1);
  for (size_t i = 0; i < keep.size(); ++i) position[keep[i]] = static_cast<LO>(i);
  fem::CsrMatrix S;
  S.n = static_cast<LO>(keep.size());
  S.rowPtr.assign(S.n + 1, 0);
  for (LO i = 0; i < S.n; ++i) {
    for (LO k = K.rowPtr[keep[i]]; k < K.rowPtr[keep[i] + 1]; ++k)
      if (position[K.colInd[k]] >= 0) {
        S.colInd.push_back(position[K.colInd[k]]);
        S.values.push_back(K.values[k]);
      }
    S.rowPtr[i + 1] = static_cast<LO>(S.colInd.size());
  }
  return S;
}

const double* readOnly(const DualVector& v) { return v.getLocalViewHost(Tpetra::Access::ReadOnly).data(); }
double* readWrite(DualVector& v) { return v.getLocalViewHost(Tpetra::Access::ReadWrite).data(); }
}  // namespace

/// One owned subdomain: its system, generalised inverse, rows of B and scratch buffers
/// (allocated before any threaded loop: TOOLCHAIN.md rule 1).
struct TotalFeti::Local {
  int subdomain = 0;
  const SubdomainBlock* block = nullptr;
  std::vector<LO> overlapIndex;  ///< local index in the overlap map of each block row
  fem::SubdomainSystem system;
  SubdomainSolver solver;
  std::vector<double> denseF;    ///< explicit F_s (m x m, column-major) when requested
  std::vector<LO> interior;      ///< dofs that no row of B touches (Dirichlet preconditioner)
  std::unique_ptr<SparseCholesky> interiorFactor;  ///< K_ii
  std::vector<double> interiorRhs, interiorSol;
  std::vector<double> in, out, x, y;
  LO m() const { return static_cast<LO>(block->rows.size()); }
  LO n() const { return system.K.n; }
};

TotalFeti::~TotalFeti() = default;

namespace {
void buildInteriorFactor(TotalFeti::Local& L, const std::string& factorization) {
  std::vector<char> touched(L.n(), 0);
  for (LO d : L.block->dof) touched[d] = 1;
  for (LO d = 0; d < L.n(); ++d)
    if (!touched[d]) L.interior.push_back(d);
  L.interiorRhs.assign(L.interior.size(), 0.0);
  L.interiorSol.assign(L.interior.size(), 0.0);
  if (L.interior.empty()) return;
  L.interiorFactor = makeSparseCholesky(factorization);
  L.interiorFactor->factorize(principalSubmatrix(L.system.K, L.interior));
}
}  // namespace

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

  // (1) Maps: owned rows (contiguous per rank by construction of B) and the overlap = the
  // rows that touch this rank's subdomains.
  const GO myFirst = B.firstRowOfRank[rank], myEnd = B.firstRowOfRank[rank + 1];
  dualMap_ = Teuchos::rcp(new DualMap(B.numRows, static_cast<size_t>(myEnd - myFirst), 0, comm));
  std::vector<GO> overlapRows;
  for (int i = 0; i < numOwned; ++i) {
    const auto& rows = B.blocks[firstOwned_ + i].rows;
    overlapRows.insert(overlapRows.end(), rows.begin(), rows.end());
  }
  std::sort(overlapRows.begin(), overlapRows.end());
  overlapRows.erase(std::unique(overlapRows.begin(), overlapRows.end()), overlapRows.end());
  overlapMap_ = Teuchos::rcp(new DualMap(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                                         Teuchos::ArrayView<const GO>(overlapRows.data(), overlapRows.size()), 0,
                                         comm));
  importer_ = Teuchos::rcp(new Tpetra::Import<LO, GO>(dualMap_, overlapMap_));

  // (2) Rigid body modes of every subdomain (every rank computes all of them: they are
  // needed for the replicated G G^T and cost little); owned systems use the same bits.
  std::vector<std::vector<double>> R(numSubdomains_);
  core::forEachSubdomain(numSubdomains_, [&](int s) {
    std::vector<std::array<double, 3>> coords;
    coords.reserve(decomposition.subdomains[s].nodes.size());
    for (LO node : decomposition.subdomains[s].nodes) coords.push_back(mesh.coords[node]);
    R[s] = fem::rigidBodyModes(coords);
  });

  // (3) Owned subdomains: factorise K_reg on threads.
  local_.resize(numOwned);
  for (int i = 0; i < numOwned; ++i) {
    auto L = std::make_unique<Local>();
    L->subdomain = firstOwned_ + i;
    L->block = &B.blocks[L->subdomain];
    L->system = std::move(owned[i]);
    L->system.R = R[L->subdomain];  // the same bits as every rank's copy
    for (GO row : L->block->rows) L->overlapIndex.push_back(overlapMap_->getLocalElement(row));
    L->in.assign(L->m(), 0.0);
    L->out.assign(L->m(), 0.0);
    L->x.assign(L->n(), 0.0);
    L->y.assign(L->n(), 0.0);
    local_[i] = std::move(L);
  }
  core::Stopwatch watch;
  core::forEachSubdomain(numOwned, [&](int i) {
    Local& L = *local_[i];
    std::vector<std::array<double, 3>> coords;
    for (LO node : decomposition.subdomains[L.subdomain].nodes) coords.push_back(mesh.coords[node]);
    L.solver.compute(L.system, coords, settings_.factorization);
    if (settings_.dirichletPreconditioner) buildInteriorFactor(L, settings_.factorization);
    if (settings_.explicitF) {
      // F_s = B_s K^dagger B_s^T, column by column of B_s^T (ALGORITHMS.md 3, explicit F).
      const LO m = L.m(), n = L.n();
      std::vector<double> Bt(static_cast<size_t>(n) * m, 0.0), Y(static_cast<size_t>(n) * m);
      for (LO r = 0; r < m; ++r)
        for (LO k = L.block->rowPtr[r]; k < L.block->rowPtr[r + 1]; ++k)
          Bt[static_cast<size_t>(r) * n + L.block->dof[k]] = L.block->value[k];
      L.solver.applyPseudoInverse(Bt.data(), Y.data(), m);
      L.denseF.assign(static_cast<size_t>(m) * m, 0.0);
      for (LO c = 0; c < m; ++c) applyBlock(*L.block, &Y[static_cast<size_t>(c) * n], &L.denseF[static_cast<size_t>(c) * m]);
    }
  });
  double seconds = watch.seconds();
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, 1, &seconds, &factorizationSeconds_);

  // (4) G G^T, replicated, factorised once.
  R_ = std::move(R);
  const fem::CsrMatrix GGt = assembleCoarse(nullptr);
  coarse_ = makeSparseCholesky(settings_.factorization);
  try {
    coarse_->factorize(GGt);
  } catch (const std::exception& e) {
    throw core::InputError(std::string("the constraints do not fix every rigid body mode of every subdomain "
                                       "(G G^T is singular: ") +
                           e.what() + "); check Boundary/Dirichlet Node Sets and the contact surfaces");
  }

  // (5) e = R^T f, d~ = B K^dagger f - c, lambda_Im = G^T (G G^T)^{-1} e.
  e_.assign(numCoarse(), 0.0);
  std::vector<double> eLocal(numCoarse(), 0.0);
  for (const auto& L : local_)
    for (int j = 0; j < 6; ++j) {
      double s = 0.0;
      for (LO k = 0; k < L->n(); ++k) s += L->system.R[static_cast<size_t>(j) * L->n() + k] * L->system.f[k];
      eLocal[6 * L->subdomain + j] = s;
    }
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, numCoarse(), eLocal.data(), e_.data());

  dTilde_ = createDualVector();
  applyBlockwise(*dTilde_, *dTilde_, [](Local& L, bool) {
    L.solver.applyPseudoInverse(L.system.f.data(), L.y.data());
    applyBlock(*L.block, L.y.data(), L.out.data());
  });
  {
    double* d = readWrite(*dTilde_);
    for (GO r = myFirst; r < myEnd; ++r) d[r - myFirst] -= B.c[r];
  }
  lambdaIm_ = createDualVector();
  std::vector<double> a = e_;
  solveCoarse(a);
  applyGt(a, *lambdaIm_);
}

fem::CsrMatrix TotalFeti::assembleCoarse(const std::vector<char>* rowMask) const {
  // g_{s,r} = R_s^T (row r of B_s)^T, and (G G^T)_{st} = sum over rows r touching both s
  // and t of g_{s,r} g_{t,r}^T: 6x6 blocks for subdomains that share a row of B.
  std::vector<std::vector<std::pair<int, std::array<double, 6>>>> byRow(B_.numRows);
  for (int s = 0; s < numSubdomains_; ++s) {
    const auto& b = B_.blocks[s];
    const LO n = static_cast<LO>(R_[s].size() / 6);
    for (size_t i = 0; i < b.rows.size(); ++i) {
      if (rowMask && !(*rowMask)[b.rows[i]]) continue;
      std::array<double, 6> g{};
      for (LO k = b.rowPtr[i]; k < b.rowPtr[i + 1]; ++k)
        for (int j = 0; j < 6; ++j) g[j] += b.value[k] * R_[s][static_cast<size_t>(j) * n + b.dof[k]];
      byRow[b.rows[i]].push_back({s, g});
    }
  }
  std::vector<std::map<int, std::array<double, 36>>> blocks(numSubdomains_);
  for (const auto& touching : byRow)
    for (const auto& [s, gs] : touching)
      for (const auto& [t, gt] : touching) {
        auto& blk = blocks[s][t];
        for (int a = 0; a < 6; ++a)
          for (int c = 0; c < 6; ++c) blk[a * 6 + c] += gs[a] * gt[c];
      }
  fem::CsrMatrix GGt;
  GGt.n = 6 * numSubdomains_;
  GGt.rowPtr.assign(GGt.n + 1, 0);
  for (int s = 0; s < numSubdomains_; ++s)
    for (int a = 0; a < 6; ++a) {
      for (const auto& [t, blk] : blocks[s])
        for (int c = 0; c < 6; ++c) {
          GGt.colInd.push_back(6 * t + c);
          GGt.values.push_back(blk[a * 6 + c]);
        }
      GGt.rowPtr[6 * s + a + 1] = static_cast<LO>(GGt.colInd.size());
    }
  return GGt;
}

std::vector<double> TotalFeti::rigidBodyCoefficients(const DualVector& lambda,
                                                     const std::vector<char>& rowMask) const {
  DualVector residual(dualMap_);
  applyF(lambda, residual);
  residual.update(-1.0, *dTilde_, 1.0);
  {
    auto data = residual.getLocalViewHost(Tpetra::Access::ReadWrite);
    const GO first = dualMap_->getMinGlobalIndex();
    for (size_t i = 0; i < data.extent(0); ++i)
      if (!rowMask[first + static_cast<GO>(i)]) data(i, 0) = 0.0;
  }
  std::vector<double> alpha;
  applyG(residual, alpha);
  auto factor = makeSparseCholesky(settings_.factorization);
  try {
    factor->factorize(assembleCoarse(&rowMask));
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string("tribos::feti::TotalFeti::rigidBodyCoefficients: G_I G_I^T is singular "
                                         "(the inactive rows do not fix every rigid body mode): ") + e.what());
  }
  std::vector<double> rhs = alpha;
  factor->solve(rhs.data(), alpha.data());
  return alpha;
}

Teuchos::RCP<DualVector> TotalFeti::createDualVector() const { return Teuchos::rcp(new DualVector(dualMap_)); }

const SubdomainSolver& TotalFeti::subdomainSolver(int i) const { return local_.at(i)->solver; }

template <class LocalOp>
void TotalFeti::applyBlockwise(const DualVector& x, DualVector& y, LocalOp op) const {
  // Import (main thread), per-subdomain work on threads with raw pointers only, then a
  // sequential, deterministic sum into the overlap vector and an export-add.
  DualVector xOverlap(overlapMap_), yOverlap(overlapMap_);
  xOverlap.doImport(x, *importer_, Tpetra::INSERT);
  const double* xo = readOnly(xOverlap);
  core::forEachSubdomain(numOwnedSubdomains(), [&](int i) {
    Local& L = *local_[i];
    for (LO r = 0; r < L.m(); ++r) L.in[r] = xo[L.overlapIndex[r]];
    op(L, true);
  });
  double* yo = readWrite(yOverlap);
  for (const auto& L : local_)
    for (LO r = 0; r < L->m(); ++r) yo[L->overlapIndex[r]] += L->out[r];
  y.putScalar(0.0);
  y.doExport(yOverlap, *importer_, Tpetra::ADD);
}

void TotalFeti::applyF(const DualVector& x, DualVector& y) const {
  ++fApplications_;
  applyBlockwise(x, y, [this](Local& L, bool) {
    if (settings_.explicitF) {
      // out = F_s in, column-major. A plain loop: Debian's serial OpenBLAS is not safe to
      // call from several threads at once (doc/factorization.md).
      const LO m = L.m();
      std::fill(L.out.begin(), L.out.end(), 0.0);
      for (LO c = 0; c < m; ++c) {
        const double x = L.in[c];
        const double* column = &L.denseF[static_cast<size_t>(c) * m];
        for (LO r = 0; r < m; ++r) L.out[r] += column[r] * x;
      }
      return;
    }
    applyBlockTranspose(*L.block, L.in.data(), L.x.data(), L.n());
    L.solver.applyPseudoInverse(L.x.data(), L.y.data());
    applyBlock(*L.block, L.y.data(), L.out.data());
  });
}

void TotalFeti::applyLumped(const DualVector& x, DualVector& y) const {
  applyBlockwise(x, y, [](Local& L, bool) {
    applyBlockTranspose(*L.block, L.in.data(), L.x.data(), L.n());
    L.system.K.apply(L.x.data(), L.y.data());
    applyBlock(*L.block, L.y.data(), L.out.data());
  });
}

void TotalFeti::applyDirichlet(const DualVector& x, DualVector& y) const {
  TEUCHOS_TEST_FOR_EXCEPTION(!settings_.dirichletPreconditioner, std::logic_error,
                             "tribos::feti::TotalFeti::applyDirichlet: construct with "
                             "settings.dirichletPreconditioner = true");
  applyBlockwise(x, y, [](Local& L, bool) {
    // y = K x with x = B^T in living on the boundary dofs: y_b = K_bb x_b, y_i = K_ib x_b.
    applyBlockTranspose(*L.block, L.in.data(), L.x.data(), L.n());
    L.system.K.apply(L.x.data(), L.y.data());
    if (L.interiorFactor) {
      // s = K_ii^{-1} K_ib x_b, then y_b -= K_bi s (computed as (K [0; s])_b).
      for (size_t k = 0; k < L.interior.size(); ++k) L.interiorRhs[k] = L.y[L.interior[k]];
      L.interiorFactor->solve(L.interiorRhs.data(), L.interiorSol.data());
      std::fill(L.x.begin(), L.x.end(), 0.0);
      for (size_t k = 0; k < L.interior.size(); ++k) L.x[L.interior[k]] = L.interiorSol[k];
      std::vector<double>& correction = L.x;
      std::vector<double> Ks(L.n());
      L.system.K.apply(correction.data(), Ks.data());
      for (LO k = 0; k < L.n(); ++k) L.y[k] -= Ks[k];
    }
    applyBlock(*L.block, L.y.data(), L.out.data());
  });
}

void TotalFeti::applyG(const DualVector& x, std::vector<double>& gx) const {
  DualVector xOverlap(overlapMap_);
  xOverlap.doImport(x, *importer_, Tpetra::INSERT);
  const double* xo = readOnly(xOverlap);
  std::vector<double> local(numCoarse(), 0.0);
  core::forEachSubdomain(numOwnedSubdomains(), [&](int i) {
    Local& L = *local_[i];
    for (LO r = 0; r < L.m(); ++r) L.in[r] = xo[L.overlapIndex[r]];
    applyBlockTranspose(*L.block, L.in.data(), L.x.data(), L.n());
    for (int j = 0; j < 6; ++j) {
      double s = 0.0;
      for (LO k = 0; k < L.n(); ++k) s += L.system.R[static_cast<size_t>(j) * L.n() + k] * L.x[k];
      local[6 * L.subdomain + j] = s;
    }
  });
  gx.assign(numCoarse(), 0.0);
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_SUM, numCoarse(), local.data(), gx.data());
}

void TotalFeti::applyGt(const std::vector<double>& a, DualVector& y) const {
  applyBlockwise(y, y, [&a](Local& L, bool) {
    const LO n = L.n();
    for (LO k = 0; k < n; ++k) {
      double s = 0.0;
      for (int j = 0; j < 6; ++j) s += L.system.R[static_cast<size_t>(j) * n + k] * a[6 * L.subdomain + j];
      L.y[k] = s;
    }
    applyBlock(*L.block, L.y.data(), L.out.data());
  });
}

void TotalFeti::solveCoarse(std::vector<double>& a) const {
  std::vector<double> b = a;
  coarse_->solve(b.data(), a.data());
}

void TotalFeti::project(const DualVector& x, DualVector& y) const {
  std::vector<double> a;
  applyG(x, a);
  solveCoarse(a);
  DualVector correction(dualMap_);
  applyGt(a, correction);
  if (&y != &x) y.assign(x);
  y.update(-1.0, correction, 1.0);
}

std::vector<double> TotalFeti::rigidBodyCoefficients(const DualVector& lambda) const {
  DualVector residual(dualMap_);
  applyF(lambda, residual);
  residual.update(-1.0, *dTilde_, 1.0);
  std::vector<double> alpha;
  applyG(residual, alpha);
  solveCoarse(alpha);
  return alpha;
}

void TotalFeti::applyB(const std::vector<std::vector<double>>& u, DualVector& y) const {
  applyBlockwise(y, y, [&u, this](Local& L, bool) {
    applyBlock(*L.block, u[L.subdomain - firstOwned_].data(), L.out.data());
  });
}

double TotalFeti::equilibriumResidual(const DualVector& lambda, const std::vector<std::vector<double>>& u) const {
  DualVector overlap(overlapMap_);
  overlap.doImport(lambda, *importer_, Tpetra::INSERT);
  const double* lo = readOnly(overlap);
  double worst = 0.0;
  for (size_t i = 0; i < local_.size(); ++i) {
    Local& L = *local_[i];
    for (LO r = 0; r < L.m(); ++r) L.in[r] = lo[L.overlapIndex[r]];
    applyBlockTranspose(*L.block, L.in.data(), L.x.data(), L.n());
    L.system.K.apply(u[i].data(), L.y.data());
    for (LO k = 0; k < L.n(); ++k) worst = std::max(worst, std::abs(L.y[k] - L.system.f[k] + L.x[k]));
  }
  double global = 0.0;
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MAX, 1, &worst, &global);
  return global;
}

double TotalFeti::energy(const std::vector<std::vector<double>>& u) const {
  double local = 0.0;
  for (size_t i = 0; i < local_.size(); ++i) {
    Local& L = *local_[i];
    L.system.K.apply(u[i].data(), L.y.data());
    for (LO k = 0; k < L.n(); ++k) local += 0.5 * u[i][k] * L.y[k] - L.system.f[k] * u[i][k];
  }
  double global = 0.0;
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_SUM, 1, &local, &global);
  return global;
}

double TotalFeti::loadNormInf() const {
  double local = 0.0;
  for (const auto& L : local_)
    for (double v : L->system.f) local = std::max(local, std::abs(v));
  double global = 0.0;
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MAX, 1, &local, &global);
  return global;
}

std::vector<std::vector<double>> TotalFeti::recoverDisplacements(const DualVector& lambda,
                                                                 const std::vector<double>& alpha) const {
  DualVector overlap(overlapMap_);
  overlap.doImport(lambda, *importer_, Tpetra::INSERT);
  const double* lo = readOnly(overlap);
  std::vector<std::vector<double>> u(local_.size());
  core::forEachSubdomain(numOwnedSubdomains(), [&](int i) {
    Local& L = *local_[i];
    const LO n = L.n();
    for (LO r = 0; r < L.m(); ++r) L.in[r] = lo[L.overlapIndex[r]];
    applyBlockTranspose(*L.block, L.in.data(), L.x.data(), n);
    for (LO k = 0; k < n; ++k) L.x[k] = L.system.f[k] - L.x[k];
    u[i].assign(n, 0.0);
    L.solver.applyPseudoInverse(L.x.data(), u[i].data());
    for (LO k = 0; k < n; ++k)
      for (int j = 0; j < 6; ++j) u[i][k] += L.system.R[static_cast<size_t>(j) * n + k] * alpha[6 * L.subdomain + j];
  });
  return u;
}

}  // namespace tribos::feti
