// SparseCholesky by CHOLMOD (SuiteSparse): LL^T with a METIS nested-dissection ordering
// computed here (METIS_NodeND) and passed as CHOLMOD_GIVEN; the numeric factor is then
// copied into a PackedFactor and CHOLMOD's freed: the solves are tribos's own loops
// (PackedFactor.hpp), which read fewer bytes than CHOLMOD's solves and need no BLAS.
//
// The factorisation is simplicial (no BLAS, so truly concurrent) below kSupernodalFromDofs
// rows and supernodal (BLAS calls under blasMutex(), see SparseCholeskyImpl.hpp) above, by
// the size of the matrix alone: the same factor, to the bit, on any number of ranks and
// threads (it used to depend on whether the call came from a team of threads, and with it
// the rounding and the iteration counts). Every object works from any thread, one thread at
// a time.
//
// Debian's CHOLMOD runs OpenMP loops with 4 threads inside supernodal factorisation; on
// small subdomain matrices that is many times slower than one thread. We never want that
// nested parallelism (threads already run over subdomains), so every call is made with
// OpenMP parallelism disabled when it is not already inside an active parallel region (and
// core::forEachSubdomain limits nesting to one active level).
#include <cholmod.h>
#include <metis.h>
#include <omp.h>

#include <algorithm>
#include <cstdlib>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include "PackedFactor.hpp"
#include "SparseCholeskyImpl.hpp"

