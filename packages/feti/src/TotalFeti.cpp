#include "tribos/feti/TotalFeti.hpp"

#include <Teuchos_DefaultMpiComm.hpp>
#include <Tpetra_Core.hpp>
#include <Tpetra_Import.hpp>
#include <Tpetra_Map.hpp>
#include <Tpetra_Vector.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <map>
#include <numeric>

#include "tribos/core/Deadline.hpp"
#include "tribos/core/Errors.hpp"
#include "tribos/core/Parallel.hpp"
#include "tribos/core/ReproducibleSum.hpp"
#include "tribos/core/Timer.hpp"
#include "tribos/feti/DistributedCoarseSolve.hpp"
#include "tribos/fem/SubdomainSystem.hpp"

namespace tribos::feti {

namespace {
// x = B_s^T lambda_s (x has n entries, zeroed here). A dof in several rows sums them in
// `order` (the rows by their global id, B.rowId): B's own row order follows the number of
// ranks, and with it the rounding of these sums.
void applyBlockTranspose(const SubdomainBlock& b, const std::vector<LO>& order, const double* lambda, double* x,
                         LO n) {
  std::fill(x, x + n, 0.0);
  for (LO i : order)
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

/// One term of B_s: its row (index into the block's rows), its dof (renumbered) and value.
/// A subdomain keeps its terms in the order applyBlockTranspose adds them (rows in `order`,
/// each row's terms in B's order), one array that F and the preconditioners stream through
/// instead of four (row order, row pointers, values and renumbered dofs:
/// doc/measurements/performance.md, "G x and B_s each in one stream").
struct BlockTerm {
  LO row, dof;
  double value;
};
static_assert(sizeof(BlockTerm) == 16, "one term of B_s in 16 bytes");

std::vector<BlockTerm> blockTerms(const SubdomainBlock& b, const std::vector<LO>& order, const std::vector<LO>& dof) {
  std::vector<BlockTerm> terms;
  terms.reserve(b.value.size());
  for (LO i : order)
    for (LO k = b.rowPtr[i]; k < b.rowPtr[i + 1]; ++k) terms.push_back({i, dof[k], b.value[k]});
  return terms;
}

// x = B_s^T lambda_s from the terms: the bits of applyBlockTranspose (same terms, same order).
void scatterTerms(const std::vector<BlockTerm>& terms, const double* lambda, double* x, LO n) {
  std::fill(x, x + n, 0.0);
  for (const BlockTerm& t : terms) x[t.dof] += t.value * lambda[t.row];
}

// out = B_s y from the terms: each row's sum takes its terms in B's order from zero, the bits
// of applyBlock (the rows are visited in another order, each sum by itself).
void gatherTerms(const std::vector<BlockTerm>& terms, const double* y, double* out, LO m) {
  std::fill(out, out + m, 0.0);
  for (const BlockTerm& t : terms) out[t.row] += t.value * y[t.dof];
}

// The explicit F_s (ALGORITHMS.md 3) as the lower triangle of (F + F^T)/2 packed by rows, rows
// and columns in `order` (the block's rows by global id: the same matrix on every rank layout).
// `full`: m x m, column-major, in the block's own row order.
std::vector<double> packLowerInRowOrder(const std::vector<double>& full, const std::vector<LO>& order) {
  const size_t m = order.size();
  std::vector<double> packed;
  packed.reserve(m * (m + 1) / 2);
  for (size_t a = 0; a < m; ++a)
    for (size_t b = 0; b <= a; ++b)
      packed.push_back(0.5 * (full[order[a] * m + order[b]] + full[order[b] * m + order[a]]));
  return packed;
}

// out = F_s in with F_s from packLowerInRowOrder: `in` gathered into `order` (t), row a of the
// triangle read once for both its dot with t (entry a of F t) and its axpy into y (the upper
// triangle's share, F_ba = F_ab), the dot in eight interleaved lanes: a fixed order of every
// sum that the compiler may vectorise. One pass over m(m+1)/2 contiguous values.
void applyPackedLower(const std::vector<double>& packed, const std::vector<LO>& order, const double* in,
                      double* __restrict t, double* __restrict y, double* out) {
  const LO m = static_cast<LO>(order.size());
  for (LO a = 0; a < m; ++a) t[a] = in[order[a]], y[a] = 0.0;
  const double* __restrict row = packed.data();
  for (LO a = 0; a < m; row += a + 1, ++a) {
    const double ta = t[a];
    double lane[8] = {0, 0, 0, 0, 0, 0, 0, 0};
    LO b = 0;
    for (; b + 8 <= a; b += 8)
      for (int k = 0; k < 8; ++k) {
        lane[k] += row[b + k] * t[b + k];
        y[b + k] += row[b + k] * ta;
      }
    for (; b < a; ++b) {
      lane[0] += row[b] * t[b];
      y[b] += row[b] * ta;
    }
    y[a] += (((lane[0] + lane[1]) + (lane[2] + lane[3])) + ((lane[4] + lane[5]) + (lane[6] + lane[7]))) + row[a] * ta;
  }
  for (LO a = 0; a < m; ++a) out[order[a]] = y[a];
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

MPI_Comm rawComm(const Teuchos::Comm<int>& comm) {
  const auto* mpi = dynamic_cast<const Teuchos::MpiComm<int>*>(&comm);
  TEUCHOS_TEST_FOR_EXCEPTION(!mpi, std::logic_error, "tribos::feti: collectives need an MPI communicator");
  return (*mpi->getRawMpiComm())();
}

/// Iterative refinement steps of solveCoarseExactly at most (about 3 at the gate's 1e-3,
/// TotalFetiSettings::singleCoarseGate).
constexpr int kMaxCoarseRefinements = 20;

// Every rank's `mine`, concatenated in rank order (all ranks get the whole list).
std::vector<long long> allGather(const Teuchos::Comm<int>& comm, const std::vector<long long>& mine) {
  const MPI_Comm raw = rawComm(comm);
  const int size = comm.getSize(), count = static_cast<int>(mine.size());
  std::vector<int> counts(size), offsets(size + 1, 0);
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, raw);
  for (int p = 0; p < size; ++p) offsets[p + 1] = offsets[p] + counts[p];
  std::vector<long long> all(offsets[size]);
  MPI_Allgatherv(mine.data(), count, MPI_LONG_LONG, all.data(), counts.data(), offsets.data(), MPI_LONG_LONG, raw);
  return all;
}

const double* readOnly(const DualVector& v) { return v.getLocalViewHost(Tpetra::Access::ReadOnly).data(); }
double* readWrite(DualVector& v) { return v.getLocalViewHost(Tpetra::Access::ReadWrite).data(); }
}  // namespace

/// A block of K in CSR (rows and columns renumbered), kept with K's column order inside each
/// row. Column indices take 2 bytes when the block has at most 65 536 columns (a subdomain's
/// boundary or interior unknowns: always at the H/h of Table 1): 10 bytes per entry instead
/// of 12; the preconditioner reads these blocks once per application (doc/measurements/performance.md).
/// Three products: with the block (rows), with its transpose (K_bi = K_ib^T read from K_ib),
/// and, for a symmetric block stored as its upper triangle (K_bb), with the whole of it.
struct KBlock {
  std::vector<LO> rowPtr, colInd;      ///< colInd: only when the columns need 4 bytes
  std::vector<std::uint16_t> colShort;  ///< otherwise
  std::vector<double> values;
  /// y = A x
  void apply(const double* x, double* y) const {
    withColumns([&](const auto* col) { applyWith(col, x, y); });
  }
  /// y -= A^T x, rows in order: y_j gets its terms in the order of A's rows.
  void subtractTransposed(const double* x, double* y) const {
    withColumns([&](const auto* col) { subtractTransposedWith(col, x, y); });
  }
  /// y = (U + U^T - diag U) x for A = U, the upper triangle of a symmetric matrix with the
  /// diagonal first in each row. Row i's sum gets its terms in ascending column order, as the
  /// row of the whole matrix would: j < i from the rows before (U_ji = A_ij), then its own.
  void applySymmetric(const double* x, double* y) const {
    withColumns([&](const auto* col) { applySymmetricWith(col, x, y); });
  }
  double bytes() const {
    return 8.0 * values.size() + 4.0 * (colInd.size() + rowPtr.size()) + 2.0 * colShort.size();
  }
  LO rows() const { return static_cast<LO>(rowPtr.size()) - 1; }

