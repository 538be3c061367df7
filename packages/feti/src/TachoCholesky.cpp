// SparseCholesky by Trilinos's Tacho (ShyLU-Node) through Tacho::Driver on Kokkos::Serial,
// with the METIS_NodeND ordering computed here: Debian builds Tacho without METIS, and its
// own fallback ordering is the identity, 16-57x slower on 3D elasticity (TOOLCHAIN.md).
// Amesos2's Tacho adapter is not used: it never calls Driver::initialize() and crashes for
// n >= 1024 (TOOLCHAIN.md).
//
// Thread safety (TOOLCHAIN.md, "Threads inside a rank"): Debian's Kokkos is Serial-only with
// non-atomic View reference counts. Driver::analyze/initialize build the symbolic structure
// (Views shared inside the driver, Kokkos' global bookkeeping), so they run one at a time
// under one mutex, and so does release(). factorize/solve only touch this driver's own Views
// and would be safe concurrently for different objects as far as Kokkos goes. Every View here
// is created and destroyed by the thread that calls this object; the arrays it wraps are
// members (std::vector), so the driver never outlives what it points to.
//
// But the supernodal kernels call BLAS/LAPACK (potrf, trsm, herk/gemm on panels; trsv/gemv
// or trsm/gemm in the solve), and Debian's serial OpenBLAS is not safe to call from two
// threads at once: measured, 25 % of concurrent Tacho factorisations at 5184 dofs and 19 %
// of 4-column solves at 1536 dofs were wrong. Tacho has no BLAS-free (simplicial) mode, so
// factorize and solve hold blasMutex(): Tacho objects work from any thread but do not run
// in parallel with each other (doc/factorization.md).
// Mutexes, not `omp critical`: an exception must not leave an OpenMP structured block.
#include <Kokkos_Core.hpp>
#include <Tacho_Driver.hpp>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include "SparseCholeskyImpl.hpp"

namespace tribos::feti {

namespace {

using TachoDevice = Kokkos::Device<Kokkos::Serial, Kokkos::HostSpace>;
using TachoDriver = Tacho::Driver<double, TachoDevice>;

class TachoCholesky final : public SparseCholesky {
 public:
  ~TachoCholesky() override { release(); }

  void factorize(const fem::CsrMatrix& A) override {
    if (!Kokkos::is_initialized())
      throw std::runtime_error("tribos::feti::TachoCholesky::factorize: Kokkos is not initialized");
    release();
    n_ = A.n;
    // Tacho keeps (unmanaged) references to the graph and ordering: own copies of them.
    rowPtr_.assign(A.rowPtr.begin(), A.rowPtr.end());
    colInd_ = A.colInd;
    perm_ = nestedDissection(A);
    identity_.resize(n_);
    for (LO k = 0; k < n_; ++k) identity_[k] = k;
    iperm_.assign(n_, 0);
    for (LO k = 0; k < n_; ++k) iperm_[perm_[k]] = k;
    nnzL_ = -1;

    using SizeArray = Kokkos::View<size_t*, TachoDevice, Kokkos::MemoryUnmanaged>;
    using OrdinalArray = Kokkos::View<int*, TachoDevice, Kokkos::MemoryUnmanaged>;
    {
      std::lock_guard<std::mutex> lock(symbolicMutex());
      try {
        driver_ = std::make_unique<TachoDriver>();
        // Symmetric positive definite: Cholesky (LL^T). No dense LAPACK path for n < 1024
        // (Tacho's default): the sparse supernodal factor at every size, since Table 1's
        // subdomains (81..648 dofs) would otherwise be factorised as dense matrices.
        driver_->setMatrixType(2, true);
        driver_->setSmallProblemThresholdsize(0);
        const int status = driver_->analyze(n_, SizeArray(rowPtr_.data(), rowPtr_.size()),
                                            OrdinalArray(colInd_.data(), colInd_.size()),
                                            OrdinalArray(perm_.data(), n_), OrdinalArray(iperm_.data(), n_));
        if (status != 0 || driver_->initialize() != 0) throw std::runtime_error("non-zero status");
      } catch (const std::exception& e) {
        releaseLocked();
        throw std::runtime_error("Tacho: symbolic analysis failed (n = " + std::to_string(n_) + "): " + e.what());
      }
    }

    // Numeric phase. LAPACK potrf inside Tacho throws std::runtime_error on a non-positive
    // pivot (and prints a line to stderr); report it in the same words as CHOLMOD.
    TachoDriver::value_type_array values(const_cast<double*>(A.values.data()), A.values.size());
    try {
      std::lock_guard<std::mutex> lock(blasMutex());
      driver_->factorize(values);
    } catch (const std::exception& e) {
      release();
      throw std::runtime_error("Tacho: the matrix (n = " + std::to_string(A.n) +
                               ") is not positive definite or the factorisation failed: " + e.what());
    }
  }

  void solve(const double* b, double* x, int nrhs) const override {
    if (!driver_) throw std::runtime_error("tribos::feti::TachoCholesky::solve: call factorize() first");
    const size_t n = static_cast<size_t>(n_), m = static_cast<size_t>(nrhs);
    work_.resize(n * m);
    TachoDriver::value_type_matrix X(x, n, m), B(const_cast<double*>(b), n, m), W(work_.data(), n, m);
    std::lock_guard<std::mutex> lock(blasMutex());  // trsv/gemv, or trsm/gemm for nrhs > 1
    driver_->solve(X, B, W);
  }

  /// Tacho permutes internally: in-place solves work in A's own order.
  const std::vector<LO>& permutation() const override { return identity_; }
  void solveInPlace(double* v) const override {
    inPlace_.assign(v, v + n_);
    solve(inPlace_.data(), v, 1);
  }

  LO size() const override { return n_; }

  long long factorNonzeros() const override {
    if (!driver_) return 0;
    if (nnzL_ < 0) {
      // Tacho does not report its factor size; the ordering is ours, so the column counts
      // of L under it are (up to supernode padding) what Tacho stores.
      fem::CsrMatrix pattern;
      pattern.n = n_;
      pattern.rowPtr.assign(rowPtr_.begin(), rowPtr_.end());
      pattern.colInd = colInd_;
      nnzL_ = choleskyFactorNonzeros(pattern, perm_);
    }
    return nnzL_;
  }

  /// Estimated as 12 bytes (value and row index) per entry of L, read twice: Tacho does not
  /// report its storage.
  long long solveBytes() const override { return 2 * 12 * factorNonzeros(); }
  std::string name() const override { return "Tacho"; }

 private:
  static std::mutex& symbolicMutex() {
    static std::mutex m;
    return m;
  }
  void release() {
    if (!driver_) return;
    std::lock_guard<std::mutex> lock(symbolicMutex());
    releaseLocked();
  }
  void releaseLocked() {
    if (!driver_) return;
    try {
      driver_->release();  // Driver has no destructor of its own: release() frees the numeric tools
    } catch (...) {
    }
    driver_.reset();
  }

  std::unique_ptr<TachoDriver> driver_;
  std::vector<size_t> rowPtr_;
  std::vector<int> colInd_, perm_, iperm_;
  mutable std::vector<double> work_, inPlace_;
  std::vector<LO> identity_;
  mutable long long nnzL_ = -1;
  LO n_ = 0;
};

}  // namespace

std::unique_ptr<SparseCholesky> makeTachoCholesky() { return std::make_unique<TachoCholesky>(); }

}  // namespace tribos::feti