namespace tribos::feti {

namespace {
/// Matrices of at least this many rows are factorised supernodally. Measured (doc/factorization.md):
/// the solves cost the same in both modes; the supernodal factorisation is faster from
/// ~2000 rows on one thread, but serialised by blasMutex() in a team of two threads it
/// catches up with two concurrent simplicial ones only at ~4000-6500 rows.
constexpr LO kSupernodalFromDofs = 4000;


/// Runs f with OpenMP parallel regions disabled unless already inside an active one.
template <class F>
void withoutNestedThreads(F&& f) {
  if (omp_get_active_level() > 0) {
    f();
    return;
  }
  const int saved = omp_get_max_active_levels();
  omp_set_max_active_levels(0);
  try {
    f();
  } catch (...) {
    omp_set_max_active_levels(saved);
    throw;
  }
  omp_set_max_active_levels(saved);
}

/// Whether CHOLMOD factorises A supernodally: by the matrix alone, never by the thread that
/// asks, so that the factor (and every result computed with it) is the same for any number
/// of ranks and threads. FETI/CHOLMOD Mode may fix it (for the measurements of
/// doc/measurements/performance.md).
bool supernodalFactor(const fem::CsrMatrix& A, CholmodMode mode) {
  if (mode != CholmodMode::Auto) return mode == CholmodMode::Supernodal;
  return A.n >= kSupernodalFromDofs;
}

/// A supernodal factor packed in place, in CHOLMOD's own array of values, which the packed
/// factor then owns (no second copy of a factor alive: the replicated G G^T is the largest
/// item per rank at thousands of subdomains, doc/measurements/scalability.md). CHOLMOD stores supernode k
/// as an nsrow x nc column-major panel at px[k] (the diagonal block whole); the packed
/// layout puts its panel rows (column-major) first and then the strict lower triangle of
/// the diagonal block (by columns). Writing from the front never overtakes what is still to
/// be read: every packed supernode starts at or before px[k] and is smaller than CHOLMOD's,
/// and a panel entry moves to an index at or below its own. Only the triangle, which the
/// panel overwrites, goes through a buffer first. The values are those of the copy
/// (appendSupernode), so the solves give the same bits.
void packSupernodalInPlace(cholmod_factor& L, PackedFactor& packed) {
  const LO* super = static_cast<const LO*>(L.super);
  const LO* pi = static_cast<const LO*>(L.pi);
  const LO* px = static_cast<const LO*>(L.px);
  const LO* s = static_cast<const LO*>(L.s);
  double* x = static_cast<double*>(L.x);
  long long rowIndices = 0;
  for (size_t k = 0; k < L.nsuper; ++k) rowIndices += pi[k + 1] - pi[k] - (super[k + 1] - super[k]);
  packed.reserve(0, rowIndices, static_cast<LO>(L.nsuper), static_cast<LO>(L.n));
  std::vector<double> triangle, inverseDiagonal;
  std::vector<LO> rows;
  long long next = 0;  // the first free entry of the packed values
  for (size_t k = 0; k < L.nsuper; ++k) {
    const LO first = super[k], nc = super[k + 1] - first, nsrow = pi[k + 1] - pi[k], nr = nsrow - nc;
    const double* panel = x + px[k];
    triangle.clear();
    inverseDiagonal.resize(nc);
    for (LO j = 0; j < nc; ++j) {
      inverseDiagonal[j] = 1.0 / panel[static_cast<size_t>(j) * nsrow + j];
      for (LO i = j + 1; i < nc; ++i) triangle.push_back(panel[static_cast<size_t>(j) * nsrow + i]);
    }
    const long long panelOffset = next;
    for (LO j = 0; j < nc; ++j)
      for (LO r = 0; r < nr; ++r) x[next++] = x[px[k] + static_cast<long long>(j) * nsrow + nc + r];
    const long long triangleOffset = next;
    for (double v : triangle) x[next++] = v;
    rows.assign(s + pi[k] + nc, s + pi[k + 1]);
    packed.appendLaidOutSupernode(first, nc, rows, triangleOffset, panelOffset, inverseDiagonal.data());
  }
  // The array, shrunk to the packed values, changes hands: CHOLMOD must not free it.
  void* shrunk = next > 0 ? SuiteSparse_config.realloc_func(x, static_cast<size_t>(next) * sizeof(double)) : nullptr;
  packed.adoptValues(static_cast<double*>(shrunk ? shrunk : x), next, SuiteSparse_config.free_func,
                     SuiteSparse_config.realloc_func);
  L.x = nullptr;
  L.xsize = 0;
}

/// The numeric factor as a PackedFactor: supernodal panels as they are (packed in place:
/// packSupernodalInPlace; L loses its values); simplicial columns merged into fundamental
/// supernodes (consecutive columns whose row sets nest), copied.
PackedFactor packFactor(cholmod_factor& L) {
  PackedFactor packed;
  const LO n = static_cast<LO>(L.n);
  const LO* perm = static_cast<const LO*>(L.Perm);
  packed.setPermutation(std::vector<LO>(perm, perm + n));
  if (L.is_super) {
    packSupernodalInPlace(L, packed);
    return packed;
  }
  const double* x = static_cast<const double*>(L.x);
  std::vector<LO> rows;
  const LO* Lp = static_cast<const LO*>(L.p);
  const LO* Li = static_cast<const LO*>(L.i);
  const LO* Lnz = static_cast<const LO*>(L.nz);
  // Column j + 1 continues the supernode of column j when its rows are column j's minus j.
  auto continues = [&](LO j) {
    if (Lnz[j] != Lnz[j + 1] + 1 || Lnz[j] < 2 || Li[Lp[j] + 1] != j + 1) return false;
    return std::equal(Li + Lp[j] + 2, Li + Lp[j] + Lnz[j], Li + Lp[j + 1] + 1);
  };
  // The supernodes (their last columns) and the exact sizes first (PackedFactor::reserve):
  // every strict lower entry of a column is stored once, in its triangle or its panel.
  std::vector<LO> lastColumn;
  long long values = 0, rowIndices = 0;
  for (LO first = 0; first < n;) {
    LO last = first;
    while (last + 1 < n && continues(last)) ++last;
    lastColumn.push_back(last);
    for (LO j = first; j <= last; ++j) values += Lnz[j] - 1;
    rowIndices += Lnz[last] - 1;
    first = last + 1;
  }
  packed.reserve(values, rowIndices, static_cast<LO>(lastColumn.size()), n);
  LO first = 0;
  for (LO last : lastColumn) {
    const LO nc = last - first + 1;
    if (!std::is_sorted(Li + Lp[last], Li + Lp[last] + Lnz[last]) || Li[Lp[last]] != last)
      throw std::logic_error("tribos::feti::CholmodCholesky: unsorted simplicial factor column");
    rows.assign(Li + Lp[last] + 1, Li + Lp[last] + Lnz[last]);
    packed.appendSupernode(first, nc, rows, [&](LO i, LO j) { return x[Lp[first + j] + (i - j)]; });
    first = last + 1;
  }
  return packed;
}

/// Drops the strict lower triangle of a symmetric CSR matrix (in place, storage shrunk):
/// with stype = 1 CHOLMOD reads the upper triangle of the columns only, and its permuted
/// copy of A, made inside cholmod_factorize next to the growing factor, is then half as big
/// as well. Only for a matrix given up (factorizeConsuming), after the ordering, which needs
/// the whole graph.
void keepUpperTriangle(fem::CsrMatrix& A) {
  LO kept = 0, begin = 0;
  for (LO i = 0; i < A.n; ++i) {
    const LO end = A.rowPtr[i + 1];
    for (LO k = begin; k < end; ++k)
      if (A.colInd[k] <= i) {
        A.colInd[kept] = A.colInd[k];
        A.values[kept++] = A.values[k];
      }
    begin = end;
    A.rowPtr[i + 1] = kept;
  }
  A.colInd.resize(kept);
  A.values.resize(kept);
  A.colInd.shrink_to_fit();
  A.values.shrink_to_fit();
}

class CholmodCholesky final : public SparseCholesky {
 public:
  explicit CholmodCholesky(const SparseCholeskyOptions& options) : options_(options) { cholmod_start(&common_); }
  ~CholmodCholesky() override { cholmod_finish(&common_); }