 private:
  template <class Op>
  void withColumns(Op op) const {
    if (colInd.empty())
      op(colShort.data());
    else
      op(colInd.data());
  }
  template <class Index>
  void applyWith(const Index* __restrict col, const double* __restrict x, double* __restrict y) const {
    const double* __restrict v = values.data();
    const LO* __restrict start = rowPtr.data();
    for (LO i = 0; i < rows(); ++i) {
      double s = 0.0;
      for (LO k = start[i]; k < start[i + 1]; ++k) s += v[k] * x[col[k]];
      y[i] = s;
    }
  }
  template <class Index>
  void subtractTransposedWith(const Index* __restrict col, const double* __restrict x, double* __restrict y) const {
    const double* __restrict v = values.data();
    const LO* __restrict start = rowPtr.data();
    for (LO i = 0; i < rows(); ++i) {
      const double xi = x[i];
      for (LO k = start[i]; k < start[i + 1]; ++k) y[col[k]] -= v[k] * xi;
    }
  }
  template <class Index>
  void applySymmetricWith(const Index* __restrict col, const double* __restrict x, double* __restrict y) const {
    const double* __restrict v = values.data();
    const LO* __restrict start = rowPtr.data();
    const LO n = rows();
    std::fill(y, y + n, 0.0);
    for (LO i = 0; i < n; ++i) {
      const double xi = x[i];
      double s = y[i] + v[start[i]] * xi;  // the lower part's terms so far, then the diagonal
      for (LO k = start[i] + 1; k < start[i + 1]; ++k) {
        s += v[k] * x[col[k]];
        y[col[k]] += v[k] * xi;
      }
      y[i] = s;
    }
  }
};

/// The dual preconditioners' blocks of one subdomain's K, b = the dofs that B touches, i = the
/// others. Lumped, B K B^T = B K_bb B^T (B^T x vanishes off b and B reads b only): K_bb.
/// Dirichlet, S = K_bb - K_bi K_ii^{-1} K_ib: the same K_bb (one copy serves both) and K_ib,
/// read a second time for K_bi = K_ib^T (K_ii is only factorised, so an application reads
/// neither K_ii nor K's other entries), interior unknowns in the order of K_ii's factor. K_bb
/// is kept as its upper triangle: half the bytes, the product exactly symmetric (K's own
/// entries K_ij and K_ji can differ in the last bit, as the element matrices do). Work vectors.
struct DirichletBlocks {
  std::vector<BlockTerm> terms;  ///< B_s with the dofs numbered among b (blockTerms)
  KBlock Kbb;                   ///< upper triangle, diagonal first in each row
  KBlock Kib;                   ///< rows of i in the factor's order (Dirichlet only)
  std::unique_ptr<SparseCholesky> interiorFactor;  ///< K_ii (none when i is empty)
  std::vector<double> xb, yb, t;
};

/// One entry (row r, subdomain s) of G in the geometric basis of s (CoarseRows): g'_{s,r} =
/// c [e_d; e_k x p~] when row r of B_s has the single term c at component d of a node with
/// scaled coordinates p~ = coords[slot] (code = 4 slot + d), else the 6 numbers full[slot]
/// (code = 4 slot + 3; contact rows with several terms). `index`: the row (G^T a) or x's
/// index on the overlap (G x). 16 bytes instead of 6 doubles and an index.
struct CoarseTerm {
  double c;
  std::uint32_t code;
  LO index;
};
static_assert(sizeof(CoarseTerm) == 16, "one entry of G in 16 bytes");

/// One owned subdomain: its system, generalised inverse, rows of B and scratch buffers
/// (allocated before any threaded loop: TOOLCHAIN.md rule 1).
struct TotalFeti::Local {
  int subdomain = 0;
  const SubdomainBlock* block = nullptr;
  std::vector<LO> overlapIndex;  ///< local index in the overlap map of each block row
  std::vector<BlockTerm> factorTerms;  ///< B_s with the dofs in the factor's order (blockTerms)
  std::vector<LO> rowOrder;      ///< the block's rows by ascending global id (B.rowId)
  fem::SubdomainSystem system;
  SubdomainSolver solver;
  std::vector<double> denseF;    ///< explicit F_s when requested (packLowerInRowOrder)
  DirichletBlocks dirichlet;     ///< the Dirichlet preconditioner's blocks of K (when requested)
  std::vector<double> in, out, x, y;
  LO m() const { return static_cast<LO>(block->rows.size()); }
  LO n() const { return system.K.n; }
};

TotalFeti::~TotalFeti() = default;

namespace {
// The rows `rows` and columns with position[col] >= 0 of K, columns renumbered by `position`;
// `upper`: only the columns at or after the row's own position (rows = the columns, ascending).
KBlock extractBlock(const fem::CsrMatrix& K, const std::vector<LO>& rows, const std::vector<LO>& position,
                    bool upper = false) {
  auto keep = [&](size_t row, LO col) { return position[col] >= (upper ? static_cast<LO>(row) : 0); };
  // Counted first, so that the blocks, kept for the whole solve, hold no spare capacity (with
  // push_back growth alone they held up to twice their entries: doc/measurements/scalability.md).
  size_t entries = 0;
  for (size_t r = 0; r < rows.size(); ++r)
    for (LO k = K.rowPtr[rows[r]]; k < K.rowPtr[rows[r] + 1]; ++k) entries += keep(r, K.colInd[k]);
  KBlock A;
  A.rowPtr.reserve(rows.size() + 1);
  A.colInd.reserve(entries);
  A.values.reserve(entries);
  A.rowPtr.push_back(0);
  for (size_t r = 0; r < rows.size(); ++r) {
    const LO i = rows[r];
    for (LO k = K.rowPtr[i]; k < K.rowPtr[i + 1]; ++k)
      if (keep(r, K.colInd[k])) {
        A.colInd.push_back(position[K.colInd[k]]);
        A.values.push_back(K.values[k]);
      }
    A.rowPtr.push_back(static_cast<LO>(A.colInd.size()));
    // applySymmetric takes each row's first entry for its diagonal (K stores every node's
    // diagonal block, so it is there).
    TEUCHOS_TEST_FOR_EXCEPTION(upper && (A.rowPtr[r + 1] == A.rowPtr[r] || A.colInd[A.rowPtr[r]] != static_cast<LO>(r)),
                               std::logic_error, "tribos::feti: K has no diagonal entry in row " << i);
  }
  const LO columns = static_cast<LO>(std::count_if(position.begin(), position.end(), [](LO p) { return p >= 0; }));
  if (columns <= 65536) {
    A.colShort.assign(A.colInd.begin(), A.colInd.end());
    std::vector<LO>().swap(A.colInd);
  }
  return A;
}

// K_bb (both preconditioners) and, for the Dirichlet one (`interiorToo`), K_ii's factor and K_ib.
void buildPreconditionerBlocks(TotalFeti::Local& L, bool interiorToo, Factorization factorization,
                               const SparseCholeskyOptions& options) {
  DirichletBlocks& D = L.dirichlet;
  std::vector<char> touched(L.n(), 0);
  for (LO d : L.block->dof) touched[d] = 1;
  std::vector<LO> boundary, interior;
  for (LO d = 0; d < L.n(); ++d) (touched[d] ? boundary : interior).push_back(d);
  std::vector<LO> boundaryPosition(L.n(), -1);
  for (size_t k = 0; k < boundary.size(); ++k) boundaryPosition[boundary[k]] = static_cast<LO>(k);
  std::vector<LO> boundaryDof;  // per entry of B_s: the position of its dof among b
  for (LO d : L.block->dof) boundaryDof.push_back(boundaryPosition[d]);
  D.terms = blockTerms(*L.block, L.rowOrder, boundaryDof);
  D.Kbb = extractBlock(L.system.K, boundary, boundaryPosition, /*upper=*/true);
  D.xb.assign(boundary.size(), 0.0);
  D.yb.assign(boundary.size(), 0.0);
  if (!interiorToo || interior.empty()) return;
  D.interiorFactor = makeSparseCholesky(factorization, options);
  D.interiorFactor->factorize(principalSubmatrix(L.system.K, interior));
  // Interior unknowns in the factor's order: K_ib's rows follow it, so the solve runs in place.
  const std::vector<LO>& perm = D.interiorFactor->permutation();
  std::vector<LO> interiorOrdered(interior.size());
  for (size_t k = 0; k < interior.size(); ++k) interiorOrdered[k] = interior[perm[k]];
  D.Kib = extractBlock(L.system.K, interiorOrdered, boundaryPosition);
  D.t.assign(interior.size(), 0.0);
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
  // rows that touch this rank's subdomains, both in B's row order. Their global ids are
  // B.rowId, the numbering of one rank: the same id for the same row on any number of ranks.
  const GO myFirst = B.firstRowOfRank[rank], myEnd = B.firstRowOfRank[rank + 1];
  std::vector<GO> ids;
  for (GO r = myFirst; r < myEnd; ++r) ids.push_back(rowId(r));
  dualMap_ = Teuchos::rcp(new DualMap(B.numRows, Teuchos::ArrayView<const GO>(ids.data(), ids.size()), 0, comm));
  std::vector<GO> overlapRows;
  for (int i = 0; i < numOwned; ++i) {
    const auto& rows = B.blocks[firstOwned_ + i].rows;
    overlapRows.insert(overlapRows.end(), rows.begin(), rows.end());
  }
  std::sort(overlapRows.begin(), overlapRows.end());
  overlapRows.erase(std::unique(overlapRows.begin(), overlapRows.end()), overlapRows.end());
  ids.clear();
  for (GO r : overlapRows) ids.push_back(rowId(r));
  overlapMap_ = Teuchos::rcp(new DualMap(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                                         Teuchos::ArrayView<const GO>(ids.data(), ids.size()), 0, comm));
  importer_ = Teuchos::rcp(new Tpetra::Import<LO, GO>(dualMap_, overlapMap_));
  overlapIsOwned_ = overlapMap_->isSameAs(*dualMap_);
  xOverlap_ = Teuchos::rcp(new DualVector(overlapMap_));

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

  // (3) Owned subdomains: factorise K_reg on threads.
  local_.resize(numOwned);
  for (int i = 0; i < numOwned; ++i) {
    auto L = std::make_unique<Local>();
    L->subdomain = firstOwned_ + i;
    L->block = &B.blocks[L->subdomain];
    L->system = std::move(owned[i]);
    L->system.R = std::move(R[i]);
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
  {
    long long mine = 0;
    for (const auto& L : local_) mine += L->n();
    Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, 1, &mine, &primalDofs_);
  }
  core::Stopwatch watch;
  std::atomic<bool> stopped{false};  // Solver/Max Seconds passed on this rank: the rest skipped
  core::forEachSubdomain(numOwned, [&](int i) {
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
    if (settings_.explicitF) {
      // F_s = B_s K^dagger B_s^T, column by column of B_s^T (ALGORITHMS.md 3, explicit F).
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
  });
  if (settings_.deadline) settings_.deadline->agree(stopped, "the factorisation", rawComm(*comm));
  double seconds = watch.seconds();
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, 1, &seconds, &factorizationSeconds_);

  // (4) G on the owned rows; G G^T assembled and factorised once, on rank 0.
  buildCoarseRows(mesh, decomposition);
  buildCoarsePattern();
  measureTraffic();  // before factorizeCoarse: "Auto" compares the coarse solve with it
  factorizeCoarse();
  if (settings_.deadline) settings_.deadline->check("the coarse problem", rawComm(*comm));
  settings_.deadline = nullptr;  // the caller's: not kept beyond the set-up

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
  solveCoarseExactly(a);  // G lambda_Im = e to double precision
  applyGt(a, *lambdaIm_);
}

/// G on this rank's owned rows of B: one entry = one row r and one subdomain s it touches.
/// Stored compactly (issue 9): R_s = R~_s M_s, with R~_s the geometric rigid modes of s
/// (translations e_d and rotations e_k x p~ at the scaled node coordinates p~ = (x - centre_s)
/// / scale_s, fem::rigidBodyModes before its Gram-Schmidt) and M_s (6 x 6) the change of
/// basis, so g_{s,r} = R_s^T b_{s,r}^T = M_s^T g'_{s,r} with g'_{s,r} = R~_s^T b_{s,r}^T. A
/// row of B_s with one term c at (node, d) has g'_{s,r} = c [e_d; (e_k x p~)_d]: a
/// CoarseTerm of 16 bytes (c, slot of p~ and d, row) instead of 6 doubles and an index; the
/// others (contact rows with several terms) keep their 6 numbers g' in `full`. G x applies
/// M_s^T once per subdomain to the sum of g' x_r, G^T a multiplies each g' by M_s a_s: the
/// same G in exact arithmetic, hence the same projector, e, alpha and G G^T; only the
/// rounding changes (doc/measurements/coarse_problem.md).
/// Threads work on fixed chunks of kRowChunk rows; inside a chunk the entries are stored by
/// subdomain ("runs"), then by kind (one loop without branches per kind), then by row, so
/// that G^T a adds each entry's g_{s,r} . a_s into its row's sum in a chunk-sized buffer,
/// runs in ascending subdomain order: every row sums its entries in ascending subdomain
/// order (the rows of one run are distinct, so there is no chain of dependent updates). G x
/// is summed by subdomain instead (ownedTerm, applyGOwnedSubdomains): a subdomain's rows are
/// owned by different ranks on different layouts, its owner has them all (its own block) and
/// reads the same coordinate slots.
/// The by-row view (rowStart, rowSubdomain, rowEntry) serves the set-up (G G^T).
struct TotalFeti::CoarseRows {
  GO firstRow = 0;
  LO numRows = 0;
  std::vector<LO> rowStart;       ///< numRows + 1; a row's entries in ascending subdomain order
  std::vector<int> rowSubdomain;  ///< per entry in row order
  std::vector<LO> rowEntry;       ///< per entry in row order: its index in the stored order
  // Stored order: chunk, subdomain, kind (d = 0, 1, 2, full), row.
  std::vector<CoarseTerm> term;   ///< per entry (index: the owned row)
  std::vector<double> coords;     ///< 3 per slot: p~ of a (subdomain, node) that a term reads
  std::vector<double> full;       ///< 6 per slot: g' of an entry with several terms
  std::vector<double> basis;      ///< M_s, 36 per subdomain (row-major: R_s = R~_s M_s)
  std::vector<LO> runStart;       ///< per run + 1: its entries
  std::vector<LO> runGroupStart;  ///< 4 per run + 1: the entries of kind g of run j from 4 j + g
  std::vector<int> runSubdomain;  ///< per run
  std::vector<int> chunkRunStart;  ///< per chunk + 1: its runs
  mutable std::vector<double> rowSum;  ///< numRows: G^T a's sums, each chunk its own rows
  /// G x's terms of the owned subdomains (index: x's index on the overlap; every row of the
  /// subdomain's own block, whichever rank owns the row), one subdomain after the other in
  /// one array, and per owned subdomain its id and where its kinds start
  /// (ownedStart[6 i .. 6 i + 4] into ownedTerm, ownedStart[6 i + 5] = s): G x streams
  /// through two arrays instead of starting a new allocation at every subdomain
  /// (doc/measurements/performance.md, "G x and B_s each in one stream").
  std::vector<CoarseTerm> ownedTerm;
  std::vector<LO> ownedStart;
  int numChunks() const { return static_cast<int>(chunkRunStart.size()) - 1; }
  const double* M(int s) const { return &basis[36 * static_cast<size_t>(s)]; }
  /// g'_{s,r} of a term (the geometric basis).
  void geometric(const CoarseTerm& t, double* g) const;
  /// g_{s,r} = M_s^T g'_{s,r} of the entry `rowOrderEntry` (row view), for G G^T.
  void rowG(LO rowOrderEntry, double* g) const;
};

namespace {
/// Rows per task of the row loops (G^T a, the sums of applyBlockwise): fixed, so that the
/// work split does not depend on the number of threads.
constexpr LO kRowChunk = 8192;
/// Subdomains per task of G x (applyGOwnedSubdomains).
constexpr int kGxSubdomains = 8;
/// Slots per entry of the reproducible sums of G G^T.
constexpr int kSlots = core::SumBins::kSlices;
/// A subdomain's frame as it travels: centre (3), scale, M_s (36).
constexpr int kFrame = 40;

/// Row d of the geometric modes at the scaled point p: [e_d; (e_0 x p)_d, (e_1 x p)_d,
/// (e_2 x p)_d] (fem::rigidBodyModes' order, before orthonormalisation).
void geometricRow(int d, const double* p, double* v) {
  for (int j = 0; j < 3; ++j) v[j] = j == d ? 1.0 : 0.0;
  const double rotation[3][3] = {{0.0, p[2], -p[1]}, {-p[2], 0.0, p[0]}, {p[1], -p[0], 0.0}};
  for (int k = 0; k < 3; ++k) v[3 + k] = rotation[d][k];
}

/// p~ = (x - centre) / scale: one function, so that every rank computes the same bits.
void scaledPoint(const double* frame, const std::array<double, 3>& x, double* p) {
  for (int j = 0; j < 3; ++j) p[j] = (x[j] - frame[j]) / frame[3];
}

/// The frame of a subdomain from its nodes and R (6 columns of n = 3 nodes): centroid, rms
/// radius (the scaled coordinates are O(1), so that R~ is well conditioned), and M with
/// R = R~ M, by the normal equations (R~^T R~) M = R~^T R (R lies in the span of R~ to
/// round-off; R~^T R~ is 6 x 6 and well conditioned after the scaling).
void subdomainFrame(const mesh::Mesh& mesh, const std::vector<LO>& nodes, const std::vector<double>& R, double* frame) {
  const size_t count = nodes.size(), n = 3 * count;
  for (int j = 0; j < 4; ++j) frame[j] = 0.0;
  for (LO node : nodes)
    for (int j = 0; j < 3; ++j) frame[j] += mesh.coords[node][j] / static_cast<double>(count);
  double sum = 0.0;
  for (LO node : nodes)
    for (int j = 0; j < 3; ++j) sum += std::pow(mesh.coords[node][j] - frame[j], 2);
  frame[3] = sum > 0.0 ? std::sqrt(sum / static_cast<double>(count)) : 1.0;
  double A[36] = {}, C[36] = {}, v[6], p[3];
  for (size_t k = 0; k < count; ++k) {
    scaledPoint(frame, mesh.coords[nodes[k]], p);
    for (int d = 0; d < 3; ++d) {
      geometricRow(d, p, v);
      for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 6; ++j) {
          A[6 * i + j] += v[i] * v[j];
          C[6 * i + j] += v[i] * R[j * n + 3 * k + d];
        }
    }
  }
  // Cholesky A = L L^T (lower, in place), then M = L^-T L^-1 C column by column.
  for (int j = 0; j < 6; ++j) {
    for (int k = 0; k < j; ++k) A[6 * j + j] -= A[6 * j + k] * A[6 * j + k];
    A[6 * j + j] = std::sqrt(A[6 * j + j]);
    for (int i = j + 1; i < 6; ++i) {
      for (int k = 0; k < j; ++k) A[6 * i + j] -= A[6 * i + k] * A[6 * j + k];
      A[6 * i + j] /= A[6 * j + j];
    }
  }
  double* M = frame + 4;
  for (int c = 0; c < 6; ++c) {
    double y[6];
    for (int i = 0; i < 6; ++i) {
      y[i] = C[6 * i + c];
      for (int k = 0; k < i; ++k) y[i] -= A[6 * i + k] * y[k];
      y[i] /= A[6 * i + i];
    }
    for (int i = 5; i >= 0; --i) {
      for (int k = i + 1; k < 6; ++k) y[i] -= A[6 * k + i] * y[k];
      y[i] /= A[6 * i + i];
    }
    for (int i = 0; i < 6; ++i) M[6 * i + c] = y[i];
  }
}

/// The kind of row i of block b: its component d when it has one term, else 3.
int termKind(const SubdomainBlock& b, LO i) { return b.rowPtr[i + 1] - b.rowPtr[i] == 1 ? b.dof[b.rowPtr[i]] % 3 : 3; }

/// y = M^T x (6 x 6, row-major M).
void transposedProduct(const double* M, const double* x, double* y) {
  for (int j = 0; j < 6; ++j) {
    double s = 0.0;
    for (int i = 0; i < 6; ++i) s += M[6 * i + j] * x[i];
    y[j] = s;
  }
}
}  // namespace

void TotalFeti::CoarseRows::geometric(const CoarseTerm& t, double* g) const {
  const size_t slot = t.code >> 2;
  const int d = static_cast<int>(t.code & 3u);
  if (d == 3) {
    std::copy(&full[6 * slot], &full[6 * slot] + 6, g);
    return;
  }
  geometricRow(d, &coords[3 * slot], g);
  for (int j = 0; j < 6; ++j) g[j] *= t.c;
}

void TotalFeti::CoarseRows::rowG(LO rowOrderEntry, double* g) const {
  double geo[6];
  geometric(term[rowEntry[rowOrderEntry]], geo);
  transposedProduct(M(rowSubdomain[rowOrderEntry]), geo, g);
}

/// Builds the CoarseTerm of rows of blocks from their `data` (6 numbers, entrySource):
/// p~ of the node of a one-term row, g' of the others. One coordinate slot per (subdomain,
/// local node) and one full slot per (subdomain, row) of the rank (G x and G^T a share them).
class TotalFeti::CoarseTermBuilder {
 public:
  explicit CoarseTermBuilder(CoarseRows& G) : G_(G) {}
  /// The term of row i of block b (subdomain s); index left to the caller.
  CoarseTerm operator()(int s, const SubdomainBlock& b, LO i, const double* data) {
    const LO first = b.rowPtr[i];
    if (b.rowPtr[i + 1] - first == 1) {
      const LO dof = b.dof[first];
      const auto key = std::make_pair(s, dof / 3);
      auto it = coordSlot_.find(key);
      if (it == coordSlot_.end()) {
        it = coordSlot_.emplace(key, static_cast<std::uint32_t>(G_.coords.size() / 3)).first;
        G_.coords.insert(G_.coords.end(), data, data + 3);
      }
      return {b.value[first], code(it->second, dof % 3), 0};
    }
    const auto key = std::make_pair(s, b.rows[i]);
    auto it = fullSlot_.find(key);
    if (it == fullSlot_.end()) {
      it = fullSlot_.emplace(key, static_cast<std::uint32_t>(G_.full.size() / 6)).first;
      G_.full.insert(G_.full.end(), data, data + 6);
    }
    return {0.0, code(it->second, 3), 0};
  }

