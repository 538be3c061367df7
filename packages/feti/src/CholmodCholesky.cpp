// SparseCholesky by CHOLMOD (SuiteSparse): supernodal LL^T with a METIS nested-dissection
// ordering computed here (METIS_NodeND) and passed as CHOLMOD_GIVEN.
//
// Inside a team of threads the factor is simplicial (no BLAS, so truly concurrent); alone it
// is supernodal and BLAS calls hold blasMutex() (see SparseCholeskyImpl.hpp). Supernodal or
// not, every object works from any thread, one thread at a time.
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
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include "SparseCholeskyImpl.hpp"

namespace tribos::feti {

namespace {
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

class CholmodCholesky final : public SparseCholesky {
 public:
  CholmodCholesky() { cholmod_start(&common_); }
  ~CholmodCholesky() override {
    if (factor_) cholmod_free_factor(&factor_, &common_);
    cholmod_finish(&common_);
  }

  void factorize(const fem::CsrMatrix& A) override {
    n_ = A.n;
    const std::vector<LO> perm = nestedDissection(A);
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
    // Supernodal factors call BLAS, and Debian's serial OpenBLAS is not safe to call from
    // several threads at once (measured: wrong, "not positive definite" factors). Inside a
    // team of threads (core::forEachSubdomain with > 1 thread) the factor is simplicial,
    // which needs no BLAS and is as fast up to ~1000 dofs (Table 1's subdomains have at
    // most 648); alone, it is supernodal (4x faster factorisation at 10^4 dofs).
    // A supernodal factor made outside a team still holds blasMutex(), so that it is safe
    // beside any other BLAS user on another thread (a Tacho factor, for instance).
    common_.supernodal = omp_get_num_threads() > 1 ? CHOLMOD_SIMPLICIAL : CHOLMOD_SUPERNODAL;
    common_.print = 0;
    if (factor_) cholmod_free_factor(&factor_, &common_);
    withoutNestedThreads([&] {
      factor_ = cholmod_analyze_p(&S, const_cast<LO*>(perm.data()), nullptr, 0, &common_);
      if (!factor_) return;
      if (factor_->is_super) {
        std::lock_guard<std::mutex> lock(blasMutex());
        cholmod_factorize(&S, factor_, &common_);
      } else {
        cholmod_factorize(&S, factor_, &common_);
      }
    });
    if (!factor_ || common_.status != CHOLMOD_OK || factor_->minor < factor_->n)
      throw std::runtime_error("CHOLMOD: the matrix (n = " + std::to_string(A.n) +
                               ") is not positive definite or the factorisation failed (status " +
                               std::to_string(common_.status) + ")");
  }

  void solve(const double* b, double* x, int nrhs) const override {
    cholmod_dense B{};
    B.nrow = static_cast<size_t>(n_);
    B.ncol = static_cast<size_t>(nrhs);
    B.nzmax = B.nrow * B.ncol;
    B.d = B.nrow;
    B.x = const_cast<double*>(b);
    B.xtype = CHOLMOD_REAL;
    B.dtype = CHOLMOD_DOUBLE;
    cholmod_dense* X = nullptr;
    withoutNestedThreads([&] {
      if (factor_->is_super) {  // dtrsv/dgemv, or dtrsm/dgemm for several columns
        std::lock_guard<std::mutex> lock(blasMutex());
        X = cholmod_solve(CHOLMOD_A, factor_, &B, &common_);
      } else {
        X = cholmod_solve(CHOLMOD_A, factor_, &B, &common_);
      }
    });
    if (!X) throw std::runtime_error("CHOLMOD: solve failed");
    const double* xs = static_cast<const double*>(X->x);
    std::copy(xs, xs + B.nzmax, x);
    cholmod_free_dense(&X, &common_);
  }

  LO size() const override { return n_; }
  long long factorNonzeros() const override {
    if (!factor_) return 0;
    return factor_->is_super ? static_cast<long long>(factor_->xsize) : static_cast<long long>(factor_->nzmax);
  }
  std::string name() const override { return "CHOLMOD"; }

 private:
  mutable cholmod_common common_{};
  cholmod_factor* factor_ = nullptr;
  LO n_ = 0;
};
}  // namespace

std::unique_ptr<SparseCholesky> makeCholmodCholesky() { return std::make_unique<CholmodCholesky>(); }

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