  void factorize(const fem::CsrMatrix& A) override { factorize(A, nullptr); }
  void factorizeConsuming(fem::CsrMatrix&& A) override { factorize(A, &A); }

 private:
  /// `consumed`: A itself, freed after the numeric factorisation, or null.
  void factorize(const fem::CsrMatrix& A, fem::CsrMatrix* consumed) {
    n_ = A.n;
    const std::vector<LO> perm = nestedDissection(A);
    if (consumed) keepUpperTriangle(*consumed);  // A is *consumed
    // A symmetric CSR matrix is its own CSC; stype = 1: CHOLMOD reads the upper triangle only.
    cholmod_sparse S{};
    S.nrow = S.ncol = static_cast<size_t>(A.n);
    S.nzmax = A.values.size();
    S.p = const_cast<LO*>(A.rowPtr.data());
    S.i = const_cast<LO*>(A.colInd.data());
    S.x = const_cast<double*>(A.values.data());
    S.stype = 1;
    S.itype = CHOLMOD_INT;
    S.xtype = CHOLMOD_REAL;
    S.dtype = CHOLMOD_DOUBLE;
    S.sorted = 1;
    S.packed = 1;
    common_.nmethods = 1;
    common_.method[0].ordering = CHOLMOD_GIVEN;
    common_.postorder = 1;
    common_.final_ll = 1;  // L L^T, the form PackedFactor stores, in both modes
    // One mode per matrix, whatever the thread (supernodalFactor). Supernodal factors call
    // BLAS, and Debian's serial OpenBLAS is not safe to call from several threads at once
    // (measured: wrong, "not positive definite" factors), so they hold blasMutex(): inside a
    // team of threads, supernodal factorisations run one at a time. Simplicial ones need no
    // BLAS and run concurrently.
    common_.supernodal = supernodalFactor(A, options_.cholmodMode) ? CHOLMOD_SUPERNODAL : CHOLMOD_SIMPLICIAL;
    common_.print = 0;
    cholmod_factor* L = nullptr;
    withoutNestedThreads([&] {
      L = cholmod_analyze_p(&S, const_cast<LO*>(perm.data()), nullptr, 0, &common_);
      if (!L) return;
      if (L->is_super) {
        std::lock_guard<std::mutex> lock(blasMutex());
        cholmod_factorize(&S, L, &common_);
      } else {
        cholmod_factorize(&S, L, &common_);
      }
    });
    const bool failed = !L || common_.status != CHOLMOD_OK || L->minor < L->n || !L->is_ll;
    if (consumed) *consumed = fem::CsrMatrix{};  // S pointed into it: not read from here on
    if (!failed) {
      reciprocalCondition_ = cholmod_rcond(L, &common_);
      packed_ = packFactor(*L);  // the solves use the packed copy only
      // The threshold depends on the factor alone: every layout takes the same path
      // (measured in doc/measurements/coarse_problem.md).
      if (subtreeSolve_) packed_.planSubtrees(options_.subtreeSolveFromValues);
    }
    if (L) cholmod_free_factor(&L, &common_);
    if (failed)
      throw std::runtime_error("CHOLMOD: the matrix (n = " + std::to_string(A.n) +
                               ") is not positive definite or the factorisation failed (status " +
                               std::to_string(common_.status) + ")");
    work_.assign(packed_.workSize(), 0.0);
  }

 public:
  void solve(const double* b, double* x, int nrhs) const override {
    // Plain loops over the packed factor: no BLAS, no lock, no allocation (work_ is this
    // object's: one thread at a time per object, SparseCholesky.hpp).
    for (int j = 0; j < nrhs; ++j)
      packed_.solve(b + static_cast<size_t>(j) * n_, x + static_cast<size_t>(j) * n_, work_.data());
  }

