#pragma once
// Internal to feti/: the kernels the T-FETI components share (doc/design.md, "T-FETI
// operators"): B_s and B_s^T applied from a subdomain's block or its terms, the explicit F_s
// packed and applied, K's principal blocks, and small helpers for communicators and vectors.
// The components: SubdomainSet (the owned subdomains, the dual layout and its blockwise sums),
// Preconditioners, CoarseSpace (G, G G^T, the projector), PrimalRecovery (alpha, u, the
// residuals), owned by TotalFeti (the orchestrator: set-up, F, d~ and lambda_Im).
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
#include "tribos/core/PhaseTimer.hpp"
#include "tribos/core/ReproducibleSum.hpp"
#include "tribos/core/Timer.hpp"
#include "tribos/fem/SubdomainSystem.hpp"
#include "tribos/feti/DistributedCoarseSolve.hpp"
#include "tribos/feti/TotalFeti.hpp"

namespace tribos::feti {

namespace detail {
// x = B_s^T lambda_s (x has n entries, zeroed here). A dof in several rows sums them in
// `order` (the rows by their global id, B.rowId): B's own row order follows the number of
// ranks, and with it the rounding of these sums.
inline void applyBlockTranspose(const SubdomainBlock& b, const std::vector<LO>& order, const double* lambda, double* x,
                         LO n) {
  std::fill(x, x + n, 0.0);
  for (LO i : order)
    for (LO k = b.rowPtr[i]; k < b.rowPtr[i + 1]; ++k) x[b.dof[k]] += b.value[k] * lambda[i];
}

// out = B_s y.
inline void applyBlock(const SubdomainBlock& b, const double* y, double* out) {
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

inline std::vector<BlockTerm> blockTerms(const SubdomainBlock& b, const std::vector<LO>& order, const std::vector<LO>& dof) {
  std::vector<BlockTerm> terms;
  terms.reserve(b.value.size());
  for (LO i : order)
    for (LO k = b.rowPtr[i]; k < b.rowPtr[i + 1]; ++k) terms.push_back({i, dof[k], b.value[k]});
  return terms;
}

// x = B_s^T lambda_s from the terms: the bits of applyBlockTranspose (same terms, same order).
inline void scatterTerms(const std::vector<BlockTerm>& terms, const double* lambda, double* x, LO n) {
  std::fill(x, x + n, 0.0);
  for (const BlockTerm& t : terms) x[t.dof] += t.value * lambda[t.row];
}

// out = B_s y from the terms: each row's sum takes its terms in B's order from zero, the bits
// of applyBlock (the rows are visited in another order, each sum by itself).
inline void gatherTerms(const std::vector<BlockTerm>& terms, const double* y, double* out, LO m) {
  std::fill(out, out + m, 0.0);
  for (const BlockTerm& t : terms) out[t.row] += t.value * y[t.dof];
}

// The explicit F_s (ALGORITHMS.md 3) as the lower triangle of (F + F^T)/2 packed by rows, rows
// and columns in `order` (the block's rows by global id: the same matrix on every rank layout).
// `full`: m x m, column-major, in the block's own row order.
inline std::vector<double> packLowerInRowOrder(const std::vector<double>& full, const std::vector<LO>& order) {
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
inline void applyPackedLower(const std::vector<double>& packed, const std::vector<LO>& order, const double* in,
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
inline fem::CsrMatrix principalSubmatrix(const fem::CsrMatrix& K, const std::vector<LO>& keep) {
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

inline MPI_Comm rawComm(const Teuchos::Comm<int>& comm) {
  const auto* mpi = dynamic_cast<const Teuchos::MpiComm<int>*>(&comm);
  TEUCHOS_TEST_FOR_EXCEPTION(!mpi, std::logic_error, "tribos::feti: collectives need an MPI communicator");
  return (*mpi->getRawMpiComm())();
}

/// Iterative refinement steps of solveCoarseExactly at most (about 3 at the gate's 1e-3,
/// TotalFetiSettings::singleCoarseGate).
constexpr int kMaxCoarseRefinements = 20;

// Every rank's `mine`, concatenated in rank order (all ranks get the whole list).
inline std::vector<long long> allGather(const Teuchos::Comm<int>& comm, const std::vector<long long>& mine) {
  const MPI_Comm raw = rawComm(comm);
  const int size = comm.getSize(), count = static_cast<int>(mine.size());
  std::vector<int> counts(size), offsets(size + 1, 0);
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, raw);
  for (int p = 0; p < size; ++p) offsets[p + 1] = offsets[p] + counts[p];
  std::vector<long long> all(offsets[size]);
  MPI_Allgatherv(mine.data(), count, MPI_LONG_LONG, all.data(), counts.data(), offsets.data(), MPI_LONG_LONG, raw);
  return all;
}

inline const double* readOnly(const DualVector& v) { return v.getLocalViewHost(Tpetra::Access::ReadOnly).data(); }
inline double* readWrite(DualVector& v) { return v.getLocalViewHost(Tpetra::Access::ReadWrite).data(); }

/// Rows per task of the row loops (G^T a, the sums of applyBlockwise): fixed, so that the
/// work split does not depend on the number of threads.
constexpr LO kRowChunk = 8192;
}  // namespace detail
using namespace detail;

}  // namespace tribos::feti