 private:
  static std::uint32_t code(std::uint32_t slot, int d) {
    TEUCHOS_TEST_FOR_EXCEPTION(slot >= (1u << 30), std::length_error, "tribos::feti: too many coarse slots on a rank");
    return 4 * slot + static_cast<std::uint32_t>(d);
  }
  CoarseRows& G_;
  std::map<std::pair<int, LO>, std::uint32_t> coordSlot_;
  std::map<std::pair<int, GO>, std::uint32_t> fullSlot_;
};

void TotalFeti::buildCoarseRows(const mesh::Mesh& mesh, const mesh::Decomposition& decomposition) {
  // Entry (s, r) = row r of B in block s, global id r * numSubdomains + s: the same id on every
  // rank without any rank knowing the sizes of the blocks it does not own. Source: the entries
  // of the owned subdomains; target: the entries of the owned rows (the rank has those rows of
  // every block, feti::keepRankRows). One import of 6 numbers per entry (the data of its
  // CoarseTerm, below), also applyBlockwise's entry-wise sums (several ranks); M_s travels
  // by one all-reduce of 40 numbers per subdomain.
  const int rank = comm_->getRank();
  const GO S = numSubdomains_;
  std::vector<GO> ids;
  for (const auto& L : local_)
    for (GO row : L->block->rows) ids.push_back(row * S + L->subdomain);
  const auto invalid = Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid();
  auto source = Teuchos::rcp(new DualMap(invalid, Teuchos::ArrayView<const GO>(ids.data(), ids.size()), 0, comm_));
  std::vector<LO> firstSource(numOwnedSubdomains() + 1, 0);  // first source entry of each owned subdomain
  for (int i = 0; i < numOwnedSubdomains(); ++i) firstSource[i + 1] = firstSource[i] + local_[i]->m();

  // The frames (centre, scale, M_s) of the owned subdomains, by their owner (which has R_s);
  // -0.0 made +0.0 so that the sum with the other ranks' zeros keeps every bit.
  std::vector<double> frames(kFrame * static_cast<size_t>(S), 0.0);
  core::forEachSubdomain(numOwnedSubdomains(), [&](int i) {
    const Local& L = *local_[i];
    double* frame = &frames[kFrame * static_cast<size_t>(L.subdomain)];
    subdomainFrame(mesh, decomposition.subdomains[L.subdomain].nodes, L.system.R, frame);
    for (int j = 0; j < kFrame; ++j) frame[j] += 0.0;
  });
  // The data of each entry of the owned subdomains, by their owner (the only rank that has
  // their nodes, stack::keepRankData): p~ of the node of a one-term row (3 numbers), g' of
  // the others (6), travelling to the owners of the rows as g did before.
  Tpetra::MultiVector<Scalar, LO, GO> dataSource(source, 6);
  {
    auto data = dataSource.getLocalViewHost(Tpetra::Access::OverwriteAll);
    core::forEachSubdomain(numOwnedSubdomains(), [&](int i) {
      const Local& L = *local_[i];
      const SubdomainBlock& b = *L.block;
      const double* frame = &frames[kFrame * static_cast<size_t>(L.subdomain)];
      const auto& nodes = decomposition.subdomains[L.subdomain].nodes;
      for (LO r = 0; r < L.m(); ++r) {
        double g[6] = {}, v[6], p[3];
        if (b.rowPtr[r + 1] - b.rowPtr[r] == 1) {
          scaledPoint(frame, mesh.coords[nodes[b.dof[b.rowPtr[r]] / 3]], g);
        } else {
          for (LO k = b.rowPtr[r]; k < b.rowPtr[r + 1]; ++k) {  // the terms in B's order
            scaledPoint(frame, mesh.coords[nodes[b.dof[k] / 3]], p);
            geometricRow(b.dof[k] % 3, p, v);
            for (int j = 0; j < 6; ++j) g[j] += b.value[k] * v[j];
          }
        }
        for (int j = 0; j < 6; ++j) data(firstSource[i] + r, j) = g[j];
      }
    });
  }
  if (comm_->getSize() > 1) {
    std::vector<double> mine = frames;
    Teuchos::reduceAll(*comm_, Teuchos::REDUCE_SUM, static_cast<int>(frames.size()), mine.data(), frames.data());
  }

  // Target: the entries of the owned rows, ordered by row, then subdomain (ascending: the
  // order in which G G^T has always summed them).
  auto G = std::make_unique<CoarseRows>();
  G->firstRow = B_.firstRowOfRank[rank];
  G->numRows = static_cast<LO>(B_.firstRowOfRank[rank + 1] - G->firstRow);
  struct Entry {
    LO row;
    int subdomain;
    LO blockRow;  ///< its row in B_s
    int kind;     ///< component d of a one-term row, 3 for several terms
  };
  std::vector<Entry> entries;
  for (int s = 0; s < numSubdomains_; ++s) {
    const auto& rows = B_.blocks[s].rows;
    const auto lo = std::lower_bound(rows.begin(), rows.end(), G->firstRow);
    for (auto it = lo; it != rows.end() && *it < G->firstRow + G->numRows; ++it)
      entries.push_back({static_cast<LO>(*it - G->firstRow), s, static_cast<LO>(it - rows.begin()),
                         termKind(B_.blocks[s], static_cast<LO>(it - rows.begin()))});
  }
  std::stable_sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) { return a.row < b.row; });
  ids.resize(entries.size());
  for (size_t e = 0; e < entries.size(); ++e) ids[e] = (G->firstRow + entries[e].row) * S + entries[e].subdomain;
  auto target = Teuchos::rcp(new DualMap(invalid, Teuchos::ArrayView<const GO>(ids.data(), ids.size()), 0, comm_));
  auto entryImport = Teuchos::rcp(new Tpetra::Import<LO, GO>(source, target));
  Tpetra::MultiVector<Scalar, LO, GO> dataTarget(target, 6);
  dataTarget.doImport(dataSource, *entryImport, Tpetra::INSERT);
  if (!overlapIsOwned_) {  // applyBlockwise's entry-wise sums (several ranks)
    entryImport_ = entryImport;
    entrySource_ = Teuchos::rcp(new DualVector(source));
    entryTarget_ = Teuchos::rcp(new DualVector(target));
    entrySourceFirst_ = firstSource;
  }

