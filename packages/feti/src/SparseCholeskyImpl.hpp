#pragma once
// Internal: the implementations behind makeSparseCholesky and what they share.
#include <memory>
#include <mutex>
#include <vector>

#include "tribos/feti/SparseCholesky.hpp"

namespace tribos::feti {
std::unique_ptr<SparseCholesky> makeCholmodCholesky(const SparseCholeskyOptions& options);
std::unique_ptr<SparseCholesky> makeTachoCholesky();

/// Fill-reducing ordering (METIS_NodeND): perm[k] = the row eliminated k-th (METIS's
/// `perm`; CHOLMOD's and Tacho's convention too).
std::vector<LO> nestedDissection(const fem::CsrMatrix& A);

/// Entries of the Cholesky factor L (diagonal included) of A under the elimination order
/// `perm`, from CHOLMOD's symbolic analysis (column counts): the memory measure for
/// implementations that do not report their own.
/// Held around every call that may reach BLAS level 3 / LAPACK (supernodal factorisations,
/// multi-column solves). Debian's serial OpenBLAS takes its work buffers from a pool without
/// any lock: two threads in dgemm/dpotrf at once can share a buffer and produce a wrong
/// factor (measured: 6-25 % of concurrent supernodal factorisations failed or were wrong,
/// CHOLMOD and Tacho alike; doc/factorization.md). Uncontended, it costs nothing.
std::mutex& blasMutex();

long long choleskyFactorNonzeros(const fem::CsrMatrix& A, const std::vector<LO>& perm);
}  // namespace tribos::feti