  const std::vector<LO>& permutation() const override { return packed_.permutation(); }
  double reciprocalCondition() const override { return reciprocalCondition_; }
  void solveInPlace(double* v) const override { packed_.solvePermuted(v, work_.data()); }
  void setSparseColumns(const std::vector<LO>& columns) override { reach_ = packed_.reach(columns); }
  void solveInPlaceOnColumns(double* v) const override {
    if (reach_.empty()) return solveInPlace(v);
    packed_.solvePermutedOnReach(v, work_.data(), reach_);
  }
  long long solveBytesOnColumns() const override {
    return reach_.empty() ? solveBytes() : packed_.solveBytes(reach_);
  }

  LO size() const override { return n_; }
  long long factorNonzeros() const override { return packed_.storedValues(); }
  bool roundToSingle() override {
    packed_.roundToSingle();
    return true;
  }
  long long solveBytes() const override { return packed_.solveBytes(); }
  std::string name() const override { return "CHOLMOD"; }
  void setSubtreeSolve(bool enabled) override { subtreeSolve_ = enabled; }
  int subtreeCount() const override { return packed_.numSubtrees(); }
  const PackedFactor* packedFactor() const override { return &packed_; }

 private:
  SparseCholeskyOptions options_;
  bool subtreeSolve_ = false;
  mutable cholmod_common common_{};
  PackedFactor packed_;
  double reciprocalCondition_ = 1.0;  ///< cholmod_rcond of the last factor
  PackedFactor::Ranges reach_;  ///< of setSparseColumns (empty: not set)
  mutable std::vector<double> work_;
  LO n_ = 0;
};
}  // namespace

std::unique_ptr<SparseCholesky> makeCholmodCholesky(const SparseCholeskyOptions& options) {
  return std::make_unique<CholmodCholesky>(options);
}

long long choleskyFactorNonzeros(const fem::CsrMatrix& A, const std::vector<LO>& perm) {
  // Symbolic analysis only (pattern, simplicial, given order): column counts of L, no BLAS,
  // no OpenMP; safe on any thread with its own cholmod_common.
  cholmod_common common;
  cholmod_start(&common);
  common.print = 0;
  common.nmethods = 1;
  common.method[0].ordering = CHOLMOD_GIVEN;
  common.postorder = 1;
  common.supernodal = CHOLMOD_SIMPLICIAL;
  cholmod_sparse S{};
  S.nrow = S.ncol = static_cast<size_t>(A.n);
  S.nzmax = A.colInd.size();
  S.p = const_cast<LO*>(A.rowPtr.data());
  S.i = const_cast<LO*>(A.colInd.data());
  S.stype = 1;
  S.itype = CHOLMOD_INT;
  S.xtype = CHOLMOD_PATTERN;
  S.dtype = CHOLMOD_DOUBLE;
  S.sorted = 1;
  S.packed = 1;
  long long nnz = -1;
  if (cholmod_factor* L = cholmod_analyze_p(&S, const_cast<LO*>(perm.data()), nullptr, 0, &common)) {
    nnz = static_cast<long long>(common.lnz);
    cholmod_free_factor(&L, &common);
  }
  cholmod_finish(&common);
  return nnz;
}

std::vector<LO> nestedDissection(const fem::CsrMatrix& A) {
  // METIS wants the adjacency graph without the diagonal.
  std::vector<idx_t> xadj(A.n + 1, 0), adjncy;
  adjncy.reserve(A.colInd.size());
  for (LO i = 0; i < A.n; ++i) {
    for (LO k = A.rowPtr[i]; k < A.rowPtr[i + 1]; ++k)
      if (A.colInd[k] != i) adjncy.push_back(A.colInd[k]);
    xadj[i + 1] = static_cast<idx_t>(adjncy.size());
  }
  std::vector<LO> perm(A.n), iperm(A.n);
  for (LO i = 0; i < A.n; ++i) perm[i] = i;
  if (A.n < 2 || adjncy.empty()) return perm;
  idx_t n = A.n;
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_NUMBERING] = 0;
  std::vector<idx_t> p(A.n), ip(A.n);
  int status = METIS_OK;
  // METIS keeps its random number state in a global: concurrent calls from the threads of
  // core::forEachSubdomain would race on it and make the orderings (and so the rounding of
  // every solve) differ from run to run. Each call reseeds it, so one at a time suffices.
#pragma omp critical(tribos_metis)
  status = METIS_NodeND(&n, xadj.data(), adjncy.data(), nullptr, options, p.data(), ip.data());
  if (status != METIS_OK) throw std::runtime_error("METIS_NodeND failed");
  for (LO i = 0; i < A.n; ++i) perm[i] = p[i];
  return perm;
}

}  // namespace tribos::feti