  G->rowStart.assign(G->numRows + 1, 0);
  G->rowSubdomain.resize(entries.size());
  for (size_t e = 0; e < entries.size(); ++e) {
    ++G->rowStart[entries[e].row + 1];
    G->rowSubdomain[e] = entries[e].subdomain;
  }
  for (LO r = 0; r < G->numRows; ++r) G->rowStart[r + 1] += G->rowStart[r];
  // The stored order: by chunk, then subdomain, then kind, then row (entries are in row order:
  // a stable sort by (chunk, subdomain, kind) keeps the rows ascending within a kind).
  std::vector<LO> order(entries.size());
  for (size_t e = 0; e < order.size(); ++e) order[e] = static_cast<LO>(e);
  std::stable_sort(order.begin(), order.end(), [&](LO a, LO b) {
    const LO ca = entries[a].row / kRowChunk, cb = entries[b].row / kRowChunk;
    if (ca != cb) return ca < cb;
    if (entries[a].subdomain != entries[b].subdomain) return entries[a].subdomain < entries[b].subdomain;
    return entries[a].kind < entries[b].kind;
  });
  G->rowEntry.resize(entries.size());
  G->term.resize(entries.size());
  CoarseTermBuilder termOf(*G);
  auto targetData = dataTarget.getLocalViewHost(Tpetra::Access::ReadOnly);
  auto sourceData = dataSource.getLocalViewHost(Tpetra::Access::ReadOnly);
  auto dataOf = [](const auto& view, LO e, double* out) {
    for (int j = 0; j < 6; ++j) out[j] = view(e, j);
  };
  double data[6];
  const LO numChunks = (G->numRows + kRowChunk - 1) / kRowChunk;
  G->chunkRunStart.assign(numChunks + 1, 0);  // runs per chunk, then their prefix sums
  for (size_t k = 0; k < order.size(); ++k) {
    const Entry& entry = entries[order[k]];
    G->rowEntry[order[k]] = static_cast<LO>(k);
    dataOf(targetData, order[k], data);
    G->term[k] = termOf(entry.subdomain, B_.blocks[entry.subdomain], entry.blockRow, data);
    G->term[k].index = entry.row;
    const LO chunk = entry.row / kRowChunk;
    if (k == 0 || chunk != entries[order[k - 1]].row / kRowChunk || entry.subdomain != entries[order[k - 1]].subdomain) {
      G->runStart.push_back(static_cast<LO>(k));
      G->runSubdomain.push_back(entry.subdomain);
      ++G->chunkRunStart[chunk + 1];
    }
  }
  G->runStart.push_back(static_cast<LO>(order.size()));
  for (LO c = 0; c < numChunks; ++c) G->chunkRunStart[c + 1] += G->chunkRunStart[c];
  const size_t numRuns = G->runSubdomain.size();
  G->runGroupStart.assign(4 * numRuns + 1, static_cast<LO>(order.size()));
  for (size_t j = 0; j < numRuns; ++j)
    for (int kind = 0; kind < 4; ++kind) {
      LO e = G->runStart[j];
      while (e < G->runStart[j + 1] && entries[order[e]].kind < kind) ++e;
      G->runGroupStart[4 * j + kind] = e;
    }
  G->rowSum.assign(G->numRows, 0.0);
  // G x of the owned subdomains: their own blocks, every row (the same slots where shared);
  // by kind (component d = 0, 1, 2 of one-term rows, then the full entries), in rowOrder
  // within a kind.
  G->ownedTerm.clear();
  G->ownedStart.clear();
  for (int i = 0; i < numOwnedSubdomains(); ++i) {
    const Local& L = *local_[i];
    for (int kind = 0; kind < 4; ++kind) {
      G->ownedStart.push_back(static_cast<LO>(G->ownedTerm.size()));
      for (LO r : L.rowOrder) {
        if (termKind(*L.block, r) != kind) continue;
        dataOf(sourceData, firstSource[i] + r, data);
        G->ownedTerm.push_back(termOf(L.subdomain, *L.block, r, data));
        G->ownedTerm.back().index = L.overlapIndex[r];
      }
    }
    G->ownedStart.push_back(static_cast<LO>(G->ownedTerm.size()));
    G->ownedStart.push_back(L.subdomain);
  }
  G->ownedTerm.shrink_to_fit();
  G->basis.resize(36 * static_cast<size_t>(S));
  for (GO s = 0; s < S; ++s)
    std::copy(frames.data() + kFrame * s + 4, frames.data() + kFrame * (s + 1), G->basis.data() + 36 * s);
  G->coords.shrink_to_fit();
  G->full.shrink_to_fit();

  // The bound of every term of G G^T (core::SumBins): the same on every layout.
  double gMax = 0.0, g[6];
  for (size_t e = 0; e < entries.size(); ++e) {
    G->rowG(static_cast<LO>(e), g);
    for (double v : g) gMax = std::max(gMax, std::abs(v));
  }
  gMax_ = core::globalMax(comm_.get(), gMax);
  profile_.gEntries = static_cast<long long>(G->rowSubdomain.size());
  profile_.gRows = G->numRows;
  G_ = std::move(G);
  coarseLocal_.assign(numCoarse(), 0.0);
  coarseVector_.assign(numCoarse(), 0.0);
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

void TotalFeti::buildCoarsePattern() {
  // Block (s, t) of G G^T is present when a row of B touches both s and t. Every row is owned
  // by one rank, which holds all its entries g_{s,r} (buildCoarseRows): the pairs of its owned
  // rows, gathered from every rank, are the whole pattern. The gathered lists are as long as
  // the pattern itself (which every rank holds in any case), not as long as B.
  const CoarseRows& G = *G_;
  std::vector<long long> pairs;  // s * numSubdomains + t, sorted and unique
  for (LO r = 0; r < G.numRows; ++r)
    for (LO e = G.rowStart[r]; e < G.rowStart[r + 1]; ++e)
      for (LO f = G.rowStart[r]; f < G.rowStart[r + 1]; ++f)
        pairs.push_back(static_cast<long long>(G.rowSubdomain[e]) * numSubdomains_ + G.rowSubdomain[f]);
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  if (comm_->getSize() > 1) pairs = allGather(*comm_, pairs);
  std::vector<std::vector<int>> neighbours(numSubdomains_);
  for (long long key : pairs) neighbours[key / numSubdomains_].push_back(static_cast<int>(key % numSubdomains_));
  pairs.clear();
  pairs.shrink_to_fit();
  coarseBlockStart_.assign(numSubdomains_ + 1, 0);  // first block of block row s
  coarseNeighbours_.clear();
  for (int s = 0; s < numSubdomains_; ++s) {
    auto& t = neighbours[s];
    std::sort(t.begin(), t.end());
    t.erase(std::unique(t.begin(), t.end()), t.end());
    coarseBlockStart_[s + 1] = coarseBlockStart_[s] + static_cast<LO>(t.size());
    coarseNeighbours_.insert(coarseNeighbours_.end(), t.begin(), t.end());
  }
}

fem::CsrMatrix TotalFeti::assembleCoarse(const std::vector<char>* ownedRowMask) const {
  // (G G^T)_{st} = sum over rows r touching both s and t of g_{s,r} g_{t,r}^T: 6x6 blocks
  // for subdomains that share a row of B (buildCoarsePattern; with a mask the same pattern,
  // the blocks of the rows left out stay zero). Each rank adds the products of its owned
  // rows into the blocks they touch, in row order; rank 0 adds every rank's blocks into the
  // whole pattern and builds the matrix, which only it factorises. No rank but 0 holds an
  // array the size of the pattern (at 4 000 subdomains 62 MB of slots and a 47 MB matrix,
  // which were the transient peak of every rank on 16 ranks, doc/measurements/scalability.md).
  auto counted = [&](LO ownedRow) { return !ownedRowMask || (*ownedRowMask)[ownedRow]; };
  const std::vector<LO>& blockStart = coarseBlockStart_;
  auto blockOf = [&](int s, int t) {
    const auto first = coarseNeighbours_.begin() + blockStart[s], last = coarseNeighbours_.begin() + blockStart[s + 1];
    return blockStart[s] + static_cast<LO>(std::lower_bound(first, last, t) - first);
  };
  const CoarseRows& G = *G_;
  // Only the blocks (s, t) with s <= t are summed: (t, s) is (s, t)^T, the same products
  // (g_t[c] g_s[a] = g_s[a] g_t[c] exactly) in the same exact slot sums, so the matrix below
  // reads them transposed with the bits of summing them itself. Each row's g_{s,r} are
  // decoded once (rowG) for all its pairs.
  const LO numBlocks = blockStart[numSubdomains_];
  std::vector<LO> slotOf(static_cast<size_t>(numBlocks), -1);  // block -> its index among `touched`
  std::vector<LO> touched;  // the upper blocks of this rank's counted rows, ascending
  for (LO r = 0; r < G.numRows; ++r) {
    if (!counted(r)) continue;
    for (LO e = G.rowStart[r]; e < G.rowStart[r + 1]; ++e)
      for (LO f = G.rowStart[r]; f < G.rowStart[r + 1]; ++f)
        if (G.rowSubdomain[e] <= G.rowSubdomain[f]) slotOf[blockOf(G.rowSubdomain[e], G.rowSubdomain[f])] = 0;
  }
  for (LO k = 0; k < numBlocks; ++k)
    if (slotOf[k] == 0) {
      slotOf[k] = static_cast<LO>(touched.size());
      touched.push_back(k);
    }

  // Reproducible sums (core::SumBins): the rows of a block are owned by different ranks on
  // different layouts. |g_s[a] g_t[c]| <= gMax^2; at most one term per row of B. The slots
  // hold exact sums, so rank 0 may add the ranks' slots in any order.
  const core::SumBins bins(gMax_ * gMax_, static_cast<long long>(B_.numRows));
  constexpr size_t kBlock = kSlots * 36;
  std::vector<double> local(kBlock * touched.size(), 0.0);
  std::vector<double> g;  // the row's g_{s,r}, 6 per entry
  for (LO r = 0; r < G.numRows; ++r) {
    if (!counted(r)) continue;
    const LO first = G.rowStart[r], entries = G.rowStart[r + 1] - first;
    g.resize(6 * static_cast<size_t>(entries));
    for (LO e = 0; e < entries; ++e) G.rowG(first + e, &g[6 * static_cast<size_t>(e)]);
    for (LO e = 0; e < entries; ++e)
      for (LO f = 0; f < entries; ++f) {
        const int s = G.rowSubdomain[first + e], t = G.rowSubdomain[first + f];
        if (s > t) continue;
        double* block = &local[kBlock * static_cast<size_t>(slotOf[blockOf(s, t)])];
        const double* gs = &g[6 * static_cast<size_t>(e)];
        const double* gt = &g[6 * static_cast<size_t>(f)];
        for (int a = 0; a < 6; ++a)
          for (int c = 0; c < 6; ++c) bins.deposit(gs[a] * gt[c], block + kSlots * (a * 6 + c));
      }
  }
  std::vector<LO>().swap(slotOf);
  std::vector<double> slots;  // rank 0: the whole pattern's (upper blocks filled)
  addBlocksOnRoot(touched, local, slots);
  fem::CsrMatrix GGt;
  if (comm_->getRank() != 0) return GGt;

  // Each value combined from its slots straight into the matrix (no array of the blocks in
  // between).
  GGt.n = numCoarse();
  GGt.rowPtr.assign(GGt.n + 1, 0);
  GGt.colInd.reserve(slots.size() / kSlots);
  GGt.values.reserve(slots.size() / kSlots);
  for (int s = 0; s < numSubdomains_; ++s)
    for (int a = 0; a < 6; ++a) {
      for (LO k = blockStart[s]; k < blockStart[s + 1]; ++k) {
        const int t = coarseNeighbours_[k];
        // (s, t) below the diagonal: entry (c, a) of the upper block (t, s).
        const LO stored = s <= t ? k : blockOf(t, s);
        for (int c = 0; c < 6; ++c) {
          const int entry = s <= t ? a * 6 + c : c * 6 + a;
          GGt.colInd.push_back(6 * t + c);
          GGt.values.push_back(core::SumBins::combine(&slots[kSlots * (36 * static_cast<size_t>(stored) + entry)]));
        }
      }
      GGt.rowPtr[6 * s + a + 1] = static_cast<LO>(GGt.colInd.size());
    }
  return GGt;
}

void TotalFeti::addBlocksOnRoot(const std::vector<LO>& blocks, std::vector<double>& values,
                                std::vector<double>& sum) const {
  // Rank 0 receives the ranks' blocks one rank at a time (its transient: one rank's share, not
  // all of them at once) and adds them to its own.
  constexpr size_t kBlock = kSlots * 36;
  auto add = [&](const LO* which, size_t count, const double* v) {
    for (size_t i = 0; i < count; ++i)
      for (size_t j = 0; j < kBlock; ++j) sum[kBlock * static_cast<size_t>(which[i]) + j] += v[kBlock * i + j];
  };
  const int rank = comm_->getRank(), size = comm_->getSize();
  if (rank == 0) {
    sum.assign(kBlock * static_cast<size_t>(coarseBlockStart_.back()), 0.0);
    add(blocks.data(), blocks.size(), values.data());
    std::vector<double>().swap(values);
  }
  if (size == 1) return;
  const MPI_Comm raw = rawComm(*comm_);
  if (rank != 0) {
    int count = static_cast<int>(blocks.size());
    MPI_Send(&count, 1, MPI_INT, 0, 0, raw);
    MPI_Send(blocks.data(), count, MPI_INT, 0, 1, raw);
    // Block by block bounds the int count of one message (kBlock doubles each).
    for (int i = 0; i < count; i += 1 << 20) {
      const int n = std::min(count - i, 1 << 20);
      MPI_Send(values.data() + kBlock * static_cast<size_t>(i), n * static_cast<int>(kBlock), MPI_DOUBLE, 0, 2, raw);
    }
    return;
  }
  std::vector<LO> theirs;
  std::vector<double> theirValues;
  for (int from = 1; from < size; ++from) {
    int count = 0;
    MPI_Recv(&count, 1, MPI_INT, from, 0, raw, MPI_STATUS_IGNORE);
    theirs.resize(static_cast<size_t>(count));
    theirValues.resize(kBlock * static_cast<size_t>(count));
    MPI_Recv(theirs.data(), count, MPI_INT, from, 1, raw, MPI_STATUS_IGNORE);
    for (int i = 0; i < count; i += 1 << 20) {
      const int n = std::min(count - i, 1 << 20);
      MPI_Recv(theirValues.data() + kBlock * static_cast<size_t>(i), n * static_cast<int>(kBlock), MPI_DOUBLE, from, 2,
               raw, MPI_STATUS_IGNORE);
    }
    add(theirs.data(), theirs.size(), theirValues.data());
  }
}

void TotalFeti::factorizeCoarse() const {
  // G G^T is assembled on rank 0 from every rank's blocks and factorised there
  // (onRootThenBroadcast): its assembled matrix lives only as long as the factorisation.
  core::Stopwatch watch;
  fem::CsrMatrix GGt = assembleCoarse(nullptr);
  // Rounded to single (1), the gate's error, and two coarse solves' bytes over those of F's
  // subdomain solves (with the double factor).
  std::vector<double> single(3, 0.0);
  onRootThenBroadcast(
      single,
      [&] {
        auto factor = makeSparseCholesky(settings_.factorization, settings_.factorOptions);
        factor->setSubtreeSolve(true);  // solved on the main thread of rank 0
        try {
          factor->factorizeConsuming(std::move(GGt));
        } catch (const std::exception& e) {
          throw core::InputError(std::string("the constraints do not fix every rigid body mode of every subdomain "
                                             "(G G^T is singular: ") +
                                 e.what() + "); check Boundary/Dirichlet Node Sets and the contact surfaces");
        }
        coarse_ = std::move(factor);
        profile_.coarseFactorNonzeros = coarse_->factorNonzeros();
        profile_.coarseSubtrees = coarse_->subtreeCount();
        single[2] = 2.0 * static_cast<double>(coarse_->solveBytes()) / subdomainBytesPerF_;
        if (singleCoarsePays(single[2]) && !coarseSingleRejected_) {
          const auto [rounded, error] = roundCoarseToSingle();
          single[0] = rounded ? 1.0 : 0.0;
          single[1] = error;
        }
      },
      [](const std::string& message) { throw core::InputError(message); });
  profile_.coarseSingleError = single[1];
  profile_.coarseToFBytes = single[2];
  if (single[0] != 0.0 && !(single[1] <= settings_.singleCoarseGate)) {
    // Too inaccurate for this G G^T (kappa ~ 1e4 and more; NaN too): factorised again in
    // double, on every rank alike (the flags came from rank 0).
    coarseSingleRejected_ = true;
    coarse_.reset();
    profile_.coarseFactorSeconds += watch.seconds();
    factorizeCoarse();
    profile_.coarseSingleError = single[1];  // the error that sent it back
    return;
  }
  coarseSingle_ = single[0] != 0.0;
  profile_.coarseSingle = coarseSingle_;
  // Collective: the subtrees of its elimination tree to the ranks that will solve them.
  distributedCoarse_ = DistributedCoarseSolve::create(rawComm(*comm_), coarse_.get(), settings_.distributedCoarseFromValues);
  profile_.coarseRankSubtrees = distributedCoarse_ ? distributedCoarse_->numLeaves() : 0;
  profile_.coarseSplitDepth = distributedCoarse_ ? distributedCoarse_->depth() : 0;
  profile_.coarseValuesPerSolve =
      distributedCoarse_ ? distributedCoarse_->valuesOnThisRank() : (coarse_ ? coarse_->factorNonzeros() : 0);
  coarseFactored_ = true;
  profile_.coarseFactorSeconds += watch.seconds();
}

bool TotalFeti::singleCoarsePays(double coarseToFBytes) const {
  // Rank 0, with the factor: "Auto" rounds where the two coarse solves of an A_rho product
  // read at least as many bytes as the subdomain solves of its F application
  // (subdomainBytesPerF_: the same on every rank layout, so that the choice, and with it
  // every bit of the run, is too): there the rounding saves a quarter or more of the
  // product's traffic.
  // Elsewhere the double factor keeps the exact projector's path: on symmetric scenes (the
  // paper's bricks) pairs of constraints reach their bounds in the same step only with it,
  // and any perturbation of P beyond ~1e-11 costs up to 20 % more F applications there
  // (doc/measurements/coarse_problem.md, "The coarse factor in single precision").
  switch (settings_.coarsePrecision) {
    case CoarsePrecision::Single: return true;
    case CoarsePrecision::Double: return false;
    case CoarsePrecision::Auto: break;
  }
  return coarseToFBytes >= 1.0;
}

std::pair<bool, double> TotalFeti::roundCoarseToSingle() const {
  // One solve of a fixed right-hand side before and after the rounding: the relative change
  // is about kappa(G G^T) 1e-7, the size of the perturbation the rounding makes to P.
  const LO n = coarse_->size();
  std::vector<double> b(static_cast<size_t>(n)), exact(b.size()), rounded(b.size());
  std::uint32_t state = 12345u;
  for (double& v : b) {
    state = 1664525u * state + 1013904223u;  // a fixed sequence (LCG), spread over [-1, 1)
    v = static_cast<double>(state) / 2147483648.0 - 1.0;
  }
  coarse_->solve(b.data(), exact.data());
  if (!coarse_->roundToSingle()) return {false, 0.0};
  coarse_->solve(b.data(), rounded.data());
  double difference = 0.0, norm = 0.0;
  for (size_t i = 0; i < b.size(); ++i) {
    difference += (rounded[i] - exact[i]) * (rounded[i] - exact[i]);
    norm += exact[i] * exact[i];
  }
  return {true, std::sqrt(difference / norm)};  // NaN or Inf: rejected by the gate
}

void TotalFeti::solveCoarseExactly(std::vector<double>& a) const {
  if (!coarseFactored_) factorizeCoarse();
  if (!coarseSingle_) {
    solveCoarse(a);
    return;
  }
  // Iterative refinement: x += C~^{-1} (b - G G^T x) contracts by about the gate's error per
  // step (at most 1e-3: 1e-16 in five steps); it stops when the correction reaches round-off
  // (1e-16 of x) or stops shrinking, and is accepted when the last correction was below 1e-10
  // of x. The same numbers on every rank (coarse vectors are replicated), so the same
  // decisions.
  const std::vector<double> b = a;
  solveCoarse(a);
  DualVector v(dualMap_);
  std::vector<double> r;
  double previous = std::numeric_limits<double>::infinity(), correction = 0.0, norm = 0.0;
  for (int k = 0; k < kMaxCoarseRefinements; ++k) {
    applyGt(a, v);
    applyG(v, r);
    for (size_t i = 0; i < r.size(); ++i) r[i] = b[i] - r[i];
    solveCoarse(r);
    ++profile_.coarseRefinementSteps;
    correction = 0.0;
    norm = 0.0;
    for (size_t i = 0; i < r.size(); ++i) {
      a[i] += r[i];
      correction += r[i] * r[i];
      norm += a[i] * a[i];
    }
    if (correction <= 1e-32 * norm || correction >= previous) break;
    previous = correction;
  }
  if (correction <= 1e-20 * norm) return;
  // Not refined to round-off (not seen): the double factor after all, for every later
  // coarse solve too; the summary keeps the gate's error (coarse_single false with an error:
  // sent back to double).
  const double error = profile_.coarseSingleError;
  coarseSingleRejected_ = true;
  releaseCoarseFactor();
  a = b;
  solveCoarse(a);
  profile_.coarseSingleError = error;
}

void TotalFeti::releaseCoarseFactor() const {
  distributedCoarse_.reset();  // it reads coarse_'s factor on rank 0
  coarse_.reset();
  coarseFactored_ = false;
  for (CoarseMemo& memo : coarseMemo_) memo = CoarseMemo{};
  for (ProjectionMemo& memo : projectionMemo_) memo = ProjectionMemo{};
}

void TotalFeti::onRootThenBroadcast(std::vector<double>& v, const std::function<void()>& work,
                                    const std::function<void(const std::string&)>& fail) const {
  if (comm_->getSize() == 1) {
    work();  // its exceptions as they are
    return;
  }
  // Every rank reaches both broadcasts, also when rank 0's work failed: then every rank
  // throws, with rank 0's message (a rank left waiting in a collective would hang the job).
  int failed = 0;
  std::string message;
  if (comm_->getRank() == 0) {
    try {
      work();
    } catch (const std::exception& e) {
      failed = 1;
      message = e.what();
    }
  }
  Teuchos::broadcast(*comm_, 0, 1, &failed);
  if (failed) {
    int length = static_cast<int>(message.size());
    Teuchos::broadcast(*comm_, 0, 1, &length);
    message.resize(static_cast<size_t>(length));
    if (length > 0) Teuchos::broadcast(*comm_, 0, length, message.data());
    fail(message);
    throw std::logic_error("tribos::feti::TotalFeti::onRootThenBroadcast: `fail` must throw");
  }
  if (!v.empty()) Teuchos::broadcast(*comm_, 0, static_cast<int>(v.size()), v.data());
}

std::vector<double> TotalFeti::rigidBodyCoefficients(const DualVector& lambda,
                                                     const std::vector<char>& ownedRowMask) const {
  const core::ScopedSeconds timed(profile_.rigidCoefficientsSeconds);
  TEUCHOS_TEST_FOR_EXCEPTION(ownedRowMask.size() != static_cast<size_t>(G_->numRows), std::invalid_argument,
                             "tribos::feti::TotalFeti::rigidBodyCoefficients: the mask has "
                                 << ownedRowMask.size() << " entries, this rank owns " << G_->numRows << " rows");
  DualVector residual(dualMap_);
  applyF(lambda, residual);
  residual.update(-1.0, *dTilde_, 1.0);
  {
    auto data = residual.getLocalViewHost(Tpetra::Access::ReadWrite);
    for (size_t i = 0; i < data.extent(0); ++i)
      if (!ownedRowMask[i]) data(i, 0) = 0.0;
  }
  std::vector<double> alpha;
  applyG(residual, alpha);
  // Assembled, factorised and solved on rank 0 (as G G^T: onRootThenBroadcast).
  fem::CsrMatrix GiGit = assembleCoarse(&ownedRowMask);
  onRootThenBroadcast(
      alpha,
      [&] {
        auto factor = makeSparseCholesky(settings_.factorization, settings_.factorOptions);
        try {
          factor->factorizeConsuming(std::move(GiGit));
        } catch (const std::exception& e) {
          throw RigidMotionsUndetermined(
              std::string("tribos::feti::TotalFeti::rigidBodyCoefficients: G_I G_I^T is singular "
                          "(the inactive rows do not fix every rigid body mode): ") +
              e.what());
        }
        std::vector<double> rhs = alpha;
        factor->solve(rhs.data(), alpha.data());
      },
      [](const std::string& message) { throw RigidMotionsUndetermined(message); });
  return alpha;
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

template <class LocalOp>
void TotalFeti::applyBlockwise(const DualVector& x, DualVector& y, LocalOp op) const {
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
    core::forEachSubdomain(numOwnedSubdomains(), [&](int i) {
      Local& L = *local_[i];
      for (LO r = 0; r < L.m(); ++r) L.in[r] = xo[L.overlapIndex[r]];
      op(L, true);
      std::copy(L.out.begin(), L.out.end(), source + entrySourceFirst_[i]);
    });
    entryTarget_->doImport(*entrySource_, *entryImport_, Tpetra::INSERT);
    const double* entry = readOnly(*entryTarget_);
    double* yo = y.getLocalViewHost(Tpetra::Access::OverwriteAll).data();
    const CoarseRows& G = *G_;
    core::forEachSubdomain((G.numRows + kRowChunk - 1) / kRowChunk, [&](int chunk) {
      const LO end = std::min<LO>(G.numRows, (chunk + 1) * kRowChunk);
      for (LO r = chunk * kRowChunk; r < end; ++r) {
        double total = 0.0;
        for (LO e = G.rowStart[r]; e < G.rowStart[r + 1]; ++e) total += entry[e];
        yo[r] = total;
      }
    });
    return;
  }
  core::forEachSubdomain(numOwnedSubdomains(), [&](int i) {
    Local& L = *local_[i];
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

void TotalFeti::applyLumped(const DualVector& x, DualVector& y) const {
  TEUCHOS_TEST_FOR_EXCEPTION(!settings_.lumpedPreconditioner && !settings_.dirichletPreconditioner, std::logic_error,
                             "tribos::feti::TotalFeti::applyLumped: construct with "
                             "settings.lumpedPreconditioner = true");
  core::Stopwatch watch;
  applyBlockwise(x, y, [](Local& L, bool) {
    // out = B_s K_bb B_s^T in: B_s^T in is zero off b, and B_s reads b only. Each row of K_bb
    // adds its terms in K's column order less the ones that multiply those zeros, with K_ji
    // for K_ij below the diagonal (the stored triangle): B_s K B_s^T to rounding.
    DirichletBlocks& D = L.dirichlet;
    scatterTerms(D.terms, L.in.data(), D.xb.data(), static_cast<LO>(D.xb.size()));
    D.Kbb.applySymmetric(D.xb.data(), D.yb.data());
    gatherTerms(D.terms, D.yb.data(), L.out.data(), L.m());
  });
  ++profile_.preconditionerApplications;
  profile_.preconditionerSeconds += watch.seconds();
}

void TotalFeti::applyDirichlet(const DualVector& x, DualVector& y) const {
  TEUCHOS_TEST_FOR_EXCEPTION(!settings_.dirichletPreconditioner, std::logic_error,
                             "tribos::feti::TotalFeti::applyDirichlet: construct with "
                             "settings.dirichletPreconditioner = true");
  core::Stopwatch watch;
  applyBlockwise(x, y, [](Local& L, bool) {
    // x_b = B_s^T in; y_b = K_bb x_b - K_ib^T K_ii^{-1} K_ib x_b; out = B_s y_b. Per subdomain,
    // in one fixed order: the same bits on every rank and thread layout.
    DirichletBlocks& D = L.dirichlet;
    scatterTerms(D.terms, L.in.data(), D.xb.data(), static_cast<LO>(D.xb.size()));
    D.Kbb.applySymmetric(D.xb.data(), D.yb.data());
    if (D.interiorFactor) {
      D.Kib.apply(D.xb.data(), D.t.data());
      D.interiorFactor->solveInPlace(D.t.data());
      D.Kib.subtractTransposed(D.t.data(), D.yb.data());
    }
    gatherTerms(D.terms, D.yb.data(), L.out.data(), L.m());
  });
  ++profile_.preconditionerApplications;
  profile_.preconditionerSeconds += watch.seconds();
}

namespace {
/// The two coordinates of p~ that component D's rotation rows read: (e_k x p~)_D involves
/// p~_k' for k' != D only.
template <int D>
constexpr int kFirstOther = D == 0 ? 1 : 0;
template <int D>
constexpr int kSecondOther = D == 2 ? 1 : 2;

/// sum[0..2] = sums of w, w p~_a, w p~_b (a, b: kFirstOther, kSecondOther) over one-term
/// rows of component D, w = c x_r; two interleaved partial sums (shorter dependency chains),
/// added at the end: a fixed order for a fixed list of terms.
template <int D>
void sumComponent(const CoarseTerm* __restrict t, const CoarseTerm* end, const double* __restrict x,
                  const double* __restrict coords, double* sum) {
  constexpr int a = kFirstOther<D>, b = kSecondOther<D>;
  double s0 = 0.0, s1 = 0.0, s2 = 0.0, u0 = 0.0, u1 = 0.0, u2 = 0.0;
  for (; t + 1 < end; t += 2) {
    const double w = t[0].c * x[t[0].index], v = t[1].c * x[t[1].index];
    const double* p = coords + 3 * static_cast<size_t>(t[0].code >> 2);
    const double* q = coords + 3 * static_cast<size_t>(t[1].code >> 2);
    s0 += w;
    s1 += w * p[a];
    s2 += w * p[b];
    u0 += v;
    u1 += v * q[a];
    u2 += v * q[b];
  }
  if (t < end) {
    const double w = t->c * x[t->index];
    const double* p = coords + 3 * static_cast<size_t>(t->code >> 2);
    s0 += w;
    s1 += w * p[a];
    s2 += w * p[b];
  }
  sum[0] = s0 + u0;
  sum[1] = s1 + u1;
  sum[2] = s2 + u2;
}

// (G x)_s of the i-th owned subdomain into gx[6 s, 6 s + 6) (applyGOwnedSubdomains).
void sumOwnedSubdomain(const TotalFeti::CoarseRows& G, int i, const double* xOverlap, double* gx) {
  const CoarseTerm* t = G.ownedTerm.data();
  const LO* start = &G.ownedStart[6 * static_cast<size_t>(i)];
  const int subdomain = start[5];
  double s0[3], s1[3], s2[3], full[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  sumComponent<0>(t + start[0], t + start[1], xOverlap, G.coords.data(), s0);
  sumComponent<1>(t + start[1], t + start[2], xOverlap, G.coords.data(), s1);
  sumComponent<2>(t + start[2], t + start[3], xOverlap, G.coords.data(), s2);
  for (LO k = start[3]; k < start[4]; ++k) {
    const double xr = xOverlap[t[k].index];
    const double* g = &G.full[6 * static_cast<size_t>(t[k].code >> 2)];
    for (int j = 0; j < 6; ++j) full[j] += g[j] * xr;
  }
  // sum of w [e_d; (e_0 x p~)_d, (e_1 x p~)_d, (e_2 x p~)_d] (geometricRow): rotation 0
  // reads z~ of d = 1 and y~ of d = 2, rotation 1 z~ of d = 0 and x~ of d = 2, rotation 2
  // y~ of d = 0 and x~ of d = 1.
  const double geo[6] = {s0[0] + full[0],
                         s1[0] + full[1],
                         s2[0] + full[2],
                         (s2[2] - s1[2]) + full[3],
                         (s0[2] - s2[1]) + full[4],
                         (s1[1] - s0[1]) + full[5]};
  transposedProduct(G.M(subdomain), geo, gx + 6 * subdomain);
}
}  // namespace

void TotalFeti::applyGOwnedSubdomains(const double* xOverlap, double* gx) const {
  // (G x)_s = M_s^T sum over the rows r of B_s of g'_{s,r} x_r, by the owner of s (threads
  // over the owned subdomains), in a fixed order of its terms (CoarseRows::ownedTerm): the same sum in
  // the same order on every layout. The other entries stay zero, so the all-reduce adds one
  // term and zeros (exact). A one-term row of component d adds w = c x_r times
  // [e_d; (e_k x p~)_d]: the sums of w and w p~ per component, combined at the end.
  std::fill(gx, gx + numCoarse(), 0.0);
  const CoarseRows& G = *G_;
  // A subdomain's sum is about a microsecond of work: the threads take up to kGxSubdomains
  // of them per task (at least 8 tasks per thread), so that the shared counter of the dynamic
  // schedule (a cache line that moves between the cores at every grab) is not touched 500
  // times per G x. Each subdomain writes only its own 6 entries: the same bits for any grouping.
  const int numOwned = numOwnedSubdomains();
  const int group = std::max(1, std::min(kGxSubdomains, numOwned / (8 * core::numThreads())));
  core::forEachSubdomain((numOwned + group - 1) / group, [&](int task) {
    const int end = std::min(numOwned, (task + 1) * group);
    for (int i = task * group; i < end; ++i) sumOwnedSubdomain(G, i, xOverlap, gx);
  });
}


void TotalFeti::reduceCoarse(std::vector<double>& local, double* gx) const {
  if (comm_->getSize() == 1)
    std::copy(local.begin(), local.end(), gx);
  else
    Teuchos::reduceAll(*comm_, Teuchos::REDUCE_SUM, numCoarse(), local.data(), gx);
}

void TotalFeti::applyG(const DualVector& x, std::vector<double>& gx) const {
  applyGOwnedSubdomains(overlapValues(x), coarseLocal_.data());
  gx.resize(numCoarse());
  reduceCoarse(coarseLocal_, gx.data());
}

namespace {
// rowSum[r] += c (b0 + ba p~_a + bb p~_b) over the one-term entries [first, end) of component
// D of one run (distinct rows: no chain between consecutive updates).
template <int D>
void addComponent(const TotalFeti::CoarseRows& G, LO first, LO end, double b0, double ba, double bb,
                  double* __restrict rowSum) {
  constexpr int a = kFirstOther<D>, b = kSecondOther<D>;
  const CoarseTerm* __restrict t = G.term.data();
  const double* __restrict coords = G.coords.data();
  for (LO e = first; e < end; ++e) {
    const double* p = coords + 3 * static_cast<size_t>(t[e].code >> 2);
    rowSum[t[e].index] += t[e].c * (b0 + (ba * p[a] + bb * p[b]));
  }
}

// y_r = x_r - sum over the entries of row r of g_{s,r} . a_s, for the owned rows (y may be
// x: each row reads its x_r before writing y_r); copyOfX (optional) gets x as well, in the
// same pass (the projection memo's input: no pass of its own over x on the main thread).
void subtractGt(const TotalFeti::CoarseRows& G, const double* a, const double* x, double* y, double* copyOfX) {
  core::forEachSubdomain(G.numChunks(), [&](int c) {
    const LO first = c * kRowChunk, end = std::min<LO>(G.numRows, first + kRowChunk);
    double* __restrict rowSum = G.rowSum.data();
    std::fill(rowSum + first, rowSum + end, 0.0);
    // Runs in ascending subdomain order: each row adds its terms in ascending subdomain
    // order (the rows of one run are distinct: no chain between consecutive updates).
    for (int run = G.chunkRunStart[c]; run < G.chunkRunStart[c + 1]; ++run) {
      // g_{s,r} . a_s = g'_{s,r} . b with b = M_s a_s: c (b[d] + (b_rot x p~)_d) for a
      // one-term row of component d.
      const int s = G.runSubdomain[run];
      const double* M = G.M(s);
      const double* as = a + 6 * s;
      double b[6];
      for (int i = 0; i < 6; ++i) {
        double sum = 0.0;
        for (int j = 0; j < 6; ++j) sum += M[6 * i + j] * as[j];
        b[i] = sum;
      }
      // (b_rot x p~)_d = sum_k b[3 + k] (e_k x p~)_d (geometricRow): per component the
      // coefficients of its two coordinates.
      const LO* group = &G.runGroupStart[4 * static_cast<size_t>(run)];
      addComponent<0>(G, group[0], group[1], b[0], -b[5], b[4], rowSum);
      addComponent<1>(G, group[1], group[2], b[1], b[5], -b[3], rowSum);
      addComponent<2>(G, group[2], group[3], b[2], -b[4], b[3], rowSum);
      for (LO e = group[3]; e < group[4]; ++e) {
        const CoarseTerm& t = G.term[e];
        const double* g = &G.full[6 * static_cast<size_t>(t.code >> 2)];
        rowSum[t.index] += (g[0] * b[0] + g[1] * b[1]) + (g[2] * b[2] + g[3] * b[3]) + (g[4] * b[4] + g[5] * b[5]);
      }
    }
    if (copyOfX)
      for (LO r = first; r < end; ++r) {
        const double xr = x[r];
        copyOfX[r] = xr;
        y[r] = xr - rowSum[r];
      }
    else
      for (LO r = first; r < end; ++r) y[r] = x[r] - rowSum[r];
  });
}
}  // namespace

void TotalFeti::applyGt(const std::vector<double>& a, DualVector& y) const {
  // y = G^T a = 0 - (-G^T a) (set-up only: lambda_Im)
  std::vector<double> minusA(a.size());
  for (size_t i = 0; i < a.size(); ++i) minusA[i] = -a[i];
  y.putScalar(0.0);
  double* yd = readWrite(y);
  subtractGt(*G_, minusA.data(), yd, yd, nullptr);
}

void TotalFeti::solveCoarse(std::vector<double>& a) const {
  core::Stopwatch watch;
  ++profile_.coarseSolves;
  // a is the same on every rank, so every rank finds the same memo entry (or none).
  for (const CoarseMemo& memo : coarseMemo_)
    if (memo.valid && std::equal(a.begin(), a.end(), memo.rhs.begin(), [](double x, double y) {
          return std::memcmp(&x, &y, sizeof(double)) == 0;
        })) {
      std::copy(memo.solution.begin(), memo.solution.end(), a.begin());
      ++profile_.coarseSolvesReused;
      profile_.coarseSolveSeconds += watch.seconds();
      return;
    }
  CoarseMemo& memo = coarseMemo_[coarseMemoNext_];
  coarseMemoNext_ = 1 - coarseMemoNext_;
  memo.valid = false;
  memo.rhs.assign(a.begin(), a.end());
  if (!coarseFactored_) factorizeCoarse();  // released (releaseCoarseFactor): the same factor again
  // Over the ranks when the factor is large (the bits of the serial solve), else on rank 0
  // alone, then broadcast: with every rank solving, the R ranks of a node streamed R copies
  // of the factor at once (16 ranks at 4 000 subdomains: doc/measurements/scalability.md).
  if (distributedCoarse_) {
    distributedCoarse_->solve(memo.rhs.data(), a.data());
    memo.solution.assign(a.begin(), a.end());
    memo.valid = true;
    profile_.coarseSolveSeconds += watch.seconds();
    return;
  }
  onRootThenBroadcast(
      a, [&] { coarse_->solve(memo.rhs.data(), a.data()); },
      [](const std::string& message) { throw std::runtime_error(message); });
  memo.solution.assign(a.begin(), a.end());
  memo.valid = true;
  profile_.coarseSolveSeconds += watch.seconds();
}

void TotalFeti::project(const DualVector& x, DualVector& y) const {
  // y = x - G^T (G G^T)^{-1} G x on the owned rows: x on the overlap rows (several ranks),
  // one all-reduce of length l, no allocation.
  const double* xd = readOnly(x);
  auto yView = [&]() { return &x == &y ? readWrite(y) : y.getLocalViewHost(Tpetra::Access::OverwriteAll).data(); };
  ++profile_.projections;
  core::Stopwatch watch;
  const int hit = findProjection(xd);
  if (hit >= 0) {
    // x has the bits of the memo's input: G^T a again with its a = (G G^T)^{-1} G x, the same
    // operations on the same numbers as the projection that stored it (the same bits), and
    // no copy of P x kept for the few projections that repeat (17 of 1140 on Table 1's
    // 10x5x5/5; the coarse coordinates, which repeat, need only gx and a).
    double* yd = yView();
    if (&x == &y) xd = yd;
    subtractGt(*G_, projectionMemo_[hit].coarse.data(), xd, yd, nullptr);
    ++profile_.projectionsReused;
    profile_.gSeconds += watch.seconds();
    return;
  }
  ProjectionMemo& memo = projectionMemo_[projectionMemoNext_];
  projectionMemoNext_ = (projectionMemoNext_ + 1) % kProjectionMemo;
  memo.valid = false;  // until its answer is stored below
  memo.rhs.resize(static_cast<size_t>(G_->numRows));  // filled by the G^T pass, before y (maybe x) is written
  applyGOwnedSubdomains(overlapValues(x), coarseLocal_.data());
  profile_.gSeconds += watch.seconds();
  watch.restart();
  reduceCoarse(coarseLocal_, coarseVector_.data());
  profile_.coarseReduceSeconds += watch.seconds();
  memo.gx.assign(coarseVector_.begin(), coarseVector_.end());
  solveCoarse(coarseVector_);
  memo.coarse.assign(coarseVector_.begin(), coarseVector_.end());
  watch.restart();
  double* yd = yView();
  if (&x == &y) xd = yd;
  subtractGt(*G_, coarseVector_.data(), xd, yd, memo.rhs.data());
  memo.valid = true;
  profile_.gSeconds += watch.seconds();
}

void TotalFeti::projectExactly(const DualVector& x, DualVector& y) const {
  if (!coarseFactored_) factorizeCoarse();
  if (!coarseSingle_) {
    project(x, y);  // exact already
    return;
  }
  std::vector<double> a;
  applyG(x, a);
  solveCoarseExactly(a);
  DualVector gta(dualMap_);
  applyGt(a, gta);
  y.update(1.0, x, -1.0, gta, 0.0);
}

int TotalFeti::findProjection(const double* x) const {
  // Bitwise (memcmp): the copy is then exactly what the projection would compute. The
  // comparison stops at the first differing entry, so a miss costs next to nothing; all
  // ranks must agree (a hit skips the all-reduce of G x): one all-reduce of an int.
  const size_t bytes = sizeof(double) * static_cast<size_t>(G_->numRows);
  int local = -1;
  // Newest first: the entry a caller most likely means.
  for (int age = 1; age <= kProjectionMemo && local < 0; ++age) {
    const int k = (projectionMemoNext_ - age + kProjectionMemo) % kProjectionMemo;
    if (projectionMemo_[k].valid && (bytes == 0 || std::memcmp(x, projectionMemo_[k].rhs.data(), bytes) == 0)) local = k;
  }
  if (comm_->getSize() == 1) return local;
  // Agreement: the same entry on every rank (MIN of (k or none) and MAX agree).
  const int none = kProjectionMemo;
  int mine[2] = {local < 0 ? none : local, -(local < 0 ? none : local)}, all[2] = {0, 0};
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MIN, 2, mine, all);
  return (all[0] == -all[1] && all[0] < none) ? all[0] : -1;
}

void TotalFeti::coarseCoordinates(const DualVector& x, std::vector<double>& gx, std::vector<double>& a) const {
  ++profile_.coarseCoordinates;
  const int hit = findProjection(readOnly(x));
  if (hit >= 0) {
    gx = projectionMemo_[hit].gx;
    a = projectionMemo_[hit].coarse;
    ++profile_.coarseCoordinatesReused;
    return;
  }
  applyG(x, gx);
  a = gx;
  solveCoarse(a);
}

std::vector<double> TotalFeti::rigidBodyCoefficients(const DualVector& lambda) const {
  const core::ScopedSeconds timed(profile_.rigidCoefficientsSeconds);
  DualVector residual(dualMap_);
  applyF(lambda, residual);
  residual.update(-1.0, *dTilde_, 1.0);
  std::vector<double> alpha;
  applyG(residual, alpha);
  solveCoarseExactly(alpha);
  return alpha;
}

void TotalFeti::applyB(const std::vector<std::vector<double>>& u, DualVector& y) const {
  applyBlockwise(y, y, [&u, this](Local& L, bool) {
    applyBlock(*L.block, u[L.subdomain - firstOwned_].data(), L.out.data());
  });
}

double TotalFeti::equilibriumResidual(const DualVector& lambda, const std::vector<std::vector<double>>& u) const {
  const double* lo = overlapValues(lambda);
  double worst = 0.0;
  for (size_t i = 0; i < local_.size(); ++i) {
    Local& L = *local_[i];
    for (LO r = 0; r < L.m(); ++r) L.in[r] = lo[L.overlapIndex[r]];
    applyBlockTranspose(*L.block, L.rowOrder, L.in.data(), L.x.data(), L.n());
    L.system.K.apply(u[i].data(), L.y.data());
    for (LO k = 0; k < L.n(); ++k) worst = std::max(worst, std::abs(L.y[k] - L.system.f[k] + L.x[k]));
  }
  double global = 0.0;
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MAX, 1, &worst, &global);
  return global;
}

double TotalFeti::energy(const std::vector<std::vector<double>>& u) const {
  // One term per dof, summed independently of the layout (core::ReproducibleSum.hpp).
  std::vector<double> terms;
  for (size_t i = 0; i < local_.size(); ++i) {
    Local& L = *local_[i];
    L.system.K.apply(u[i].data(), L.y.data());
    for (LO k = 0; k < L.n(); ++k) terms.push_back(0.5 * u[i][k] * L.y[k] - L.system.f[k] * u[i][k]);
  }
  return core::reproducibleSum(comm_.get(), terms.data(), terms.size(), primalDofs_);
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
  const double* lo = overlapValues(lambda);
  std::vector<std::vector<double>> u(local_.size());
  core::forEachSubdomain(numOwnedSubdomains(), [&](int i) {
    Local& L = *local_[i];
    const LO n = L.n();
    for (LO r = 0; r < L.m(); ++r) L.in[r] = lo[L.overlapIndex[r]];
    applyBlockTranspose(*L.block, L.rowOrder, L.in.data(), L.x.data(), n);
    for (LO k = 0; k < n; ++k) L.x[k] = L.system.f[k] - L.x[k];
    u[i].assign(n, 0.0);
    L.solver.applyPseudoInverse(L.x.data(), u[i].data());
    for (LO k = 0; k < n; ++k)
      for (int j = 0; j < 6; ++j) u[i][k] += L.system.R[static_cast<size_t>(j) * n + k] * alpha[6 * L.subdomain + j];
  });
  return u;
}

}  // namespace tribos::feti
